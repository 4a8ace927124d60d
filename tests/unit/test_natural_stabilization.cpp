// Naturally stabilized nodal integration (natural_stabilization.h): the dual
// cells' second moments against independent integrals, and the free
// spectrum (rigid modes only at zero, where plain nodal integration has
// spurious ones). The linear patch tests it must not spoil, on the curved
// graded mesh and across a cut: test_integration_constraint.cpp.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>

#include "discretization/body_factory.h"
#include "geometry/mesh.h"
#include "solvers/sparse_assembly.h"
#include "support/test_support.h"

namespace kerf {
namespace {

/// int over a polygon (counter-clockwise) of x^2 and y^2: Green's theorem,
/// a formula independent of the simplex one under test.
Vec3 polygon_second_moment(const std::vector<Vec3>& p) {
  Vec3 m = Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3 &a = p[k], &b = p[(k + 1) % p.size()];
    const double cross = a.x() * b.y() - b.x() * a.y();
    m.x() += cross * (a.x() * a.x() + a.x() * b.x() + b.x() * b.x()) / 12.0;
    m.y() += cross * (a.y() * a.y() + a.y() * b.y() + b.y() * b.y()) / 12.0;
  }
  return m;
}

TEST(DualCellSecondMoments, TriangleCornersMatchGreensTheorem) {
  Mesh mesh;
  mesh.dimension = 2;
  mesh.nodes = {Vec3(0.1, 0.2, 0), Vec3(1.3, 0.4, 0), Vec3(0.5, 1.1, 0)};
  mesh.cells = {0, 1, 2};
  const std::vector<Vec3> moments = dual_cell_second_moments(mesh);
  const Vec3 centroid = (mesh.nodes[0] + mesh.nodes[1] + mesh.nodes[2]) / 3.0;
  for (int a = 0; a < 3; ++a) {
    const Vec3 &p = mesh.nodes[a], &next = mesh.nodes[(a + 1) % 3], &previous = mesh.nodes[(a + 2) % 3];
    // The corner's dual part: the corner, the midpoint of its next edge, the
    // centroid, the midpoint of its previous edge; taken about the corner.
    const std::vector<Vec3> quad{Vec3::Zero(), 0.5 * (next - p), centroid - p, 0.5 * (previous - p)};
    const Vec3 expected = polygon_second_moment(quad);
    EXPECT_NEAR(moments[a].x(), expected.x(), 1e-14) << a;
    EXPECT_NEAR(moments[a].y(), expected.y(), 1e-14) << a;
    EXPECT_EQ(moments[a].z(), 0.0);
  }
}

TEST(DualCellSecondMoments, TetrahedronCornersMatchAGridSum) {
  Mesh mesh;
  mesh.nodes = {Vec3(0, 0, 0), Vec3(1.0, 0.1, 0), Vec3(0.2, 0.9, 0.1), Vec3(0.3, 0.2, 1.2)};
  mesh.cells = {0, 1, 2, 3};
  const std::vector<Vec3> moments = dual_cell_second_moments(mesh);
  // Midpoints of a 240^3 grid over the bounding box, each given to the corner
  // of largest barycentric coordinate.
  Mat3 edges;
  for (int k = 0; k < 3; ++k) edges.col(k) = mesh.nodes[k + 1] - mesh.nodes[0];
  const Mat3 to_local = edges.inverse();
  const int n = 240;
  const Vec3 lo(0, 0, 0), hi(1.0, 0.9, 1.2);
  const Vec3 step = (hi - lo) / n;
  std::vector<Vec3> sums(4, Vec3::Zero());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vec3 x = lo + Vec3((i + 0.5) * step.x(), (j + 0.5) * step.y(), (k + 0.5) * step.z());
        const Vec3 l = to_local * (x - mesh.nodes[0]);
        const std::array<double, 4> lambda{1.0 - l.sum(), l.x(), l.y(), l.z()};
        if (*std::min_element(lambda.begin(), lambda.end()) < 0.0) continue;
        const int a = static_cast<int>(std::max_element(lambda.begin(), lambda.end()) - lambda.begin());
        const Vec3 d = x - mesh.nodes[a];
        sums[a] += d.cwiseProduct(d) * step.prod();
      }
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(moments[a][i], sums[a][i], 0.01 * sums[a][i]) << a << " " << i;
}

std::unique_ptr<DiscreteBody> body_of(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  Scene scene = testing::scene_from_text(yaml, overrides);
  RunReport report;
  return make_body(scene, report);
}

/// omega^2 of the free body's K x = omega^2 M x (ascending).
Eigen::VectorXd free_spectrum(const DiscreteBody& body) {
  SparseMatrix K = build_pattern(body), M = build_pattern(body);
  body.tangent(Vector::Zero(body.dof_count()), add_into(K), nullptr);
  body.consistent_mass(add_into(M));
  const Eigen::MatrixXd k = K, m = M;
  return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(k, m, Eigen::EigenvaluesOnly).eigenvalues();
}

// A free 2 x 1 x 1 cm block (nodes 2.5 mm apart). Nodal integration without
// stabilisation has near-zero-energy modes besides the six rigid ones (its
// softest at 0.005 of tet4's softest deformation mode); NSNI holds them with
// no parameter and leaves the rigid modes at zero. It holds them more weakly
// than the hourglass term (c = 0.1) on so coarse a block: its softest mode is
// 0.082 of tet4's (0.11 of tet10's), the hourglass term's 0.73 (measured
// 2026-11-27; docs/meshless_integration.md).
TEST(NaturalStabilization, FreeBlockKeepsOnlyItsRigidModesAtZero) {
  const std::string block =
      "domain: {box: {min: [0, 0, 0], max: [0.02, 0.01, 0.01]}}\n"
      "material: {model: linear, young: 1.0e4, poisson: 0.3, density: 1000}\n"
      "discretization: {method: fem, fem: {size: 0.0025}, meshless: {spacing: 0.0025}}\n"
      "solve: {analysis: static}\n";
  const double softest_tet4 = free_spectrum(*body_of(block))[6];
  auto softest = [&](const std::string& stabilization) {
    const Eigen::VectorXd omega2 = free_spectrum(*body_of(
        block, {"discretization.method=nodal", "discretization.meshless.stabilization=" + stabilization}));
    for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(omega2[i]), 1e-8 * omega2[omega2.size() - 1]) << stabilization;
    return omega2[6] / softest_tet4;
  };
  EXPECT_LT(softest("none"), 0.01);
  EXPECT_GT(softest("nsni"), 0.05);
}

}  // namespace
}  // namespace kerf
