#include "discretization/prescribed_dofs.h"

#include <map>

#include "core/check.h"

namespace kerf {

std::vector<DirichletDof> prescribed_dofs(const Scene& scene, int dim,
                                          const std::function<std::vector<Index>(const Selection&)>& select,
                                          std::span<const Vec3> positions,
                                          const std::function<bool(const BoundaryCondition&)>& take) {
  std::map<Index, std::pair<double, const BoundaryCondition*>> prescribed;
  for (const BoundaryCondition& bc : scene.boundary) {
    if (!bc.is_dirichlet() || !take(bc)) continue;
    for (Index n : select(bc.select))
      for (int i = 0; i < dim; ++i) {
        if (!bc.fixed[i] && !bc.displacement[i]) continue;
        double value = bc.fixed[i] ? 0.0 : *bc.displacement[i];
        auto [it, inserted] = prescribed.try_emplace(dim * n + i, value, &bc);
        KERF_CHECK(inserted || it->second.first == value, bc.where.describe(), ": component ", "xyz"[i],
                   " of the node at [", positions[n].transpose(), "] is prescribed ", value, " here and ",
                   it->second.first, " by ", it->second.second->where.describe(), "; expected one value");
      }
  }
  std::vector<DirichletDof> out;
  for (const auto& [dof, entry] : prescribed) out.push_back({dof, entry.first});
  return out;
}

}  // namespace kerf
