#pragma once
// The `kerf` program as a module (libkerf_program.so, core/module_loader.h):
// the command line and everything it runs, loaded by the launcher `kerf`
// (cli/launcher.cpp) once the thread policy's variables are set, so that
// libgomp, which the program links, reads them when it loads.
#include "core/module_loader.h"

namespace kerf {

struct ProgramModule {
  ModuleStamp stamp;
  int (*main)(int argc, char** argv);
};

}  // namespace kerf
