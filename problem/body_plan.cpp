#include "problem/body_plan.h"

#include <algorithm>
#include <string>

namespace kerf {
namespace {

bool has_boundary_loads(const Scene& scene) {
  return std::any_of(scene.boundary.begin(), scene.boundary.end(),
                     [](const BoundaryCondition& bc) { return !bc.is_dirichlet(); });
}

/// Why the body stays whole on every rank under mpirun (empty: its mesh is divided).
std::string whole_on_every_rank(const Scene& scene) {
  const DiscretizationOptions& d = scene.discretization;
  if (d.method == Method::efg)
    return "discretization.method: efg: the node set, the background mesh and the shape functions at the nodes "
           "and boundary points are whole on every rank (not divided yet); each rank holds and computes only its "
           "own cells' Gauss points";
  if (d.method != Method::fem)
    return std::string("discretization.method: ") + method_descriptor(d.method).name +
           ": a meshless node set is not divided among the ranks yet; each rank holds it whole and computes its "
           "share of the points";
  for (std::size_t i = 0; i < scene.cuts.size(); ++i) {
    const Cut& cut = scene.cuts[i];
    const std::string key = "cuts." + std::to_string(i);
    if (cut.grows())
      return key + (cut.live ? ".live" : ".times") + ": a growing FEM cut meshes the body anew at each growth, so every rank builds and "
                   "assembles the whole body; only the linear solve is shared";
    if (cut.fem == FemCut::split)
      return key + ".fem: split: cells split by a cut are not divided among the ranks yet; each rank holds the "
                   "whole mesh and assembles its share of the cells";
  }
  if (d.fem.volumetric == FemVolumetric::averaged_nodal)
    return "discretization.fem.volumetric: averaged_nodal: its nodal averages are not divided among the ranks "
           "yet; each rank holds the whole mesh and assembles its share of the cells";
  if (!scene.contact.empty())
    return "contact: its boundary samples are not divided among the ranks yet; each rank holds the whole mesh and "
           "assembles its share of the cells";
  return "";
}

}  // namespace

BodyPlan body_plan(const Scene& scene) {
  const DiscretizationOptions& d = scene.discretization;
  BodyPlan plan;
  plan.method = &method_descriptor(d.method);
  plan.nodes_on_mesh = plan.method->meshless && (d.meshless.nodes == NodePlacement::mesh || !scene.box);
  if (!plan.method->meshless || plan.nodes_on_mesh) {
    // The element's mesh at FEM's size: FEM's cells, or the meshless nodes at its corners.
    plan.mesh = {true, element_descriptor(d.fem.element).order, d.fem.size,
                 scene.box && d.fem.box_mesher == FemBoxMesher::lattice};
    plan.size_key = "discretization.fem.size", plan.size = d.fem.size;
    plan.whole_on_every_rank = whole_on_every_rank(scene);
    return plan;
  }
  // A lattice of nodes; linear background cells where EFG integrates, loads act or spheres touch.
  const bool needs_cells = plan.method->integration == Integration::background_cells || has_boundary_loads(scene) ||
                           !scene.contact.empty();
  if (needs_cells)
    plan.mesh = {true, 1, d.meshless.spacing, background_cells_of(scene) == BackgroundCells::lattice};
  plan.size_key = "discretization.meshless.spacing", plan.size = d.meshless.spacing;
  plan.whole_on_every_rank = whole_on_every_rank(scene);
  return plan;
}

}  // namespace kerf
