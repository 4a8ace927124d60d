#pragma once
// One MPI rank's piece of a body's snapshot for a .pvtu: a contiguous range of
// its cells, the points they use and their fields, and a cell field `rank`
// that shows the partition in ParaView.
#include <utility>

#include "discretization/body_snapshot.h"

namespace kerf {

/// The cells [cells.first, cells.second) of `whole` with the points they use
/// (in their order in `whole`), both kinds of fields cut to match, and the
/// cell field "rank" = `rank`.
BodySnapshot snapshot_piece(const BodySnapshot& whole, std::pair<Index, Index> cells, int rank);

}  // namespace kerf
