#pragma once
// An order of the cells for parallel assembly without write conflicts: phases
// run one after another; the ranges of one phase run in parallel and share no
// node. On a banded (RCM-ordered) mesh the cells are cut into 2 x threads
// contiguous chunks, even chunks in one phase and odd in the next, so each
// thread walks the matrix rows in order; where chunks would touch, greedy
// colouring is the fallback (one phase per colour).
#include <utility>
#include <vector>

#include "geometry/mesh.h"

namespace kerf {

struct CellSchedule {
  std::vector<Index> cells;                                   // the scheduled cells, in schedule order
  std::vector<std::vector<std::pair<Index, Index>>> phases;   // [begin, end) ranges into `cells`
  bool banded = false;                                        // chunks (true) or colours (false)
  int threads = 1;                                            // the threads it was made for
};

/// The cells [begin, end) (all by default: end < 0) scheduled for `threads`.
CellSchedule schedule_cells(const Mesh& mesh, int threads, Index begin = 0, Index end = -1);

/// The same for the threads kerf runs, or for one where a thread's share of a
/// phase would be smaller than items_worth_a_thread (core/threads_worth_waking.h):
/// small or finely coloured meshes then pay no wake-up a phase.
CellSchedule schedule_cells_worth_threads(const Mesh& mesh, Index begin, Index end);

}  // namespace kerf
