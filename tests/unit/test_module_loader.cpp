// kerf's modules (core/module_loader.h): one that cannot be found, or that
// another build left, is refused with a message naming it and what needed it
// (and not kept); one that loads is recorded with its cost, once.
#include <gtest/gtest.h>

#include "core/module_loader.h"
#include "output/vtk_module.h"

namespace kerf {
namespace {

bool says(const Error& e, const std::string& words) { return std::string(e.what()).find(words) != std::string::npos; }

struct AnyTable {
  ModuleStamp stamp;
};

TEST(ModuleLoader, RefusesAModuleItCannotFindNamingItAndWhatNeededIt) {
  try {
    load_module<AnyTable>("absent", "for this test");
    FAIL() << "a module that is not there loaded";
  } catch (const Error& e) {
    EXPECT_TRUE(says(e, "could not load its absent module libkerf_absent.so, needed for this test")) << e.what();
  }
}

TEST(ModuleLoader, RefusesAModuleWhoseTableIsNotTheOneThisKerfCalls) {
  struct WiderTable {
    ModuleStamp stamp;
    void (*functions[8])();
  };
  try {
    load_module<WiderTable>("vtk", "for this test");
    FAIL() << "a module of another table was taken";
  } catch (const Error& e) {
    EXPECT_TRUE(says(e, "module libkerf_vtk.so was built from another kerf")) << e.what();
  }
}

TEST(ModuleLoader, RecordsAModuleOnceWhenItLoadsWithTheLibrariesItBrought) {
  const auto count = [](const std::string& name) {
    int n = 0;
    for (const LoadedModule& m : loaded_modules()) n += m.name == name;
    return n;
  };
  vtk_module();
  vtk_module();
  EXPECT_EQ(count("vtk"), 1);
  for (const LoadedModule& m : loaded_modules())
    if (m.name == "vtk") {
      EXPECT_GE(m.libraries, 1);  // itself, at least (the test program links VTK already)
      EXPECT_GT(m.load_ms, 0.0);
    }
}

}  // namespace
}  // namespace kerf
