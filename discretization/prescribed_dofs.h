#pragma once
// The scene's fix and displacement conditions as prescribed nodal dofs, the
// same for FEM and the meshless methods: a component prescribed twice with
// different values is refused, naming both conditions.
#include <functional>
#include <span>
#include <vector>

#include "discretization/discrete_body.h"
#include "problem/scene.h"

namespace kerf {

/// dofs-per-node `dim`; `select` gives a selection's nodes, `positions` their
/// places (for messages); only the conditions `take` accepts count.
std::vector<DirichletDof> prescribed_dofs(const Scene& scene, int dim,
                                          const std::function<std::vector<Index>(const Selection&)>& select,
                                          std::span<const Vec3> positions,
                                          const std::function<bool(const BoundaryCondition&)>& take);

}  // namespace kerf
