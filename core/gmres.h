#pragma once
// Restarted GMRES, right-preconditioned, for the systems whose matrix is not
// symmetric (nodal integration with VCI tests its forces with other
// gradients than its strains use): A M^-1 y = b, x = M^-1 y, so the residual
// it minimises is the true one. Header-only, as all of core/. kerf preconditions with a factorization of
// the symmetric part, (A + A^T) / 2, by the scene's linear backend: close to
// A, it converges in a few iterations.
#include <cmath>
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "core/types.h"

namespace kerf {

/// y = op(x).
using LinearOperator = std::function<void(const Vector& x, Vector& y)>;

struct GmresResult {
  bool converged = false;
  int iterations = 0;
  double relative_residual = 0.0;
};

/// Solves A x = b to |b - A x| <= tolerance |b|, x as the initial guess;
/// `restart` Krylov vectors a cycle, at most `max_iterations` products with A.
inline GmresResult gmres(const LinearOperator& A, const LinearOperator& preconditioner, const Vector& b, Vector& x,
                  double tolerance, int restart, int max_iterations) {
  GmresResult result;
  const double b_norm = b.norm();
  if (x.size() != b.size()) x = Vector::Zero(b.size());
  if (b_norm == 0.0) {
    x.setZero();
    result.converged = true;
    return result;
  }
  Vector r(b.size()), w, z;
  std::vector<Vector> basis;  // V: orthonormal Krylov vectors of A M^-1
  Eigen::MatrixXd H;          // Hessenberg matrix, (restart + 1) x restart
  Eigen::VectorXd cs, sn, g;  // Givens rotations and the rotated right-hand side
  while (result.iterations < max_iterations) {
    A(x, r);
    r = b - r;
    double beta = r.norm();
    result.relative_residual = beta / b_norm;
    if (result.relative_residual <= tolerance) {
      result.converged = true;
      return result;
    }
    basis.assign(1, r / beta);
    H = Eigen::MatrixXd::Zero(restart + 1, restart);
    cs = sn = Eigen::VectorXd::Zero(restart);
    g = Eigen::VectorXd::Zero(restart + 1);
    g[0] = beta;
    int k = 0;
    for (; k < restart && result.iterations < max_iterations; ++k) {
      preconditioner(basis[k], z);
      A(z, w);
      ++result.iterations;
      for (int j = 0; j <= k; ++j) {  // modified Gram-Schmidt
        H(j, k) = w.dot(basis[j]);
        w -= H(j, k) * basis[j];
      }
      H(k + 1, k) = w.norm();
      for (int j = 0; j < k; ++j) {  // earlier rotations on the new column
        const double t = cs[j] * H(j, k) + sn[j] * H(j + 1, k);
        H(j + 1, k) = -sn[j] * H(j, k) + cs[j] * H(j + 1, k);
        H(j, k) = t;
      }
      const double rho = std::hypot(H(k, k), H(k + 1, k));
      cs[k] = H(k, k) / rho;
      sn[k] = H(k + 1, k) / rho;
      H(k, k) = rho;
      H(k + 1, k) = 0.0;
      g[k + 1] = -sn[k] * g[k];
      g[k] = cs[k] * g[k];
      result.relative_residual = std::abs(g[k + 1]) / b_norm;
      if (result.relative_residual <= tolerance || H(k, k) == 0.0) {
        ++k;
        break;
      }
      basis.push_back(w / (std::abs(g[k + 1]) > 0.0 ? w.norm() : 1.0));
    }
    // x += M^-1 V y, H y = g (upper triangular k x k)
    const Eigen::VectorXd y = H.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    Vector update = Vector::Zero(b.size());
    for (int j = 0; j < k; ++j) update += y[j] * basis[j];
    preconditioner(update, z);
    x += z;
  }
  A(x, r);
  result.relative_residual = (b - r).norm() / b_norm;
  result.converged = result.relative_residual <= tolerance;
  return result;
}

}  // namespace kerf
