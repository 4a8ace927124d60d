#pragma once
// Moving-least-squares shape functions (the paper's eq. 1-10) with the quartic
// spline weight (eq. 4), a linear or quadratic basis shifted to the evaluation
// point and scaled by the support size (for conditioning), and their first and
// second derivatives:
//   phi_I(x) = p(x)^T A(x)^-1 w_I(x) p(x_I),  A(x) = sum_I w_I(x) p(x_I) p(x_I)^T.
#include <span>
#include <vector>

#include "core/types.h"
#include "problem/scene.h"

namespace kerf {

/// w(r) = 1 - 6 r^2 + 8 r^3 - 3 r^4 for r = |x - x_I| / d <= 1, else 0, and
/// its gradient and Hessian in x (1/m, 1/m^2).
struct WeightValue {
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
  Mat3 hessian = Mat3::Zero();
};
/// Without `with_hessian`, the Hessian is left zero (shape functions without second derivatives).
WeightValue quartic_weight(const Vec3& x, const Vec3& node, double radius, bool with_hessian = true);
/// Its value alone (no derivatives), where only the value is wanted.
double quartic_weight_value(const Vec3& x, const Vec3& node, double radius);

/// Number of basis terms: 1 + dim (linear), plus dim (dim + 1) / 2 (quadratic).
int mls_basis_size(int dim, MlsBasis basis);

/// Shape functions of n nodes at one point: value, gradient (z = 0 in 2D) and,
/// when asked, Hessian.
struct MlsShape {
  std::vector<double> value;    // n
  std::vector<Vec3> gradient;   // n (1/m)
  std::vector<Mat3> hessian;    // n (1/m^2), empty unless asked
  double condition = 0.0;       // of the scaled moment matrix
};

/// MLS shape functions at x of `nodes` with support radii `radii` (those whose
/// supports cover x). Returns false when the moment matrix cannot be inverted
/// (too few or degenerate neighbours); `out.condition` says how bad it is.
bool mls_shape_functions(int dim, MlsBasis basis, const Vec3& x, std::span<const Vec3> nodes,
                         std::span<const double> radii, bool hessians, MlsShape& out);

/// The same with the nodes' weights at x given (a cut's enriched weights
/// w_I g_I); `scale` (m) scales the basis, the largest support radius.
bool mls_shape_functions(int dim, MlsBasis basis, const Vec3& x, std::span<const Vec3> nodes,
                         std::span<const WeightValue> weights, double scale, bool hessians, MlsShape& out);

}  // namespace kerf
