#include "discretization/critical_step_bound.h"

#include <cmath>
#include <mutex>

namespace kerf {

double gershgorin_critical_step(const DiscreteBody& body) {
  Vector row = Vector::Zero(body.dof_count());
  std::mutex guard;  // the sink contract allows concurrent calls that share no dof; rows may repeat here
  BlockSink add_magnitudes = [&](std::span<const Index> dofs, std::span<const double> values) {
    std::lock_guard lock(guard);
    const std::size_t n = dofs.size();
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t c = 0; c < n; ++c) row[dofs[r]] += std::abs(values[r * n + c]);
  };
  body.tangent(Vector::Zero(body.dof_count()), add_magnitudes, nullptr);
  const double omega2 = (row.array() / body.lumped_mass().array()).maxCoeff();
  return 2.0 / std::sqrt(omega2);
}

}  // namespace kerf
