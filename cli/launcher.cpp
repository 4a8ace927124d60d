// kerf: soft-tissue cutting simulation, FEM against enriched meshless methods.
//
// This launcher links no OpenMP. It sets the thread policy's variables
// (core/thread_policy.h) for the commands that compute, then loads the
// program (libkerf_program.so: cli/program_main.cpp), whose libgomp reads
// them as it loads: the process starts once (a program linking libgomp
// itself sets them and starts again, which doubled a small run's start:
// results/startup.md). `kerf --version` loads nothing.
#include <cstdio>
#include <exception>
#include <string_view>

#include "cli/program_module.h"
#include "core/thread_policy.h"

namespace {

/// The commands that run nothing on threads leave libgomp its defaults.
bool runs_on_threads(int argc, char** argv) {
  if (argc < 2) return false;  // the usage
  const std::string_view command = argv[1];
  return command != "--version" && command != "version" && command != "--help" && command != "help" &&
         command != "check";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (std::string_view(argv[1]) == "--version" || std::string_view(argv[1]) == "version")) {
    std::printf("kerf %s\n", kerf::version);
    return 0;
  }
  if (runs_on_threads(argc, argv)) kerf::set_thread_policy_environment();
  try {
    return kerf::load_module<kerf::ProgramModule>("program", "to run any command but --version").main(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kerf: error: %s\n", e.what());
    return 1;
  }
}
