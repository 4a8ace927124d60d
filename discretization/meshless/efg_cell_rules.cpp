#include "discretization/meshless/efg_cell_rules.h"

#include "discretization/fem/symmetric_simplex_quadrature.h"

namespace kerf {

QuadratureRule efg_cell_rule(const MeshlessOptions& options, int dim) {
  if (options.quadrature_rule == CellRule::symmetric) return symmetric_simplex_rule(dim, options.quadrature_degree);
  return collapsed_gauss(dim, options.quadrature_order);
}

QuadratureRule efg_facet_rule(const MeshlessOptions& options, int dim) {
  if (options.quadrature_rule == CellRule::gauss) return collapsed_gauss(dim - 1, options.quadrature_order);
  // n Gauss-Legendre points are exact to degree 2n - 1.
  if (dim == 2) return gauss_legendre_unit(options.quadrature_degree / 2 + 1);
  return symmetric_simplex_rule(2, options.quadrature_degree);
}

}  // namespace kerf
