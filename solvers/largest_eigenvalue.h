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
  Vector ritz_vector;        // over the free dofs, unit in the mass-scaled form: a start for the next estimate
};

struct LanczosOptions {
  int max_iterations = 80;
  double tolerance = 1e-6;       // stop when the Ritz value's residual is below this times the value
  const Vector* start = nullptr;  // over the free dofs (a previous ritz_vector); random when null
  /// The random start's entry at a dof; std::rand's when empty. A value
  /// fixed by the dof itself (its position) keeps the estimate independent
  /// of the dofs' numbering, which a mesh divided among ranks changes.
  std::function<double(Index dof)> start_entry;
};

/// y = K x for x over all dofs (a partitioned body's parts added across ranks).
using StiffnessTimes = std::function<void(const Vector& x, Vector& y)>;

EigenvalueBound largest_eigenvalue(const StiffnessTimes& stiffness_times, const Vector& lumped_mass,
                                   const FreeDofs& free, const LanczosOptions& options = {});

}  // namespace kerf
