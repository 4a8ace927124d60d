// EFG writes its stiffness straight into the matrix node by node
// (PointIntegration::add_stiffness_rows, through MatrixAssembly): it must be
// the matrix its cells' blocks give through a sink, for a law with one tangent
// everywhere (linear: the moments path) and one a point (neo-Hookean), on the
// curved organ read from a graded .msh file, its mesh's nodes, a cut through
// it, in 2D and 3D; its lower half the exact mirror of the upper.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "discretization/body_factory.h"
#include "discretization/meshless/efg_body.h"
#include "solvers/sparse_assembly.h"
#include "support/organ_mesh.h"
#include "support/test_support.h"

namespace kerf {
namespace {

/// The graded organ (3 to 6 mm), its mesh's nodes, held on its base, a
/// blade's strip through it in the plane y = 0.0007 (off the mesh's nodes) and
/// a second piece tilted through the top.
std::string organ_scene() {
  return "domain: {mesh: " + testing::graded_organ_file() + "}\n"
         "material: {young: 5.0e3, poisson: 0.35, density: 1000.0}\n"
         "discretization: {method: efg, meshless: {nodes: mesh}}\n"
         "boundary:\n"
         "  - {select: {plane: {axis: z, at: -0.012}}, fix: [x, y, z]}\n"
         "body_force: {gravity: [0, 0, -9.81]}\n"
         "cuts:\n"
         "  - strip: [[-0.05, 0.0007, 0.02], [-0.05, 0.0007, -0.004], [0.0, 0.0007, 0.02], [0.0, 0.0007, -0.004],\n"
         "            [0.01, 0.004, 0.02], [0.01, 0.004, 0.002]]\n"
         "solve: {analysis: static}\n";
}

/// A 3 x 2 cm plate, nodes 4 mm apart, a cut from its top edge to its middle.
std::string plate_scene() {
  return "dimension: 2\n"
         "domain: {box: {min: [0, 0], max: [0.03, 0.02]}}\n"
         "material: {young: 1.0e4, poisson: 0.3}\n"
         "discretization: {method: efg, meshless: {spacing: 0.004}}\n"
         "boundary:\n"
         "  - {select: {plane: {axis: x, at: 0.0}}, fix: [x, y]}\n"
         "cuts:\n"
         "  - polyline: [[0.0151, 0.03], [0.0151, 0.01]]\n"
         "solve: {analysis: static}\n";
}

/// Strains of about 5% (3D: compressive in places, where the neo-Hookean tangent is indefinite) plus noise.
Vector strained(const DiscreteBody& body) {
  std::srand(11);
  const int dim = body.dofs_per_node();
  Vector u = 1e-5 * Vector::Random(body.dof_count());
  for (Index n = 0; n < body.node_count(); ++n) {
    const Vec3 x = 40.0 * body.node_position(n);
    const Vec3 s(0.002 * std::sin(x.x() + 2 * x.y()), 0.002 * std::cos(3 * x.z() + x.x()), 0.002 * std::sin(x.y()));
    for (int i = 0; i < dim; ++i) u[dim * n + i] += s[i];
  }
  return u;
}

/// The matrices both ways, with Nitsche's terms (added through a sink, the
/// same way, after the material part) or, with `essential: parameters`, without.
void expect_rows_equal_the_sinks_matrix(const std::string& yaml, MaterialModel model, const std::string& essential) {
  const std::string what = to_string(model) + std::string(", essential ") + essential;
  const Scene scene = testing::scene_from_text(
      yaml, {std::string("material.model=") + to_string(model), "discretization.meshless.essential=" + essential});
  RunReport report;
  const std::unique_ptr<DiscreteBody> body = make_body(scene, report);
  const auto& efg = dynamic_cast<const EfgBody&>(*body);
  ASSERT_NE(efg.domain().enrichment(), nullptr) << what << ": the cut must enrich the body";
  const Vector u = strained(*body);
  SparseMatrix by_rows = build_pattern(*body), by_sink = by_rows;
  Vector f_rows, f_sink;
  efg.add_tangent_into(u, csr_view(by_rows), &f_rows);
  efg.tangent(u, add_into(by_sink), &f_sink);
  const double largest = Eigen::Map<const Vector>(by_sink.valuePtr(), by_sink.nonZeros()).cwiseAbs().maxCoeff();
  ASSERT_GT(largest, 0.0) << what;
  double worst = 0.0;
  for (Index k = 0; k < by_rows.nonZeros(); ++k)
    worst = std::max(worst, std::abs(by_rows.valuePtr()[k] - by_sink.valuePtr()[k]));
  EXPECT_LT(worst, 1e-12 * largest) << what;
  EXPECT_EQ((f_rows - f_sink).norm(), 0.0) << what;
  // The material part's lower node blocks are copies of the upper ones; a
  // node's own block is symmetric to round-off (so are Nitsche's blocks).
  if (essential == "nitsche") return;
  const int dim = body->dofs_per_node();
  const SparseMatrix transposed = by_rows.transpose();
  Index copies = 0;
  for (Index r = 0; r < by_rows.rows(); ++r)
    for (SparseMatrix::InnerIterator it(by_rows, r); it; ++it) {
      const double mirror = transposed.coeff(r, it.col());
      if (r / dim != it.col() / dim) {
        ASSERT_EQ(it.value(), mirror) << what << " (" << r << ", " << it.col() << ")";
        ++copies;
      } else {
        EXPECT_LE(std::abs(it.value() - mirror), 1e-14 * largest) << what << " (" << r << ", " << it.col() << ")";
      }
    }
  EXPECT_GT(copies, by_rows.nonZeros() / 2) << what;
}

TEST(EfgStiffnessRows, EqualTheCellBlocksOnTheCutGradedOrgan) {
  for (MaterialModel model : {MaterialModel::linear, MaterialModel::neohookean})
    for (const char* essential : {"nitsche", "parameters"})
      expect_rows_equal_the_sinks_matrix(organ_scene(), model, essential);
}

TEST(EfgStiffnessRows, EqualTheCellBlocksOnACutPlate) {
  for (MaterialModel model : {MaterialModel::linear, MaterialModel::stvk})
    for (const char* essential : {"nitsche", "parameters"})
      expect_rows_equal_the_sinks_matrix(plate_scene(), model, essential);
}

// A pattern without a pair a point couples is an internal error that names
// the point and the nodes, not a write past the row.
TEST(EfgStiffnessRows, RefuseAPatternMissingAPair) {
  const Scene scene = testing::scene_from_text(plate_scene(), {});
  RunReport report;
  const std::unique_ptr<DiscreteBody> body = make_body(scene, report);
  // The couplings of every point but those holding both the first point's first and last nodes.
  const auto& efg = dynamic_cast<const EfgBody&>(*body);
  const ShapeTable& t = efg.points().shapes();
  const Index a = t.neighbours.of(0).front(), b = t.neighbours.of(0).back();
  auto holds = [&](Index p, Index node) {
    auto near = t.neighbours.of(p);
    return std::find(near.begin(), near.end(), node) != near.end();
  };
  SparseMatrix pattern = build_pattern(body->dofs_per_node(), body->dof_count(), [&](const CouplingVisitor& visit) {
    std::vector<Index> dofs;
    for (Index p = 0; p < t.point_count(); ++p) {
      if (holds(p, a) && holds(p, b)) continue;
      neighbour_dofs(t, p, dofs);
      visit(dofs);
    }
  });
  const std::string message = testing::error_message(
      [&] { efg.add_tangent_into(Vector::Zero(body->dof_count()), csr_view(pattern), nullptr); });
  testing::expect_mentions(message, {"internal: point ", " couples nodes ", "which the matrix's pattern leaves out"});
}

}  // namespace
}  // namespace kerf
