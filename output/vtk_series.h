#pragma once
// ParaView output: one .vtu (XML, appended raw binary) per written step and a
// .pvd collection rewritten after each, so the series on disk is always readable.
#include <string>
#include <vector>

#include "discretization/discrete_body.h"

namespace kerf {

class VtkSeries {
 public:
  /// Files are <directory>/<name>_NNNN.vtu and <directory>/<name>.pvd.
  VtkSeries(std::string directory, std::string name);
  /// Writes the snapshot at `time` (s); returns the .vtu path.
  std::string write(const BodySnapshot& snapshot, double time);

 private:
  std::string directory_, name_, pvd_path_;
  std::vector<std::pair<double, std::string>> entries_;  // time, file name
};

/// Writes one snapshot as a .vtu file (atomically).
void write_vtu(const BodySnapshot& snapshot, const std::string& path);

}  // namespace kerf
