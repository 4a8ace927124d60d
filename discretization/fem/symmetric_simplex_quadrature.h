#pragma once
// Fully symmetric quadrature rules with positive weights and all points inside
// the reference triangle or tetrahedron: fewer points than the collapsed
// Gauss rule of the same degree (a tet: 14 points for degree 5 against 27 for
// degree 3). Weights sum to the simplex measure (1/2, 1/6).
#include <vector>

#include "core/symmetric_rule_degrees.h"
#include "discretization/fem/simplex_quadrature.h"

namespace kerf {

/// The rule exact to `degree` (one of symmetric_rule_degrees(dim): 1, 2, 4, 5
/// on triangles; 1, 2, 5 on tetrahedra); throws
/// std::invalid_argument for another degree or dimension.
QuadratureRule symmetric_simplex_rule(int dim, int degree);

}  // namespace kerf
