#pragma once
// The integration constraint (Chen et al. 2001): the discrete divergence
// theorem that a meshless quadrature must keep for every node I,
//   r_I = sum_b psi_I(x_b) n_b w_b - sum_L ghat_I(x_L) V_L = 0,
// over the body's closed boundary (the cut's faces included) and its
// integration points L, ghat the gradient the internal force is tested with.
// Where it fails, a linear patch test fails: the error then depends on where
// the nodes sit, not on their spacing. Its linear-order variationally
// consistent correction (VCI, Chen, Hillman, Rueter 2013) keeps it to
// round-off. kerf's form keeps the test functions' sum constant (with a
// constant xi_I per node, as in the paper, the nodal forces did not balance
// the loads: a support reaction 2% off the weight):
//   ghat_I(x_L) = grad psi_I(x_L) + psi_I(x_L) (xi_I - eta_L),
//   eta_L = sum_J psi_J(x_L) xi_J,
// whence sum_I ghat_I(x_L) = 0, and xi solves per component the symmetric
// system (D - C) xi = r, D_II = sum_L V_L psi_I(x_L), C_IJ = sum_L V_L
// psi_I(x_L) psi_J(x_L): a weighted graph Laplacian (constants in its null
// space, r orthogonal to them), solved by conjugate gradients. The trial
// gradients, hence the strains, are untouched: an explicit step pays one
// more load per neighbour.
#include <span>
#include <vector>

#include "discretization/meshless/boundary_quadrature.h"
#include "discretization/meshless/shape_table.h"

namespace kerf {

/// Per node: sum_b psi_I(x_b) n_b w_b over a boundary quadrature whose shape
/// functions are `at_boundary`, added into `terms` (dim entries a node).
void add_boundary_terms(const ShapeTable& at_boundary, const BoundaryQuadrature& quadrature, std::vector<double>& terms);

/// Per node, over integration points with weights V_L: the sum of V_L ghat_I(x_L)
/// (dim a node), of V_L |grad psi_I(x_L)| (the scale a residual is measured
/// against) and of V_L psi_I(x_L). ghat = grad psi + `offsets` (dim per slot
/// of the table) when given, else grad psi.
struct VolumeTerms {
  std::vector<double> gradient_sum, magnitude, value_sum;
};
VolumeTerms volume_terms(const ShapeTable& points, std::span<const double> weights, Index node_count,
                         std::span<const double> offsets = {});

/// The largest and root-mean-square relative residual |r_I| / sum V_L |ghat_I|
/// over the nodes, and the node holding the largest.
struct ConstraintResidual {
  double max = 0.0, rms = 0.0;
  Index worst = -1;
};
ConstraintResidual constraint_residual(std::span<const double> boundary_terms, const VolumeTerms& volume,
                                       int dimension);

/// VCI's offsets ghat - grad psi = psi_I(x_L) (xi_I - eta_L), dim per slot of
/// `points` (1/m), that zero every residual; `plain` the table's own terms.
/// Throws (naming the iterations) when conjugate gradients do not converge.
std::vector<double> consistent_offsets(const ShapeTable& points, std::span<const double> weights,
                                       std::span<const double> boundary_terms, const VolumeTerms& plain);

}  // namespace kerf
