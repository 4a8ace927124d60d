#include "output/vtk_series.h"

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/check.h"
#include "output/atomic_file.h"
#include "output/pvtu_file.h"
#include "output/snapshot_piece.h"

namespace kerf {

VtkSeries::VtkSeries(std::string directory, std::string name, RankShare ranks,
                     std::function<void()> wait_for_every_rank)
    : directory_(std::move(directory)),
      name_(std::move(name)),
      pvd_path_(directory_ + "/" + name_ + ".pvd"),
      ranks_(ranks),
      wait_for_every_rank_(std::move(wait_for_every_rank)) {
  KERF_CHECK(!ranks_.distributed() || wait_for_every_rank_, "a series across ranks needs a way to wait for them");
}

std::string VtkSeries::file_name(const std::string& part, std::size_t step, const std::string& ending) const {
  char number[32];
  std::snprintf(number, sizeof number, "_%04zu", step);
  return name_ + part + number + ending;
}

std::string VtkSeries::write_pieces(const BodySnapshot& snapshot, std::size_t step) {
  auto piece_name = [&](int rank) {
    char ending[32];
    std::snprintf(ending, sizeof ending, "_%d.vtu", rank);
    return file_name("", step, ending);
  };
  // The whole body on every rank: each writes its share of the cells.
  const Index cell_count = static_cast<Index>(snapshot.cell_types.size());
  const auto cells =
      snapshot.piece ? std::pair<Index, Index>(0, cell_count) : even_part(cell_count, ranks_.rank, ranks_.count);
  const BodySnapshot piece = snapshot_piece(snapshot, cells, ranks_.rank);
  write_vtu(piece, directory_ + "/" + piece_name(ranks_.rank));
  wait_for_every_rank_();  // the .pvtu names only pieces that are on disk
  const std::string pvtu = file_name("", step, ".pvtu");
  if (ranks_.rank != 0) return pvtu;
  std::vector<std::string> pieces;
  for (int rank = 0; rank < ranks_.count; ++rank) pieces.push_back(piece_name(rank));
  write_pvtu(piece, pieces, directory_ + "/" + pvtu);
  return pvtu;
}

std::string VtkSeries::write(const BodySnapshot& snapshot, double time, const BodySnapshot* cut,
                             const std::vector<LatticeSnapshot>* lattices) {
  const std::size_t step = steps_++;
  Entry entry{time, {}};
  if (ranks_.distributed()) {
    entry.parts.push_back(write_pieces(snapshot, step));
    if (ranks_.rank != 0) return directory_ + "/" + entry.parts[0];
  } else {
    entry.parts.push_back(file_name("", step, ".vtu"));
    write_vtu(snapshot, directory_ + "/" + entry.parts[0]);
  }
  entry.parts.push_back("");
  if (cut && !cut->cell_types.empty()) {
    entry.parts[1] = file_name("_cut", step, ".vtu");
    write_vtu(*cut, directory_ + "/" + entry.parts[1]);
    part_names_.resize(std::max<std::size_t>(part_names_.size(), 2), "");
    part_names_[1] = "cut";
  }
  if (lattices) {
    lattice_files_.resize(std::max(lattice_files_.size(), lattices->size()));
    part_names_.resize(std::max(part_names_.size(), 2 + lattices->size()), "");
    for (std::size_t g = 0; g < lattices->size(); ++g) {
      lattice_files_[g] = file_name("_" + (*lattices)[g].name, step, ".vti");
      write_vti((*lattices)[g], directory_ + "/" + lattice_files_[g]);
      part_names_[2 + g] = (*lattices)[g].name;
    }
  }
  entry.parts.insert(entry.parts.end(), lattice_files_.begin(), lattice_files_.end());
  entries_.push_back(std::move(entry));
  write_collection();
  return directory_ + "/" + entries_.back().parts[0];
}

// ParaView's PVD reader fixes the number of parts it reads from the first
// step: a part that first appears later (a cut that grows in, its grid) would
// never be shown. So once a part has appeared, every step lists it, an empty
// file standing in where it did not exist yet.
void VtkSeries::write_collection() {
  std::ostringstream pvd;
  pvd.precision(17);
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  <Collection>\n";
  const std::size_t parts = part_names_.size();
  for (const Entry& e : entries_)
    for (std::size_t part = 0; part < std::max<std::size_t>(parts, 1); ++part) {
      std::string file = part < e.parts.size() ? e.parts[part] : "";
      if (file.empty()) file = empty_part_file(part);
      if (file.empty()) continue;  // a part no step has had yet
      pvd << "    <DataSet timestep=\"" << e.time << "\" part=\"" << part << "\" file=\"" << file << "\" name=\""
          << (part == 0 ? "body" : part_names_[part]) << "\"/>\n";
    }
  pvd << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(pvd_path_, pvd.str());
}

std::string VtkSeries::empty_part_file(std::size_t part) {
  if (part == 0 || part >= part_names_.size() || part_names_[part].empty()) return "";
  const bool lattice = part >= 2;
  const std::string file = name_ + "_" + part_names_[part] + (lattice ? "_empty.vti" : "_empty.vtu");
  if (!std::filesystem::exists(directory_ + "/" + file)) {
    if (lattice) {
      LatticeSnapshot empty;
      empty.name = part_names_[part];
      empty.count = {0, 0, 0};
      write_vti(empty, directory_ + "/" + file);
    } else {
      write_vtu(BodySnapshot{}, directory_ + "/" + file);
    }
  }
  return file;
}

}  // namespace kerf
