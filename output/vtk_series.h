#pragma once
// ParaView output: one .vtu (XML, appended raw binary) per written step and a
// .pvd collection rewritten after each, so the series on disk is always
// readable. With cuts, the cut surface is its own part (part 1, its own .vtu
// per step) and each Enrichment Grid's phi a further part (.vti, written when
// the grid changed and referred to until it changes again); once a part has
// appeared every step lists it (empty before), as ParaView's reader needs. Under mpirun
// each rank writes its share of the body's cells as a piece and rank 0 joins
// them in a .pvtu per step; the other parts are small and rank 0 writes them.
#include <functional>
#include <string>
#include <vector>

#include "core/rank_share.h"
#include "discretization/discrete_body.h"

namespace kerf {

class VtkSeries {
 public:
  /// Files are <directory>/<name>_NNNN.vtu and <directory>/<name>.pvd (and
  /// <name>_cut_NNNN.vtu, <name>_<lattice name>_NNNN.vti). Across `ranks`,
  /// the body is <name>_NNNN.pvtu of pieces <name>_NNNN_R.vtu (rank R), and
  /// `wait_for_every_rank` holds each rank until every piece is written.
  VtkSeries(std::string directory, std::string name, RankShare ranks = {},
            std::function<void()> wait_for_every_rank = {});
  /// Writes the snapshot at `time` (s), with the cut surface when `cut` holds
  /// cells and the lattices when given (changed since the last write);
  /// returns the body's .vtu (.pvtu) path. Across ranks every rank calls it
  /// with the whole snapshot and writes its piece; rank 0 alone writes the
  /// rest (the other ranks' `cut` and `lattices` are not read).
  std::string write(const BodySnapshot& snapshot, double time, const BodySnapshot* cut = nullptr,
                    const std::vector<LatticeSnapshot>* lattices = nullptr);

 private:
  /// This rank's piece of step `step`; on rank 0 also the .pvtu, once every
  /// piece is written. Returns the .pvtu's file name.
  std::string write_pieces(const BodySnapshot& snapshot, std::size_t step);
  std::string file_name(const std::string& part, std::size_t step, const std::string& ending) const;
  /// Rewrites the .pvd: every step, every part that has appeared so far.
  void write_collection();
  /// The empty file standing in for `part` at a step it did not exist ("" for the body).
  std::string empty_part_file(std::size_t part);

  std::string directory_, name_, pvd_path_;
  RankShare ranks_;
  std::function<void()> wait_for_every_rank_;
  std::size_t steps_ = 0;
  struct Entry {
    double time;
    std::vector<std::string> parts;  // file name of each part (empty: none at that time)
  };
  std::vector<Entry> entries_;
  std::vector<std::string> lattice_files_;  // the last written file of each lattice
  std::vector<std::string> part_names_;     // ParaView's block names: "", "cut", each lattice's ("" not yet)
};

/// Writes one snapshot as a .vtu file (atomically).
void write_vtu(const BodySnapshot& snapshot, const std::string& path);
/// Writes a lattice as a .vti file (image data with its direction matrix; atomically).
void write_vti(const LatticeSnapshot& lattice, const std::string& path);

}  // namespace kerf
