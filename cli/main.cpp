// kerf: soft-tissue cutting simulation, FEM against enriched meshless methods.
#include "cli/command_line.h"
#include "core/denormals.h"
#include "core/thread_policy.h"

int main(int argc, char** argv) {
  kerf::apply_thread_policy(argv);
  kerf::flush_denormals_to_zero();
  return kerf::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
