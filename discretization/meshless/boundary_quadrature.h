#pragma once
// The closed boundary of a meshless body as its integration constraint sees
// it (the discrete divergence theorem: for every node I,
//   sum_L grad psi_I(x_L) V_L = sum_b psi_I(x_b) n_b w_b):
// the domain's boundary facets, and both faces of every cut piece present
// inside the body. Each point carries its outward normal times its weight.
// A cut face's points stand a hair off the cut on the side they belong to,
// where the enriched shape functions take that side's values (psi jumps
// across the cut): the face of the region the cut's normal points into has
// outward normal -n, the other +n.
#include <span>
#include <vector>

#include "geometry/boundary_facets.h"
#include "geometry/cut_in_cells.h"
#include "geometry/mesh.h"

namespace kerf {

struct BoundaryQuadrature {
  std::vector<Vec3> position;         // m
  std::vector<Vec3> weighted_normal;  // outward unit normal times weight (m^2; 2D: m)
  Index size() const { return static_cast<Index>(position.size()); }
  void append(const BoundaryQuadrature& other);
};

/// Collapsed Gauss points on the straight facets `facets` of `mesh`,
/// `per_direction[f]` points a direction on facet f (the loads' rule where
/// loads act, so that a traction patch test balances exactly).
BoundaryQuadrature facet_quadrature(const Mesh& mesh, const BoundaryFacets& facets, std::span<const int> per_direction);

/// Both faces of one cut piece where it lies inside `cells` (the body's
/// linear cells; `candidates`: those that may meet it), `hair` (m) off it.
BoundaryQuadrature cut_face_quadrature(const Mesh& cells, std::span<const Index> candidates, const CutPiece& piece,
                                       double hair);

}  // namespace kerf
