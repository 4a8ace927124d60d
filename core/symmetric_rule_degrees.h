#pragma once
// The degrees kerf has a fully symmetric simplex quadrature rule for
// (discretization/fem/symmetric_simplex_quadrature.h): the scene's
// validation and the rules read this one list.
#include <span>

namespace kerf {

inline std::span<const int> symmetric_rule_degrees(int dim) {
  static constexpr int triangle[] = {1, 2, 4, 5}, tetrahedron[] = {1, 2, 5};
  if (dim == 2) return triangle;
  if (dim == 3) return tetrahedron;
  return {};
}

}  // namespace kerf
