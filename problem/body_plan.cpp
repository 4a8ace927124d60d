#include "problem/body_plan.h"

#include <algorithm>

namespace kerf {
namespace {

bool has_boundary_loads(const Scene& scene) {
  return std::any_of(scene.boundary.begin(), scene.boundary.end(),
                     [](const BoundaryCondition& bc) { return !bc.is_dirichlet(); });
}

void plan_meshless(const Scene& scene, BodyPlan& plan) {
  const DiscretizationOptions& d = scene.discretization;
  const MeshlessOptions& o = d.meshless;
  plan.nodes_on_mesh = o.nodes == NodePlacement::mesh || !scene.box;
  if (plan.nodes_on_mesh) {
    // The element's mesh at FEM's size; the body keeps its corners.
    plan.mesh = {true, element_descriptor(d.fem.element).order, d.fem.size};
    plan.size_key = "discretization.fem.size", plan.size = d.fem.size;
    return;
  }
  const bool needs_cells = plan.method->integration == Integration::background_cells || has_boundary_loads(scene) ||
                           !scene.contact.empty();
  if (needs_cells) plan.mesh = {true, 1, o.spacing};
  plan.size_key = "discretization.meshless.spacing", plan.size = o.spacing;
}

}  // namespace

BodyPlan body_plan(const Scene& scene) {
  const DiscretizationOptions& d = scene.discretization;
  BodyPlan plan;
  plan.method = &method_descriptor(d.method);
  if (plan.method->meshless) {
    plan_meshless(scene, plan);
    return plan;
  }
  plan.mesh = {true, element_descriptor(d.fem.element).order, d.fem.size};
  plan.size_key = "discretization.fem.size", plan.size = d.fem.size;
  return plan;
}

}  // namespace kerf
