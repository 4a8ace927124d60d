#pragma once
// The largest eigenvalue of M^-1 K on the free dofs (M diagonal), by Lanczos
// with full reorthogonalisation: omega_max^2 for the critical explicit step.
#include <functional>

#include "solvers/sparse_assembly.h"

namespace kerf {

struct EigenvalueBound {
  double ritz_value = 0.0;   // largest Ritz value (a lower bound on the eigenvalue)
  double upper_bound = 0.0;  // Ritz value plus its residual norm
  int iterations = 0;
};

/// y = K x for x over all dofs (a partitioned body's parts added across ranks).
using StiffnessTimes = std::function<void(const Vector& x, Vector& y)>;

EigenvalueBound largest_eigenvalue(const StiffnessTimes& stiffness_times, const Vector& lumped_mass,
                                   const FreeDofs& free, int max_iterations = 80);

}  // namespace kerf
