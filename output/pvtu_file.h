#pragma once
// The .pvtu that joins the pieces MPI ranks wrote of one step: the fields'
// names and sizes, and the piece files. VTK's own parallel writer needs VTK's
// MPI controller to gather that; every piece has the same fields, so the rank
// that writes it knows them from its own piece.
#include <string>
#include <vector>

#include "discretization/body_snapshot.h"

namespace kerf {

/// Writes `path` (atomically) naming `pieces` (file names relative to it),
/// with the point and cell fields of `layout` (any one of the pieces).
void write_pvtu(const BodySnapshot& layout, const std::vector<std::string>& pieces, const std::string& path);

}  // namespace kerf
