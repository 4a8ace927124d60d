#pragma once
// ParaView output: one .vtu (XML, appended raw binary) per written step and a
// .pvd collection rewritten after each, so the series on disk is always
// readable. With cuts, the cut surface is its own part (part 1, its own .vtu
// per step) and each Enrichment Grid's phi a further part (.vti, written when
// the grid changed and referred to until it changes again).
#include <string>
#include <vector>

#include "discretization/discrete_body.h"

namespace kerf {

class VtkSeries {
 public:
  /// Files are <directory>/<name>_NNNN.vtu and <directory>/<name>.pvd (and
  /// <name>_cut_NNNN.vtu, <name>_<lattice name>_NNNN.vti).
  VtkSeries(std::string directory, std::string name);
  /// Writes the snapshot at `time` (s), with the cut surface when `cut` holds
  /// cells and the lattices when given (changed since the last write);
  /// returns the body's .vtu path.
  std::string write(const BodySnapshot& snapshot, double time, const BodySnapshot* cut = nullptr,
                    const std::vector<LatticeSnapshot>* lattices = nullptr);

 private:
  std::string directory_, name_, pvd_path_;
  struct Entry {
    double time;
    std::vector<std::string> parts;  // file name of each part (empty: none at that time)
  };
  std::vector<Entry> entries_;
  std::vector<std::string> lattice_files_;  // the last written file of each lattice
};

/// Writes one snapshot as a .vtu file (atomically).
void write_vtu(const BodySnapshot& snapshot, const std::string& path);
/// Writes a lattice as a .vti file (image data with its direction matrix; atomically).
void write_vti(const LatticeSnapshot& lattice, const std::string& path);

}  // namespace kerf
