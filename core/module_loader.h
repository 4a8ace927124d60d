#pragma once
// kerf's modules: the parts that need a heavy library (gmsh, PETSc and MPI,
// VTK) are shared objects loaded on their first use, so that a run which
// never meshes, never leaves its rank and writes no ParaView file never pays
// for loading those libraries (about 90 of them each for gmsh and PETSc).
// A module exports one function, `kerf_<name>_module`, that gives its table.
// It is found through the program's RUNPATH: the build's modules/ folder, an
// installed kerf's lib/kerf (the kerf package adds it to a program built
// against it).
#include <dlfcn.h>
#include <link.h>

#include <chrono>
#include <mutex>
#include <string>
#include <vector>

#include "core/check.h"
#include "kerf/version.h"

namespace kerf {

/// What every module table begins with: the kerf it was built from, so that
/// a module left from another build is refused rather than called.
struct ModuleStamp {
  const char* version = kerf::version;
  std::size_t table_size = 0;
};

/// A module this process loaded: how long loading it took and how many
/// shared libraries it brought (itself and those it needs that were not
/// loaded yet). summary.json's timing.modules.
struct LoadedModule {
  std::string name;
  double load_ms = 0.0;
  int libraries = 0;
};

namespace detail {
inline std::mutex& module_registry_mutex() {
  static std::mutex m;
  return m;
}
inline std::vector<LoadedModule>& module_registry() {
  static std::vector<LoadedModule> loaded;
  return loaded;
}
inline int shared_objects_loaded() {
  int count = 0;
  dl_iterate_phdr([](dl_phdr_info*, std::size_t, void* n) { return ++*static_cast<int*>(n), 0; }, &count);
  return count;
}
}  // namespace detail

/// The modules this process has loaded so far, in the order it loaded them.
inline std::vector<LoadedModule> loaded_modules() {
  std::lock_guard lock(detail::module_registry_mutex());
  return detail::module_registry();
}

/// The table libkerf_<name>.so's `kerf_<name>_module` gives, loading the
/// module now (call once per process: the dynamic loader keeps it).
/// `global`: its libraries' symbols are made visible to what they load
/// themselves (MPI's plugins need it).
template <class Table>
const Table& load_module(const std::string& name, const std::string& needed_for, bool global = false) {
  const std::string file = "libkerf_" + name + ".so";
  std::lock_guard lock(detail::module_registry_mutex());
  const int before = detail::shared_objects_loaded();
  const auto start = std::chrono::steady_clock::now();
  void* handle = dlopen(file.c_str(), RTLD_NOW | (global ? RTLD_GLOBAL : RTLD_LOCAL));
  const std::chrono::duration<double, std::milli> took = std::chrono::steady_clock::now() - start;
  KERF_CHECK(handle, "kerf could not load its ", name, " module ", file, ", needed ", needed_for, ": ", dlerror(),
             " (it is looked for beside kerf: the build's modules/ folder or an installed kerf's lib/kerf)");
  const std::string entry = "kerf_" + name + "_module";
  auto table = reinterpret_cast<const Table* (*)()>(dlsym(handle, entry.c_str()));
  std::string wrong;  // read while the module is loaded
  if (!table)
    wrong = "has no " + entry + ": it is not a kerf module";
  else if (std::string(table()->stamp.version) != kerf::version || table()->stamp.table_size != sizeof(Table))
    wrong = detail::concat("was built from another kerf (", table()->stamp.version, ", a table of ",
                           table()->stamp.table_size, " bytes; this is ", kerf::version, ", ", sizeof(Table),
                           "): rebuild or reinstall kerf");
  if (!wrong.empty()) {
    dlclose(handle);  // not called, not kept
    throw Error("kerf's " + name + " module " + file + " " + wrong);
  }
  detail::module_registry().push_back({name, took.count(), detail::shared_objects_loaded() - before});
  return *table();
}

}  // namespace kerf

/// A module's one exported symbol (the rest of it is hidden by its link).
#define KERF_MODULE_ENTRY extern "C" __attribute__((visibility("default")))
