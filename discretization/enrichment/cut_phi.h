#pragma once
// The discontinuous function phi of a cut (paper eq. 16 and 26):
//   phi = s / d,  d = sqrt(d+^2 + s^2),
// with s the signed normal distance to the cut piece and d+ the in-frame
// distance from the cut's projection (0 over the cut). phi is +1 on the
// normal's side of the cut, -1 on the other, varies smoothly around the tips
// and is 0 on the cut's extension beyond them. Convention: a point on the cut
// itself (d = 0), tips included, counts as the +1 side.
#include <limits>

#include "core/types.h"
#include "geometry/cut_surface.h"

namespace kerf {

struct PhiValue {
  double value = 1.0;
  Vec3 gradient = Vec3::Zero();  // 1/m
  // d (m): around the front the distance to it, grad phi ~ 1/d; over the cut |s|, where grad phi = 0.
  double front_distance = std::numeric_limits<double>::infinity();
};

/// phi and its analytic gradient from a point's region data.
PhiValue phi_of(const CutRegion& region);

/// The Enrichment Grid's phi (section 6): pieces [first, last) treated as one
/// cut in their common frame (2D: regions along the common line and d1+ from
/// the two ends, eq. 23; 3D: d2+ to the projected strip, eq. 25).
PhiValue grid_phi(const CutSurface& cut, Index first, Index last, const CutFrame& frame, const Vec3& x);

}  // namespace kerf
