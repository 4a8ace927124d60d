#pragma once
// The cuts as ParaView shows them, for any body: their pieces present at time
// t (lines in 2D, triangles in 3D) in the reference configuration, with the
// opening u(x + delta n) - u(x - delta n) across the cut at each vertex, read
// through the body's own interpolation (FEM: the cells on either face of a
// remeshed cut; meshless: the enriched shape functions), the time each piece
// appeared and the index of its cut.
#include "discretization/cut_timeline.h"
#include "discretization/discrete_body.h"

namespace kerf {

/// Empty (no cells) when no piece is present at t. A vertex outside the body
/// has no opening (zero); one where too few nodes see either side shows NaN.
void cut_snapshot(const CutTimeline& cuts, double t, const DiscreteBody& body, const Vector& u, BodySnapshot& out);

}  // namespace kerf
