#pragma once
// Quadrature on the reference simplex (dimension 1, 2, 3) exact for polynomials
// of a given degree. Weights sum to the simplex measure (1, 1/2, 1/6).
#include <vector>

#include "core/types.h"

namespace kerf {

struct QuadratureRule {
  std::vector<Vec3> points;     // reference coordinates
  std::vector<double> weights;
};

QuadratureRule simplex_quadrature(int dim, int degree);

/// Collapsed (Duffy) product of Gauss-Legendre rules: n points per direction,
/// n^dim points, exact to degree 2n - dim.
QuadratureRule collapsed_gauss(int dim, int n);

/// Gauss-Legendre rule with n points on [0, 1].
QuadratureRule gauss_legendre_unit(int n);

}  // namespace kerf
