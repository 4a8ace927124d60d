#include "geometry/cell_schedule.h"

#include <omp.h>

#include <numeric>

#include "core/threads_worth_waking.h"
#include "geometry/cell_coloring.h"

namespace kerf {
namespace {

/// Whether the ranges of every phase are pairwise node-disjoint.
bool conflict_free(const Mesh& mesh, const CellSchedule& s) {
  std::vector<int> owner(mesh.nodes.size());
  for (const auto& phase : s.phases) {
    std::fill(owner.begin(), owner.end(), -1);
    for (std::size_t r = 0; r < phase.size(); ++r)
      for (Index k = phase[r].first; k < phase[r].second; ++k)
        for (Index n : mesh.cell(s.cells[k])) {
          if (owner[n] >= 0 && owner[n] != static_cast<int>(r)) return false;
          owner[n] = static_cast<int>(r);
        }
  }
  return true;
}

/// Splits [begin, end) into `parts` nearly equal ranges.
std::vector<std::pair<Index, Index>> split(Index begin, Index end, int parts) {
  std::vector<std::pair<Index, Index>> out;
  for (int p = 0; p < parts; ++p)
    out.emplace_back(begin + (end - begin) * p / parts, begin + (end - begin) * (p + 1) / parts);
  return out;
}

}  // namespace

CellSchedule schedule_cells(const Mesh& mesh, int threads, Index begin, Index end) {
  if (end < 0) end = mesh.cell_count();
  CellSchedule s;
  s.cells.resize(end - begin);
  std::iota(s.cells.begin(), s.cells.end(), begin);
  if (threads <= 1) {
    s.phases = {{{0, end - begin}}};
    s.banded = true;
    return s;
  }
  s.threads = threads;
  // Banded: chunk c of 2T holds the range's cells [c n / 2T, (c + 1) n / 2T) in mesh order.
  auto chunks = split(0, end - begin, 2 * threads);
  s.phases.assign(2, {});
  for (std::size_t c = 0; c < chunks.size(); ++c) s.phases[c % 2].push_back(chunks[c]);
  s.banded = true;
  if (conflict_free(mesh, s)) return s;
  // Colours (of the whole mesh, keeping the range's cells), each split among the threads.
  CellColoring coloring = color_cells(mesh);
  s.cells.clear();
  s.phases.clear();
  for (int k = 0; k < coloring.color_count(); ++k) {
    const Index first = static_cast<Index>(s.cells.size());
    for (Index i = coloring.start[k]; i < coloring.start[k + 1]; ++i)
      if (coloring.cells[i] >= begin && coloring.cells[i] < end) s.cells.push_back(coloring.cells[i]);
    s.phases.push_back(split(first, static_cast<Index>(s.cells.size()), threads));
  }
  s.banded = false;
  return s;
}

CellSchedule schedule_cells_worth_threads(const Mesh& mesh, Index begin, Index end) {
  const int threads = omp_get_max_threads();
  if (end < 0) end = mesh.cell_count();
  if (!worth_threads(end - begin)) return schedule_cells(mesh, 1, begin, end);
  CellSchedule s = schedule_cells(mesh, threads, begin, end);
  const Index share = (end - begin) / (static_cast<Index>(s.phases.size()) * threads);
  return share >= items_worth_a_thread ? s : schedule_cells(mesh, 1, begin, end);
}

}  // namespace kerf
