// kerf's command line with this project's laws registered (mooney_rivlin.cpp
// registers at start-up): `kerf_mooney_rivlin run SCENE.yaml`, as `kerf run`.
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "core/denormals.h"
#include "core/thread_policy.h"

int main(int argc, char** argv) {
  kerf::apply_thread_policy(argv);
  kerf::flush_denormals_to_zero();
  return kerf::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}
