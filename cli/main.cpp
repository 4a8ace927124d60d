// kerf: soft-tissue cutting simulation, FEM against enriched meshless methods.
#include <string_view>

#include "cli/command_line.h"
#include "core/denormals.h"
#include "core/thread_policy.h"

namespace {

/// The commands that run nothing on threads start once: the thread policy
/// starts the program a second time (core/thread_policy.h), which would
/// double their time (results/startup.md).
bool runs_on_threads(int argc, char** argv) {
  if (argc < 2) return false;  // the usage
  const std::string_view command = argv[1];
  return command != "--version" && command != "version" && command != "--help" && command != "help" &&
         command != "check";
}

}  // namespace

int main(int argc, char** argv) {
  if (runs_on_threads(argc, argv)) kerf::apply_thread_policy(argv);
  kerf::flush_denormals_to_zero();
  return kerf::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
