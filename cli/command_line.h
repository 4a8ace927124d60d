#pragma once
// The `kerf` command line: run, check, study, --version. Returns the exit code:
// 0 success, 1 a failed run, 2 bad usage or a bad scene.
#include <string>
#include <vector>

namespace kerf {

int run_command_line(const std::vector<std::string>& args);

}  // namespace kerf
