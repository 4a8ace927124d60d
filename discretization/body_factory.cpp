#include "discretization/body_factory.h"

#include "core/check.h"
#include "discretization/fem/fem_body.h"
#include "geometry/box_mesher.h"
#include "geometry/msh_reader.h"

namespace kerf {
namespace {

Mesh make_mesh(const Scene& scene) {
  const FemOptions& fem = scene.discretization.fem;
  const int order = fem.element == ElementType::tet10 || fem.element == ElementType::tri6 ? 2 : 1;
  if (!scene.box) {
    Mesh mesh = read_msh(scene.mesh_file, scene.dimension);
    return mesh;
  }
  BoxMeshRequest request;
  request.dimension = scene.dimension;
  request.order = order;
  request.min = scene.box->min;
  request.max = scene.box->max;
  request.size = fem.size;
  for (const RefineRegion& r : scene.discretization.refine) request.refine.push_back({r.box.min, r.box.max, r.size});
  return mesh_box(request);
}

}  // namespace

std::unique_ptr<DiscreteBody> make_body(const Scene& scene, RunReport& report) {
  KERF_CHECK(scene.discretization.method == Method::fem, scene.file, ": key 'discretization.method': value '",
             to_string(scene.discretization.method),
             "' is not implemented yet (the meshless methods are issue 3); expected fem");
  ScopedTimer timer(report.phases, "setup");
  Mesh mesh = make_mesh(scene);
  report.add_stage("mesh");
  return std::make_unique<FemBody>(scene, std::move(mesh));
}

}  // namespace kerf
