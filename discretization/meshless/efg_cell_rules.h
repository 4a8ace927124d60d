#pragma once
// The quadrature an EFG body's background cells and boundary facets get from
// the scene (discretization.meshless.quadrature): the collapsed Gauss product
// with `order` points a direction, or the symmetric rule exact to `degree`.
#include "discretization/fem/simplex_quadrature.h"
#include "problem/scene.h"

namespace kerf {

/// The rule on each reference cell (triangle or tetrahedron) of dimension `dim`.
QuadratureRule efg_cell_rule(const MeshlessOptions& options, int dim);

/// The rule on each boundary facet of a body of dimension `dim` (weak
/// essential conditions): the cells' rule one dimension down, of the same
/// exactness (a segment: the Gauss-Legendre rule exact to `degree`).
QuadratureRule efg_facet_rule(const MeshlessOptions& options, int dim);

}  // namespace kerf
