// libFuzzer target: mesh files, through read_msh as a scene's domain.mesh is
// read (kerf's own reader in this process for MSH 4.1 and 2.2; gmsh's in a
// child process for the files it leaves, so that gmsh's own crashes on
// malformed files end in a message), then the checks kerf makes on what comes back.
// Every bad file must end in kerf::Error; a mesh that comes back must be
// whole (every cell's nodes exist). Any other exception, a crash or a
// sanitizer report in this process is a finding.
#include <pthread.h>
#include <sanitizer/common_interface_defs.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "core/check.h"
#include "geometry/msh_reader.h"

// read_msh may fork gmsh's reader; the child is a copy of this fuzzer, and its
// death (gmsh crashing or running out of memory, which kerf reports) would
// run libFuzzer's death callback there and be written up as the fuzzer's crash.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pthread_atfork(nullptr, nullptr, [] { __sanitizer_set_death_callback(nullptr); });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/kerf_fuzz_" + std::to_string(::getpid()) + ".msh";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  for (int dimension : {3, 2}) {
    try {
      const kerf::Mesh mesh = kerf::read_msh(path, dimension);
      const auto nodes = static_cast<kerf::Index>(mesh.nodes.size());
      for (kerf::Index n : mesh.cells)
        if (n < 0 || n >= nodes) {
          std::fprintf(stderr, "read_msh returned a cell with node %lld of %lld\n", static_cast<long long>(n),
                       static_cast<long long>(nodes));
          std::abort();
        }
    } catch (const kerf::Error&) {
    } catch (const std::exception& e) {
      std::fprintf(stderr, "not a kerf::Error: %s\n", e.what());
      std::abort();
    }
  }
  return 0;
}
