// The meshless bodies (nodal integration and EFG) on small lattices: tangents
// and forces against finite differences for every material, the stabilisation
// blind to affine motions, objectivity, masses and loads adding up.
#include <gtest/gtest.h>

#include <algorithm>

#include <Eigen/Geometry>

#include "core/check.h"
#include "discretization/body_factory.h"
#include "discretization/meshless/efg_body.h"
#include "discretization/meshless/nodal_body.h"
#include "discretization/meshless/point_integration.h"
#include "solvers/sparse_assembly.h"
#include "support/test_support.h"

namespace kerf {
namespace {

const MaterialModel all_models[] = {MaterialModel::linear, MaterialModel::corotational, MaterialModel::stvk,
                                    MaterialModel::neohookean, MaterialModel::neohookean_uncoupled};

/// A 3 x 2 x 2 cm block (or 3 x 2 cm plate) at 5 mm spacing, clamped at x = 0,
/// pulled at x = 0.03, under gravity.
std::unique_ptr<DiscreteBody> small_body(const std::string& method, int dim, MaterialModel model,
                                         std::vector<std::string> overrides = {}) {
  std::string yaml = dim == 3 ? "domain: {box: {min: [0,0,0], max: [0.03,0.02,0.02]}}\n"
                                "body_force: {gravity: [0, 0, -9.81]}\n"
                                "boundary:\n"
                                "  - {select: {plane: {axis: x, at: 0.0}}, fix: [x, y, z]}\n"
                                "  - {select: {plane: {axis: x, at: 0.03}}, traction: [100, 50, 0]}\n"
                              : "dimension: 2\ndomain: {box: {min: [0,0], max: [0.03,0.02]}}\n"
                                "body_force: {gravity: [0, -9.81]}\n"
                                "boundary:\n"
                                "  - {select: {plane: {axis: x, at: 0.0}}, fix: [x, y]}\n"
                                "  - {select: {plane: {axis: x, at: 0.03}}, traction: [100, 50]}\n";
  yaml += "material: {young: 1.0e4, poisson: 0.3}\n"
          "discretization: {method: " + method + ", meshless: {spacing: 0.005}}\n"
          "solve: {analysis: static}\n";
  overrides.push_back(std::string("material.model=") + to_string(model));
  Scene scene = testing::scene_from_text(yaml, overrides);
  RunReport report;
  return make_body(scene, report);
}

/// A smooth field with strains up to about 0.2 plus noise.
Vector smooth_field(const DiscreteBody& body) {
  std::srand(5);
  const int dim = body.dofs_per_node();
  Vector u = 1e-5 * Vector::Random(body.dof_count());
  for (Index n = 0; n < body.node_count(); ++n) {
    const Vec3 x = 50.0 * body.node_position(n);
    Vec3 s(0.004 * std::sin(x.x() + 2 * x.y()), 0.004 * std::cos(3 * x.z() + x.x()), 0.004 * std::sin(x.y() * x.z()));
    for (int i = 0; i < dim; ++i) u[dim * n + i] += s[i];
  }
  return u;
}

void expect_consistent_derivatives(const DiscreteBody& body, const std::string& what, bool check_tangent) {
  const Vector u = smooth_field(body);
  std::srand(7);
  const Vector du = Vector::Random(body.dof_count());
  const double h = 1e-7;
  Vector fp, fm, f;
  body.internal_force(u + h * du, fp);
  body.internal_force(u - h * du, fm);
  body.internal_force(u, f);
  // The force is the gradient of the energy (of a Galerkin body: with VCI the
  // forces are tested with other gradients than the strains are made of).
  if (body.symmetric_tangent()) {
    const double power = (body.strain_energy(u + h * du) - body.strain_energy(u - h * du)) / (2 * h);
    EXPECT_NEAR(f.dot(du), power, 1e-6 * std::abs(power)) << what;
  }
  if (!check_tangent) return;
  SparseMatrix K = testing::assemble_stiffness(body, u);
  const Vector numeric = (fp - fm) / (2 * h), analytic = K * du;
  EXPECT_LT((analytic - numeric).norm(), 1e-6 * analytic.norm()) << what;
  // The tangent is symmetric; a Petrov-Galerkin body's Galerkin tangent (its preconditioner) is.
  SparseMatrix G = build_pattern(body);
  body.galerkin_tangent(u, add_into(G));
  if (body.symmetric_tangent()) {
    EXPECT_LT((K - G).norm(), 1e-12 * K.norm()) << what;
  }
  SparseMatrix GT = G.transpose();
  EXPECT_LT((G - GT).norm(), 1e-10 * G.norm()) << what;
}

TEST(NodalBody, ForceAndTangentMatchFiniteDifferencesForEveryMaterial) {
  for (int dim : {2, 3})
    for (MaterialModel model : all_models)
      for (const char* stab : {"true", "false", "nsni"})
        for (const char* gradient : {"direct", "smoothed"})
          for (const char* vci : {"none", "linear"})
            expect_consistent_derivatives(
                *small_body("nodal", dim, model,
                            {std::string("discretization.meshless.stabilization=") + stab,
                             std::string("discretization.meshless.gradient=") + gradient,
                             std::string("discretization.meshless.vci=") + vci}),
                std::string("nodal ") + to_string(model) + " dim " + std::to_string(dim) + " stab " + stab + " " +
                    gradient + " vci " + vci,
                true);
}

TEST(NodalBody, VciTestsWithTheGalerkinTangentOfThePlainBody) {
  // The Galerkin tangent of a VCI body is the tangent of the same body without it.
  for (int dim : {2, 3}) {
    auto corrected = small_body("nodal", dim, MaterialModel::neohookean, {"discretization.meshless.vci=linear"});
    auto plain = small_body("nodal", dim, MaterialModel::neohookean, {"discretization.meshless.vci=none"});
    ASSERT_FALSE(corrected->symmetric_tangent());
    ASSERT_TRUE(plain->symmetric_tangent());
    const Vector u = smooth_field(*plain);
    SparseMatrix G = build_pattern(*corrected);
    corrected->galerkin_tangent(u, add_into(G));
    const SparseMatrix K = testing::assemble_stiffness(*plain, u), K_vci = testing::assemble_stiffness(*corrected, u);
    EXPECT_LT((G - K).norm(), 1e-12 * K.norm()) << dim;
    EXPECT_GT((K_vci - K).norm(), 1e-6 * K.norm()) << dim;  // the correction is there
  }
}

TEST(EfgBody, ForceAndTangentMatchFiniteDifferencesForEveryMaterial) {
  for (int dim : {2, 3})
    for (MaterialModel model : all_models) {
      const std::string what = std::string("efg ") + to_string(model) + " dim " + std::to_string(dim);
      expect_consistent_derivatives(*small_body("efg", dim, model, {"discretization.meshless.essential=penalty"}),
                                    what + " penalty", true);
      // Nitsche's tangent is exact for linear materials; for the others it drops
      // a term proportional to the constraint violation, so only the energy is checked.
      expect_consistent_derivatives(*small_body("efg", dim, model), what + " nitsche",
                                    model == MaterialModel::linear);
    }
}

// VCI's test functions still add up to a constant: the nodal forces of any
// displacement sum to zero, so reactions balance the loads.
TEST(NodalBody, VciForcesSumToZero) {
  for (int dim : {2, 3})
    for (const char* gradient : {"direct", "smoothed"}) {
      auto body = small_body("nodal", dim, MaterialModel::neohookean,
                             {"discretization.meshless.vci=linear", std::string("discretization.meshless.gradient=") + gradient});
      ASSERT_FALSE(body->symmetric_tangent());
      Vector f;
      body->internal_force(smooth_field(*body), f);
      Vec3 sum = Vec3::Zero(), scale = Vec3::Zero();
      for (Index n = 0; n < body->node_count(); ++n)
        for (int i = 0; i < dim; ++i) sum[i] += f[dim * n + i], scale[i] += std::abs(f[dim * n + i]);
      EXPECT_LT(sum.norm(), 1e-12 * scale.norm()) << dim << "D " << gradient;
    }
}

// The 3D force pass is compiled twice (AVX2 + FMA, baseline x86-64) and the
// CPU picks one: both must give the same forces (to round-off: FMA rounds once).
TEST(NodalBody, BaselineAndVectorForcePassesAgree) {
  for (MaterialModel model : {MaterialModel::linear, MaterialModel::corotational})
    for (const char* stab : {"true", "false", "nsni"})
      for (const char* vci : {"none", "linear"}) {
      auto body = small_body("nodal", 3, model, {std::string("discretization.meshless.stabilization=") + stab,
                                                 std::string("discretization.meshless.vci=") + vci});
      const auto& nodal = dynamic_cast<const NodalBody&>(*body);
      Vector u = smooth_field(*body);
      Vector best, baseline;
      nodal.internal_force(u, best);
      nodal.internal_force_baseline(u, baseline);
      ASSERT_GT(best.norm(), 0.0);
      EXPECT_LT((best - baseline).norm(), 1e-12 * best.norm()) << to_string(model) << " stab " << stab << " vci " << vci;
    }
}

// Assembly hands the blocks of one colour's cubes to the sink at the same
// time: no two cubes of a colour may share a node, and every point is there
// once, whether points go one by one (nodal) or a cell's Gauss points together (EFG).
TEST(MeshlessBodies, PointScheduleColoursShareNoNodeAndHoldEveryPoint) {
  for (const char* method : {"nodal", "efg"})
    for (int dim : {2, 3}) {
      // 2 mm spacing: cubes about a centimetre wide, several to a colour.
      auto body = small_body(method, dim, MaterialModel::linear, {"discretization.meshless.spacing=0.002"});
      const auto* efg = dynamic_cast<const EfgBody*>(body.get());
      const ShapeTable& table = efg ? efg->points().shapes() : dynamic_cast<const NodalBody&>(*body).domain().at_nodes();
      const PointSchedule schedule =
          efg ? efg->points().schedule()
              : schedule_points(table, dynamic_cast<const NodalBody&>(*body).domain().nodes().positions);
      EXPECT_EQ(schedule.group_size, efg ? (dim == 3 ? 8 : 4) : 1) << method;
      std::vector<int> seen(table.point_count(), 0);
      std::size_t cubes = 0;
      for (const auto& colour : schedule.colours) {
        std::vector<int> owner(body->node_count(), -1);  // the cube of this colour holding the node
        for (std::size_t c = 0; c < colour.size(); ++c, ++cubes)
          for (Index first : colour[c])
            for (Index p = first; p < std::min(first + schedule.group_size, table.point_count()); ++p) {
              ++seen[p];
              for (Index J : table.neighbours.of(p)) {
                EXPECT_TRUE(owner[J] < 0 || owner[J] == static_cast<int>(c)) << method << dim << " node " << J;
                owner[J] = static_cast<int>(c);
              }
            }
      }
      EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), table.point_count()) << method << dim;
      // More than one cube a colour: the colours run in parallel.
      EXPECT_GT(cubes, schedule.colours.size()) << method << dim;
    }
}

// A cell's Gauss points are summed over the union of their nodes before the
// sink, each writing the upper half, mirrored once a group: the matrix must
// be the one the points give one by one, each block written whole.
TEST(MeshlessBodies, GroupedPointBlocksAssembleThePointsMatrix) {
  for (int dim : {2, 3}) {
    auto body = small_body("efg", dim, MaterialModel::corotational);
    const PointIntegration& points = dynamic_cast<const EfgBody&>(*body).points();
    const MeshlessDomain& domain = dynamic_cast<const EfgBody&>(*body).domain();
    const MaterialLaw law(MaterialModel::corotational, 1.0e4, 0.3);
    const Vector u = smooth_field(*body);
    auto assembled = [&](const PointSchedule& schedule) {
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(body->dof_count(), body->dof_count());
      assemble_material_blocks(points.shapes(), schedule, points.weights(), law, u,
                               [&](std::span<const Index> dofs, std::span<const double> block) {
                                 const std::size_t n = dofs.size();
                                 for (std::size_t i = 0; i < n; ++i)
                                   for (std::size_t j = 0; j < n; ++j) K(dofs[i], dofs[j]) += block[i * n + j];
                               });
      return K;
    };
    const Eigen::MatrixXd one_by_one = assembled(schedule_points(points.shapes(), domain.nodes().positions));
    const Eigen::MatrixXd by_cells = assembled(points.schedule());
    ASSERT_GT(points.schedule().group_size, 1);
    ASSERT_GT(one_by_one.norm(), 0.0);
    EXPECT_LT((by_cells - one_by_one).norm(), 1e-13 * one_by_one.norm()) << dim;
    // Both write the blocks' upper halves and mirror them: against every node
    // pair written point by point, each point's whole block.
    const ShapeTable& table = points.shapes();
    Eigen::MatrixXd whole = Eigen::MatrixXd::Zero(body->dof_count(), body->dof_count());
    for (Index p = 0; p < table.point_count(); ++p) {
      auto near = table.neighbours.of(p);
      const Index n = static_cast<Index>(near.size());
      std::vector<Index> place(n);
      for (Index k = 0; k < n; ++k) place[k] = k;
      std::vector<double> block(static_cast<std::size_t>(dim * n) * (dim * n), 0.0);
      Mat3 P;
      Mat9 dPdF;
      law.stress_and_tangent(deformation_gradient(table, p, u), P, dPdF);
      add_material_block(table, p, dPdF, points.weight(p), place, n, block);
      for (Index a = 0; a < dim * n; ++a)
        for (Index b = 0; b < dim * n; ++b)
          whole(dim * near[a / dim] + a % dim, dim * near[b / dim] + b % dim) += block[a * dim * n + b];
    }
    EXPECT_LT((by_cells - whole).norm(), 1e-13 * whole.norm()) << dim;
    EXPECT_LT((one_by_one - whole).norm(), 1e-13 * whole.norm()) << dim;
  }
}

TEST(NodalBody, StabilizationIgnoresAffineMotionsOfAnySize) {
  for (const char* stab : {"hourglass", "nsni"}) {
    SCOPED_TRACE(stab);
    auto body = small_body("nodal", 3, MaterialModel::corotational,
                           {std::string("discretization.meshless.stabilization=") + stab});
    const auto& nodal = dynamic_cast<const NodalBody&>(*body);
    const Mat3 R = Eigen::AngleAxisd(1.1, Vec3(1, 2, 3).normalized()).toRotationMatrix();
    const Mat3 A = R * (Mat3() << 1.2, 0.1, 0.0, 0.0, 0.9, 0.2, 0.1, 0.0, 1.1).finished() - Mat3::Identity();
    Vector affine(body->dof_count()), rotation(body->dof_count());
    for (Index n = 0; n < body->node_count(); ++n) {
      const Vec3 x = body->node_position(n);
      affine.segment<3>(3 * n) = A * x + Vec3(0.01, -0.02, 0.03);
      rotation.segment<3>(3 * n) = (R - Mat3::Identity()) * x;
    }
    const double scale = nodal.strain_energy(affine);
    EXPECT_LT(nodal.stabilization_energy(affine), 1e-12 * scale);
    EXPECT_GT(nodal.stabilization_energy(smooth_field(*body)), 0.0);
    // A rigid rotation of 63 degrees stresses nothing (corotational material).
    Vector f;
    nodal.internal_force(rotation, f);
    Vector f_stretch;
    nodal.internal_force(affine, f_stretch);
    EXPECT_LT(f.norm(), 1e-10 * f_stretch.norm());
  }
}

TEST(MeshlessBodies, MassesAndLoadsAddUpToTheirTotals) {
  for (const char* method : {"nodal", "efg"})
    for (int dim : {2, 3}) {
      auto body = small_body(method, dim, MaterialModel::linear);
      const double volume = dim == 3 ? 0.03 * 0.02 * 0.02 : 0.03 * 0.02, area = dim == 3 ? 0.02 * 0.02 : 0.02;
      const Vector m = body->lumped_mass();
      EXPECT_NEAR(m.sum() / dim, 1000.0 * volume, 1e-10 * volume) << method << dim;
      // The consistent mass: symmetric, its rows sum to the lumped mass (the phi
      // add up to one), no coupling between directions.
      SparseMatrix M = build_pattern(*body);
      body->consistent_mass(add_into(M));
      const SparseMatrix MT = M.transpose();
      EXPECT_LT((M - MT).norm(), 1e-14 * M.norm()) << method << dim;
      Vector x_only = Vector::Zero(body->dof_count());
      for (Index n = 0; n < body->node_count(); ++n) x_only[dim * n] = 1.0;
      const Vector pushed = M * x_only, expected_push = m.cwiseProduct(x_only);
      EXPECT_LT((pushed - expected_push).norm(), 1e-12 * m.norm()) << method << dim;
      Vector load;
      body->external_force(0.0, load);
      Vec3 total = Vec3::Zero();
      for (Index n = 0; n < body->node_count(); ++n)
        for (int i = 0; i < dim; ++i) total[i] += load[dim * n + i];
      // Gravity (rho g V) plus the traction on the x = 0.03 face (t A).
      const Vec3 expected = dim == 3 ? Vec3(100 * area, 50 * area, -9.81 * 1000 * volume)
                                     : Vec3(100 * area, 50 * area - 9.81 * 1000 * volume, 0);
      EXPECT_LT((total - expected).norm(), 1e-10 * expected.norm()) << method << dim;
    }
}

TEST(MeshlessBodies, InterpolationReproducesLinearFieldsAndRefusesOutsidePoints) {
  auto body = small_body("nodal", 3, MaterialModel::linear);
  Vector u(body->dof_count());
  const Mat3 A = (Mat3() << 1, 2, 3, 4, 5, 6, 7, 8, 10).finished();
  for (Index n = 0; n < body->node_count(); ++n) u.segment<3>(3 * n) = A * body->node_position(n);
  const Vec3 x(0.0123, 0.0071, 0.0189);
  auto p = body->interpolation_at(x);
  ASSERT_TRUE(p.has_value());
  Vec3 value = Vec3::Zero();
  for (std::size_t k = 0; k < p->nodes.size(); ++k) value += p->weights[k] * u.segment<3>(3 * p->nodes[k]);
  EXPECT_LT((value - A * x).norm(), 1e-12 * (A * x).norm());
  EXPECT_FALSE(body->interpolation_at(Vec3(0.05, 0.01, 0.01)).has_value());
}

TEST(MeshlessBodies, ASupportTooSmallIsReportedByPosition) {
  try {
    // Seven nodes (a node and its six lattice neighbours) for a ten-term quadratic basis.
    small_body("nodal", 3, MaterialModel::linear,
               {"discretization.meshless.support=1.2", "discretization.meshless.basis=quadratic"});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("cannot be inverted"), std::string::npos) << message;
    EXPECT_NE(message.find("the node ["), std::string::npos) << message;
    EXPECT_NE(message.find("discretization.meshless.support"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace kerf
