#pragma once
// The `fem: remove` baseline: the cells a cut crosses are deleted, which opens
// a gap one cell wide along it, and the nodes no cell uses any more go.
#include <span>

#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf {

/// Does the piece cross the interior of the straight-sided cell c? A piece
/// that only touches the cell (a corner or an edge on its line or plane) does not.
bool piece_crosses_cell(const Mesh& mesh, Index c, const CutPiece& piece);

/// Deletes the cells some piece crosses and the nodes left in no cell (the
/// others keep their order). Returns how many cells went.
Index remove_crossed_cells(Mesh& mesh, std::span<const CutPiece> pieces);

}  // namespace kerf
