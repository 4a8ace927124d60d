// The `kerf` program's one exported symbol: its table (cli/program_module.h).
#include <string>
#include <vector>

#include "cli/command_line.h"
#include "cli/program_module.h"
#include "core/denormals.h"

namespace {

int program_main(int argc, char** argv) {
  kerf::flush_denormals_to_zero();
  return kerf::run_command_line(std::vector<std::string>(argv + 1, argv + argc));
}

}  // namespace

KERF_MODULE_ENTRY const kerf::ProgramModule* kerf_program_module() {
  static const kerf::ProgramModule table{{kerf::version, sizeof(kerf::ProgramModule)}, program_main};
  return &table;
}
