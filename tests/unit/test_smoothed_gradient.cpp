// Smoothed nodal gradients (SCNI): every node's cell is closed and its
// boundary encloses exactly the nodal volume (lattices, graded lattices, mesh
// vertices; 2D and 3D), and the smoothed gradient of an affine field is exact
// at every node, also where a straight or kinked cut runs through the cells.
#include <gtest/gtest.h>

#include <functional>

#include "discretization/body_factory.h"
#include "discretization/meshless/nodal_body.h"
#include "discretization/meshless/smoothed_gradient.h"
#include "support/test_support.h"

namespace kerf {
namespace {

/// Sum of the weighted normals (must vanish: the cell is closed) and
/// (1/dim) sum x . n dA, the enclosed measure (divergence theorem).
void expect_closed_cells_of_nodal_volume(const NodeSet& nodes, const std::string& what) {
  const SupportIndex index(nodes.positions, nodes.support);
  const SmoothedGradients smoothing(nodes, index);
  double largest_gap = 0.0, largest_volume_error = 0.0, total = 0.0;
  for (Index I = 0; I < nodes.size(); ++I) {
    Vec3 closure = Vec3::Zero();
    double enclosed = 0.0;
    for (const CellSample& s : smoothing.samples_of(I)) {
      closure += s.weighted_normal;
      enclosed += (s.position - nodes.positions[I]).dot(s.weighted_normal) / nodes.dimension;
    }
    const double scale = std::pow(nodes.volume[I], (nodes.dimension - 1.0) / nodes.dimension);
    largest_gap = std::max(largest_gap, closure.norm() / scale);
    largest_volume_error = std::max(largest_volume_error, std::abs(enclosed - nodes.volume[I]) / nodes.volume[I]);
    total += enclosed;
  }
  EXPECT_LT(largest_gap, 1e-12) << what;
  EXPECT_LT(largest_volume_error, 1e-12) << what;
  double volume = 0.0;
  for (double v : nodes.volume) volume += v;
  EXPECT_NEAR(total, volume, 1e-12 * volume) << what;
}

TEST(SmoothedGradients, CellsAreClosedAndEncloseTheNodalVolumes) {
  expect_closed_cells_of_nodal_volume(lattice_nodes(2, Box{Vec3(0, 0, 0), Vec3(0.1, 0.05, 0)}, 0.01, {}, 2.2),
                                      "2D lattice");
  expect_closed_cells_of_nodal_volume(lattice_nodes(3, Box{Vec3(0, 0, 0), Vec3(0.03, 0.02, 0.02)}, 0.005, {}, 2.2),
                                      "3D lattice");
  const RefineRegion fine{Box{Vec3(0.01, 0.01, 0), Vec3(0.03, 0.03, 0)}, 0.0025};
  expect_closed_cells_of_nodal_volume(
      lattice_nodes(2, Box{Vec3(0, 0, 0), Vec3(0.05, 0.04, 0)}, 0.005, std::span(&fine, 1), 2.2), "graded lattice");
  expect_closed_cells_of_nodal_volume(mesh_nodes(testing::unit_box_mesh(3, 1, 0.25), 2.2), "tet mesh vertices");
}

/// The largest |F - I - A| over the nodes of a nodal body for u = `field`(x).
double gradient_error(const std::string& yaml, const std::vector<std::string>& overrides, const Mat3& A,
                      const std::function<Vec3(const Vec3&)>& field) {
  Scene scene = testing::scene_from_text(yaml, overrides);
  RunReport report;
  auto body = make_body(scene, report);
  const ShapeTable& table = dynamic_cast<const NodalBody&>(*body).domain().at_nodes();
  const int dim = scene.dimension;
  Vector u(body->dof_count());
  for (Index n = 0; n < body->node_count(); ++n) {
    const Vec3 v = field(body->node_position(n));
    for (int i = 0; i < dim; ++i) u[dim * n + i] = v[i];
  }
  double error = 0.0;
  for (Index I = 0; I < table.point_count(); ++I)
    error = std::max(error, (deformation_gradient(table, I, u) - Mat3::Identity() - A).norm());
  return error;
}

/// The largest relative error of the smoothed gradient of u = A x + b over the nodes of a nodal body.
double affine_gradient_error(const std::string& yaml, const std::vector<std::string>& overrides) {
  const int dim = testing::scene_from_text(yaml, overrides).dimension;
  Mat3 A;
  A << 0.3, -0.2, 0.1, 0.05, 0.4, -0.3, 0.2, 0.1, -0.1;
  if (dim == 2) A.row(2).setZero(), A.col(2).setZero();
  return gradient_error(yaml, overrides, A, [&](const Vec3& x) { return Vec3(A * x + Vec3(0.01, -0.02, 0.03)); }) /
         A.norm();
}

// Across a cut the faces are sampled 1e-10 spacings off it: a linear field's
// gradient is then exact to about 2e-10 (not round-off).
TEST(SmoothedGradients, GradientOfAnAffineFieldIsExactAlsoAcrossCuts) {
  const std::string plate =
      "dimension: 2\n"
      "domain: {box: {min: [-0.02, -0.02], max: [0.02, 0.02]}}\n"
      "material: {young: 1.0e4, poisson: 0.3}\n"
      "discretization: {method: nodal, meshless: {spacing: 0.002, gradient: smoothed}}\n"
      "solve: {analysis: static}\n";
  EXPECT_LT(affine_gradient_error(plate, {}), 1e-12);
  EXPECT_LT(affine_gradient_error(plate + "cuts: [{polyline: [[-0.0203, 0.0003], [0.0071, 0.0003]]}]\n", {}), 1e-9);
  EXPECT_LT(
      affine_gradient_error(plate + "cuts: [{polyline: [[-0.011, -0.0031], [-0.002, 0.0043], [0.009, -0.001]]}]\n", {}),
      1e-9);
  EXPECT_LT(affine_gradient_error(plate + "cuts: [{polyline: [[-0.011, -0.0031], [0.009, 0.004]]}]\n",
                                  {"cuts.0.enrichment=multiplicative"}),
            1e-9);
  const std::string block =
      "domain: {box: {min: [0, 0, 0], max: [0.02, 0.02, 0.01]}}\n"
      "material: {young: 1.0e4, poisson: 0.3}\n"
      "discretization: {method: nodal, meshless: {spacing: 0.0025, gradient: smoothed}}\n"
      "solve: {analysis: static}\n"
      "cuts: [{strip: [[0.0051, -0.001, 0.0107], [0.0053, -0.001, -0.0013],"
      " [0.0121, 0.0131, 0.0109], [0.0119, 0.0131, -0.0011]]}]\n";
  EXPECT_LT(affine_gradient_error(block, {}), 1e-9);
}

// A cut right across the plate splits it in two: enriched MLS reproduces a
// different rigid translation on each side, whose strain is zero. The cut's
// faces inside the cells are what cancels the jump in the cells' boundary
// integrals (without them the cells along the cut would see a strain of
// jump / h).
TEST(SmoothedGradients, ACutAcrossTheBodyLetsTwoRigidPartsMoveWithoutStrain) {
  const std::string plate =
      "dimension: 2\n"
      "domain: {box: {min: [-0.02, -0.02], max: [0.02, 0.02]}}\n"
      "material: {young: 1.0e4, poisson: 0.3}\n"
      "discretization: {method: nodal, meshless: {spacing: 0.002, gradient: smoothed}}\n"
      "solve: {analysis: static}\n"
      "cuts: [{polyline: [[-0.025, 0.0003], [0.025, 0.0013]]}]\n";
  const double jump = 1e-3;
  auto parts = [&](const Vec3& x) {
    return x.y() > 0.0003 + 0.02 * (x.x() + 0.025) ? Vec3(0.4 * jump, jump, 0) : Vec3(-0.2 * jump, 0.3 * jump, 0);
  };
  // The cells are 2 mm wide: a jump the faces did not cancel would show as a strain near 0.5.
  EXPECT_LT(gradient_error(plate, {}, Mat3::Zero(), parts), 1e-9);
}

}  // namespace
}  // namespace kerf
