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
/// The value and gradient alone (the linear kernel's weights, 32 bytes).
struct WeightWithGradient {
  double value = 0.0;
  Vec3 gradient = Vec3::Zero();
};
/// w(r) for r < 1.
inline double quartic(double r) { return 1.0 - 6.0 * r * r + 8.0 * r * r * r - 3.0 * r * r * r * r; }
/// Inline, as quartic_weight_value: every table row and stabilisation pair row calls them for each of its nodes.
inline WeightWithGradient quartic_weight_with_gradient(const Vec3& x, const Vec3& node, double radius) {
  WeightWithGradient w;
  const Vec3 s = x - node;
  const double inverse = 1.0 / radius, r = s.norm() * inverse;  // one division, not two
  if (r >= 1.0) return w;
  const double a = 1.0 - r;
  w.value = quartic(r);
  // dw/dr = -12 r (1 - r)^2, so grad w = -12 (1 - r)^2 s / d^2: smooth at the node.
  w.gradient = (-12.0 * a * a * inverse * inverse) * s;
  return w;
}
/// Without `with_hessian`, the Hessian is left zero (shape functions without second derivatives).
WeightValue quartic_weight(const Vec3& x, const Vec3& node, double radius, bool with_hessian = true);
/// Its value alone (no derivatives), where only the value is wanted.
inline double quartic_weight_value(const Vec3& x, const Vec3& node, double radius) {
  const double r = (x - node).norm() / radius;
  return r >= 1.0 ? 0.0 : quartic(r);
}

/// Number of basis terms: 1 + dim (linear), plus dim (dim + 1) / 2 (quadratic).
int mls_basis_size(int dim, MlsBasis basis);

/// Shape functions of n nodes at one point: value, gradient (z = 0 in 2D) and,
/// when asked, Hessian.
struct MlsShape {
  std::vector<double> value;    // n
  std::vector<Vec3> gradient;   // n (1/m)
  std::vector<Mat3> hessian;    // n (1/m^2), empty unless asked
  double condition = 0.0;       // of the scaled moment matrix
  int spanned_directions = -1;  // -1: the full basis; else mls_spanned_linear's r
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

/// How the nodes that weigh on x spread: the eigenvectors of their weighted
/// covariance whose variance is at least `thinnest` of the largest (axes'
/// first `directions` columns). A cut that leaves a point few nodes on its
/// side (a flap one node layer thick, a node alone in a corner, a shaved cap
/// of a curved body) leaves them thin along some direction: a full basis
/// there is singular, or so ill-conditioned that its gradients (and the
/// explicit step) grow with one over that thinness.
struct NodeSpread {
  static constexpr double thinnest = 1e-2;  // a standard deviation a tenth of the largest
  bool weighted = false;                    // some weight is positive
  int directions = 0;
  Mat3 axes = Mat3::Zero();
};
NodeSpread node_spread(int dim, const Vec3& x, std::span<const Vec3> nodes, std::span<const WeightValue> weights,
                       double scale);

/// The linear basis over the directions `spread` keeps, 0 <= r <= dim: it
/// reproduces constants, and linear fields along those directions; across
/// them the gradient is zero. r = 0 is Shepard's functions (a node alone:
/// psi = 1, its own translation). out.spanned_directions = r. False only
/// when no weight is positive.
bool mls_spanned_linear(int dim, const Vec3& x, std::span<const Vec3> nodes, std::span<const WeightValue> weights,
                        const NodeSpread& spread, double scale, bool hessians, MlsShape& out);

}  // namespace kerf
