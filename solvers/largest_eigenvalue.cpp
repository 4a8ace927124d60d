#include "solvers/largest_eigenvalue.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace kerf {

EigenvalueBound largest_eigenvalue(const StiffnessTimes& stiffness_times, const Vector& lumped_mass,
                                   const FreeDofs& free, const LanczosOptions& options) {
  const Index n = free.free_count();
  const int m = std::min<int>(options.max_iterations, n);
  // Symmetric form A = S K S with S = M^-1/2, restricted to the free dofs.
  Vector scale = Vector::Zero(lumped_mass.size()), y;
  for (Index d : free.free_dofs()) scale[d] = 1.0 / std::sqrt(lumped_mass[d]);
  auto apply = [&](const Vector& q_free) {
    Vector full = Vector::Zero(lumped_mass.size());
    for (Index i = 0; i < n; ++i) full[free.free_dofs()[i]] = scale[free.free_dofs()[i]] * q_free[i];
    stiffness_times(full, y);
    Vector out(n);
    for (Index i = 0; i < n; ++i) out[i] = scale[free.free_dofs()[i]] * y[free.free_dofs()[i]];
    return out;
  };
  Eigen::MatrixXd Q(n, m + 1);
  std::vector<double> alpha, beta;
  if (options.start_entry) {
    for (Index i = 0; i < n; ++i) Q(i, 0) = options.start_entry(free.free_dofs()[i]);
  } else {
    std::srand(1);
    Q.col(0) = Vector::Random(n);
  }
  Q.col(0).normalize();
  // A previous Ritz vector with the random one mixed in: a mode it lacks is still reached.
  if (options.start && options.start->size() == n) {
    // A Ritz vector's sign is rounding's choice: the start takes the one
    // nearer the fixed vector, so that a run on 2 ranks, whose vector came out
    // negated, starts where the serial run does (it differed by 2.5e-4).
    const double sign = options.start->dot(Q.col(0)) < 0.0 ? -1.0 : 1.0;
    Q.col(0) = (sign * *options.start + 0.5 * Q.col(0)).normalized();
  }
  EigenvalueBound result;
  for (int j = 0; j < m; ++j) {
    Vector w = apply(Q.col(j));
    alpha.push_back(Q.col(j).dot(w));
    // Full reorthogonalisation against every Lanczos vector so far (twice is enough).
    for (int pass = 0; pass < 2; ++pass) w -= Q.leftCols(j + 1) * (Q.leftCols(j + 1).transpose() * w);
    double b = w.norm();
    beta.push_back(b);
    result.iterations = j + 1;
    // Ritz pair of the tridiagonal matrix.
    const int k = j + 1;
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(k, k);
    for (int i = 0; i < k; ++i) {
      T(i, i) = alpha[i];
      if (i + 1 < k) T(i, i + 1) = T(i + 1, i) = beta[i];
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(T);
    double theta = eig.eigenvalues()[k - 1];
    double residual = b * std::abs(eig.eigenvectors()(k - 1, k - 1));
    result.ritz_value = theta;
    result.upper_bound = theta + residual;
    const bool done = residual <= options.tolerance * theta || b <= 1e-14 * std::abs(theta) || k == m;
    if (done) {
      result.ritz_vector = (Q.leftCols(k) * eig.eigenvectors().col(k - 1)).normalized();
      break;
    }
    Q.col(j + 1) = w / b;
  }
  return result;
}

}  // namespace kerf
