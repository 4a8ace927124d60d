#include "problem/body_plan.h"

#include <algorithm>

namespace kerf {
namespace {

bool has_boundary_loads(const Scene& scene) {
  return std::any_of(scene.boundary.begin(), scene.boundary.end(),
                     [](const BoundaryCondition& bc) { return !bc.is_dirichlet(); });
}

bool fem_mesh_divides(const Scene& scene) {
  const auto keeps_whole = [](const Cut& cut) {
    const bool grows = std::any_of(cut.times.begin(), cut.times.end(), [](double t) { return t > 0.0; });
    return cut.fem == FemCut::split || grows;
  };
  return scene.discretization.method == Method::fem &&
         std::none_of(scene.cuts.begin(), scene.cuts.end(), keeps_whole) &&
         scene.discretization.fem.volumetric != FemVolumetric::averaged_nodal && scene.contact.empty();
}

}  // namespace

BodyPlan body_plan(const Scene& scene) {
  const DiscretizationOptions& d = scene.discretization;
  BodyPlan plan;
  plan.method = &method_descriptor(d.method);
  plan.nodes_on_mesh = plan.method->meshless && (d.meshless.nodes == NodePlacement::mesh || !scene.box);
  if (!plan.method->meshless || plan.nodes_on_mesh) {
    // The element's mesh at FEM's size: FEM's cells, or the meshless nodes at its corners.
    plan.mesh = {true, element_descriptor(d.fem.element).order, d.fem.size};
    plan.size_key = "discretization.fem.size", plan.size = d.fem.size;
    plan.divided_among_ranks = fem_mesh_divides(scene);
    return plan;
  }
  // A lattice of nodes; linear background cells where EFG integrates, loads act or spheres touch.
  const bool needs_cells = plan.method->integration == Integration::background_cells || has_boundary_loads(scene) ||
                           !scene.contact.empty();
  if (needs_cells) plan.mesh = {true, 1, d.meshless.spacing};
  plan.size_key = "discretization.meshless.spacing", plan.size = d.meshless.spacing;
  return plan;
}

}  // namespace kerf
