// The FEM body on real gmsh meshes: patch test, rigid-body modes in the null
// space, tangent by finite differences for every material, mass and load totals.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <limits>

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include "core/check.h"
#include "support/test_support.h"

namespace kerf {
namespace {

struct ElementCase {
  ElementType element;
  int dim, order;
  FemVolumetric volumetric = FemVolumetric::element;
};

// The linear cells twice: with their bulk term in the cell and averaged at the nodes.
const ElementCase all_elements[] = {{ElementType::tet4, 3, 1},
                                    {ElementType::tet10, 3, 2},
                                    {ElementType::tri3, 2, 1},
                                    {ElementType::tri6, 2, 2},
                                    {ElementType::tet4, 3, 1, FemVolumetric::averaged_nodal},
                                    {ElementType::tri3, 2, 1, FemVolumetric::averaged_nodal}};

Scene plain_scene(int dim, MaterialModel model = MaterialModel::linear,
                  FemVolumetric volumetric = FemVolumetric::element) {
  Scene s = testing::scene_from_text(dim == 3 ? "domain: {box: {min: [0,0,0], max: [1,1,1]}}\n"
                                              : "dimension: 2\ndomain: {box: {min: [0,0], max: [1,1]}}\n");
  s.material.model = model;
  s.discretization.fem.volumetric = volumetric;
  return s;
}

class FemElementTest : public ::testing::TestWithParam<ElementCase> {
 protected:
  FemBody make_body(MaterialModel model = MaterialModel::linear, double size = 0.5) const {
    const ElementCase& e = GetParam();
    return FemBody(plain_scene(e.dim, model, e.volumetric), testing::unit_box_mesh(e.dim, e.order, size));
  }
};

// A linear displacement field u = A x + b imposed on every boundary node is
// reproduced at the interior nodes by the solve.
TEST_P(FemElementTest, PatchTestReproducesLinearField) {
  FemBody body = make_body(MaterialModel::linear, 0.34);
  const int dim = GetParam().dim;
  const Mesh& mesh = body.mesh();
  Mat3 A;
  A << 1e-3, 2e-3, -1e-3, 0.5e-3, -2e-3, 1.5e-3, 0.7e-3, 0.3e-3, 1e-3;
  Vec3 b(1e-4, -2e-4, 3e-4);
  Vector exact(body.dof_count());
  for (Index n = 0; n < mesh.node_count(); ++n)
    for (int i = 0; i < dim; ++i) exact[dim * n + i] = (A * mesh.nodes[n] + b)[i];
  BoundaryFacets facets = boundary_facets(mesh);
  std::vector<char> on_boundary = boundary_node_flags(mesh, facets);
  std::vector<DirichletDof> fixed;
  for (Index n = 0; n < mesh.node_count(); ++n)
    if (on_boundary[n])
      for (int i = 0; i < dim; ++i) fixed.push_back({dim * n + i, exact[dim * n + i]});
  ASSERT_LT(static_cast<Index>(fixed.size()), body.dof_count()) << "the mesh has no interior node";
  SparseMatrix K = testing::assemble_stiffness(body, Vector::Zero(body.dof_count()));
  FreeDofs free(body.dof_count(), fixed);
  free.prepare_matrix(K);
  free.restrict_values(K);
  Vector boundary_part = Vector::Zero(body.dof_count());
  for (const DirichletDof& d : fixed) boundary_part[d.dof] = d.value;
  Vector rhs = -free.restrict_vector(K * boundary_part);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(Eigen::SparseMatrix<double>(free.restricted()));
  Vector interior = solver.solve(rhs);
  Vector expected = free.restrict_vector(exact);
  EXPECT_LT((interior - expected).norm() / expected.norm(), 1e-10);
}

TEST_P(FemElementTest, RigidBodyModesAreInTheNullSpace) {
  FemBody body = make_body();
  const int dim = GetParam().dim;
  const Mesh& mesh = body.mesh();
  SparseMatrix K = testing::assemble_stiffness(body, Vector::Zero(body.dof_count()));
  double scale = 0.0;
  for (Index k = 0; k < K.nonZeros(); ++k) scale = std::max(scale, std::abs(K.valuePtr()[k]));
  std::vector<Vector> modes;
  for (int i = 0; i < dim; ++i) {
    Vector t = Vector::Zero(body.dof_count());
    for (Index n = 0; n < mesh.node_count(); ++n) t[dim * n + i] = 1.0;
    modes.push_back(t);
  }
  for (int axis = (dim == 3 ? 0 : 2); axis < 3; ++axis) {
    Vector r = Vector::Zero(body.dof_count());
    Vec3 w = Vec3::Unit(axis);
    for (Index n = 0; n < mesh.node_count(); ++n) {
      Vec3 v = w.cross(mesh.nodes[n]);
      for (int i = 0; i < dim; ++i) r[dim * n + i] = v[i];
    }
    modes.push_back(r);
  }
  for (const Vector& m : modes) EXPECT_LT((K * m).norm() / (scale * m.norm()), 1e-12);
}

TEST_P(FemElementTest, TangentMatchesFiniteDifferencesForEveryMaterial) {
  for (MaterialModel model :
       {MaterialModel::linear, MaterialModel::corotational, MaterialModel::stvk, MaterialModel::neohookean,
        MaterialModel::neohookean_uncoupled}) {
    FemBody body = make_body(model, 0.5);
    // A smooth field (strains up to about 0.3) plus small noise: large enough to
    // exercise the nonlinearity, too smooth to invert an element.
    std::srand(11);
    const int dim = GetParam().dim;
    Vector u = 0.002 * Vector::Random(body.dof_count());
    for (Index n = 0; n < body.node_count(); ++n) {
      const Vec3& x = body.mesh().nodes[n];
      Vec3 smooth(0.1 * std::sin(x.x() + 2 * x.y()), 0.1 * std::cos(3 * x.z() + x.x()), 0.1 * std::sin(x.y() * x.z()));
      for (int i = 0; i < dim; ++i) u[dim * n + i] += smooth[i];
    }
    Vector du = Vector::Random(body.dof_count());
    SparseMatrix K = testing::assemble_stiffness(body, u);
    Vector fp, fm, f;
    const double h = 1e-6;
    body.internal_force(u + h * du, fp);
    body.internal_force(u - h * du, fm);
    Vector numeric = (fp - fm) / (2 * h);
    Vector analytic = K * du;
    EXPECT_LT((analytic - numeric).norm(), 1e-6 * analytic.norm()) << to_string(model);
    // The force returned with the tangent is the internal force.
    SparseMatrix K2 = build_pattern(body);
    body.tangent(u, add_into(K2), &f);
    Vector f_alone;
    body.internal_force(u, f_alone);
    EXPECT_LT((f - f_alone).norm(), 1e-12 * f_alone.norm()) << to_string(model);
    // The force is the gradient of the strain energy.
    double numeric_power = (body.strain_energy(u + h * du) - body.strain_energy(u - h * du)) / (2 * h);
    EXPECT_NEAR(f_alone.dot(du), numeric_power, 1e-6 * std::abs(numeric_power)) << to_string(model);
  }
}

// A curved tet10 whose mid-edge node lies past its edge's end has a negative
// det J inside: the body refuses it naming the first such cell (by the mean
// of its corners: the body's cell numbers follow its own order) and the
// point, the same on one thread as on two (the cells run in parallel).
TEST(FemBody, ACellInvertedInsideIsRefusedNamingTheFirstOne) {
  Mesh mesh = testing::unit_box_mesh(3, 2, 0.5);
  const Index c = mesh.cell_count() / 2;
  const auto nodes = mesh.cell(c);
  const Vec3 from = mesh.nodes[nodes[0]], to = mesh.nodes[nodes[1]];
  const Index moved = nodes[4];  // the middle of edge (0, 1), now three edge lengths along it
  mesh.nodes[moved] = from + 3.0 * (to - from);
  auto refusal = [&](int threads) {
    omp_set_num_threads(threads);
    try {
      FemBody body(plain_scene(3), mesh);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string two = refusal(2), one = refusal(1);
  omp_set_num_threads(2);
  EXPECT_NE(two.find(") is inverted or degenerate (det J = -"), std::string::npos) << two;
  EXPECT_NE(two.find("at quadrature point"), std::string::npos) << two;
  EXPECT_EQ(two, one);
  // The centre named is that of a cell holding the moved node.
  Vec3 named;
  ASSERT_EQ(std::sscanf(two.c_str() + two.find("centred at ") + 11, "%lf, %lf, %lf", &named.x(), &named.y(),
                        &named.z()), 3) << two;
  double nearest = std::numeric_limits<double>::infinity();
  for (Index k = 0; k < mesh.cell_count(); ++k) {
    const auto cell = mesh.cell(k);
    if (std::find(cell.begin(), cell.end(), moved) == cell.end()) continue;
    Vec3 centre = Vec3::Zero();
    for (int a = 0; a < 4; ++a) centre += mesh.nodes[cell[a]] / 4.0;
    nearest = std::min(nearest, (centre - named).norm());
  }
  EXPECT_LT(nearest, 1e-5) << two;
}

TEST_P(FemElementTest, DirectAssemblyWritesWhatTheSinkWrites) {
  FemBody body = make_body(MaterialModel::corotational, 0.4);
  std::srand(5);
  const Vector u = 0.05 * Vector::Random(body.dof_count());
  SparseMatrix through_sink = build_pattern(body), direct = build_pattern(body);
  Vector f_sink, f_direct;
  body.tangent(u, add_into(through_sink), &f_sink);
  body.add_tangent_into(u, csr_view(direct), &f_direct);
  // The same values added in the same order: equal to the last bit.
  EXPECT_EQ((through_sink - direct).norm(), 0.0);
  EXPECT_GT(direct.norm(), 0.0);
  EXPECT_EQ((f_sink - f_direct).norm(), 0.0);
  // A second matrix of another pattern (more columns) gets its own places.
  ASSERT_GT(build_pattern(body).nonZeros(), 0);
  SparseMatrix wider = build_pattern(body.dofs_per_node(), body.dof_count(), [&](const CouplingVisitor& visit) {
    body.visit_couplings(visit);
    const int dpn = body.dofs_per_node();
    std::vector<Index> first_and_last;  // two nodes far apart: a coupling no cell has
    for (Index node : {Index{0}, body.node_count() - 1})
      for (int i = 0; i < dpn; ++i) first_and_last.push_back(dpn * node + i);
    visit(first_and_last);
  });
  body.add_tangent_into(u, csr_view(wider), nullptr);
  EXPECT_EQ((Eigen::MatrixXd(wider) - Eigen::MatrixXd(through_sink)).norm(), 0.0);
}

// What three ranks' bodies compute from their own cells adds up to the whole
// body's: forces, stiffness, energy and both masses; each rank's touched rows
// hold its own and every row its part writes; the owned rows tile the dofs.
TEST_P(FemElementTest, ThreeRanksPartsAddUpToTheWhole) {
  const ElementCase& e = GetParam();
  const Scene scene = plain_scene(e.dim, MaterialModel::corotational, e.volumetric);
  const Mesh mesh = testing::unit_box_mesh(e.dim, e.order, 0.4);
  const FemBody whole(scene, mesh);
  std::srand(7);
  const Vector u = 0.05 * Vector::Random(whole.dof_count());
  SparseMatrix K = build_pattern(whole), M = build_pattern(whole);
  Vector f;
  whole.add_tangent_into(u, csr_view(K), &f);
  whole.consistent_mass(add_into(M));
  EXPECT_FALSE(whole.partitioned());
  SparseMatrix K_sum = build_pattern(whole), M_sum = build_pattern(whole);
  Vector f_sum = Vector::Zero(f.size()), lumped_sum = Vector::Zero(f.size());
  double energy_sum = 0.0, smallest_step = std::numeric_limits<double>::infinity();
  Index next_owned = 0;
  for (int rank = 0; rank < 3; ++rank) {
    const FemBody part(scene, mesh, RankShare{rank, 3});
    ASSERT_TRUE(part.partitioned());
    EXPECT_EQ(part.owned_nodes().first, next_owned);
    next_owned = part.owned_nodes().second;
    SparseMatrix K_part = build_pattern(part);
    Vector f_part;
    part.add_tangent_into(u, csr_view(K_part), &f_part);
    std::vector<char> touched(part.node_count(), 0);
    for (Index n : part.touched_nodes()) touched[n] = 1;
    for (Index n = part.owned_nodes().first; n < part.owned_nodes().second; ++n) EXPECT_TRUE(touched[n]);
    for (Index d = 0; d < f_part.size(); ++d)
      if (!touched[d / e.dim]) {
        ASSERT_EQ(f_part[d], 0.0) << "rank " << rank << " writes force to untouched dof " << d;
        ASSERT_EQ(K_part.row(d).norm(), 0.0) << "rank " << rank << " writes untouched row " << d;
      }
    K_sum += K_part;
    f_sum += f_part;
    part.consistent_mass(add_into(M_sum));
    lumped_sum += part.lumped_mass();
    energy_sum += part.strain_energy(u);
    smallest_step = std::min(smallest_step, part.critical_time_step());
  }
  EXPECT_EQ(next_owned, whole.node_count());
  EXPECT_EQ(smallest_step, whole.critical_time_step());
  EXPECT_LT((K_sum - K).norm(), 1e-12 * K.norm());
  EXPECT_LT((f_sum - f).norm(), 1e-12 * f.norm());
  EXPECT_LT((M_sum - M).norm(), 1e-12 * M.norm());
  EXPECT_LT((lumped_sum - whole.lumped_mass()).norm(), 1e-12 * lumped_sum.norm());
  EXPECT_NEAR(energy_sum, whole.strain_energy(u), 1e-12 * std::abs(energy_sum));
}

TEST_P(FemElementTest, MassesAddUpToTheBodyMass) {
  FemBody body = make_body();
  const int dim = GetParam().dim;
  const double mass = 1000.0;  // default density, unit volume
  Vector lumped = body.lumped_mass();
  EXPECT_TRUE((lumped.array() > 0.0).all());
  EXPECT_NEAR(lumped.sum(), dim * mass, 1e-9 * mass);
  SparseMatrix M = build_pattern(body);
  body.consistent_mass(add_into(M));
  EXPECT_NEAR(M.sum(), dim * mass, 1e-9 * mass);
}

TEST_P(FemElementTest, CriticalStepShrinksWithTheMesh) {
  double coarse = make_body(MaterialModel::linear, 0.5).critical_time_step();
  double fine = make_body(MaterialModel::linear, 0.25).critical_time_step();
  // The step is of order h / c, with c the dilatational wave speed.
  const double c = std::sqrt(Lame::from_young_poisson(1e6, 0.3).mu * (2 - 2 * 0.3) / (1 - 2 * 0.3) / 1000.0);
  EXPECT_GT(coarse, fine);
  EXPECT_LT(coarse, 0.5 / c);
  EXPECT_GT(fine, 0.01 * 0.25 / c);
}

INSTANTIATE_TEST_SUITE_P(AllElements, FemElementTest, ::testing::ValuesIn(all_elements),
                         [](const auto& info) {
                           const bool averaged = info.param.volumetric == FemVolumetric::averaged_nodal;
                           return std::string(to_string(info.param.element)) + (averaged ? "_averaged_nodal" : "");
                         });

// A large rigid rotation strains nothing: the nonlinear materials see no force,
// while small-strain linear elasticity reports spurious ones.
TEST(FemObjectivity, RigidRotationIsForceFreeExceptForLinearElasticity) {
  Mat3 R = Eigen::AngleAxisd(0.8, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  for (MaterialModel model :
       {MaterialModel::linear, MaterialModel::corotational, MaterialModel::stvk, MaterialModel::neohookean,
        MaterialModel::neohookean_uncoupled}) {
    FemBody body(plain_scene(3, model), testing::unit_box_mesh(3, 2, 0.5));
    Vector u(body.dof_count());
    for (Index n = 0; n < body.node_count(); ++n) u.segment<3>(3 * n) = (R - Mat3::Identity()) * body.mesh().nodes[n];
    Vector f;
    body.internal_force(u, f);
    // Scale: the force a 1% strain would cause, E * 0.01 * (unit area).
    const double scale = 1e6 * 0.01;
    if (model == MaterialModel::linear)
      EXPECT_GT(f.norm(), scale) << "linear elasticity should not be rotation invariant";
    else
      EXPECT_LT(f.norm(), 1e-8 * scale) << to_string(model);
    // Against the energy of a 1% strain, 0.5 E 0.01^2 (unit volume).
    if (model != MaterialModel::linear) {
      EXPECT_LT(body.strain_energy(u), 1e-12 * 50.0) << to_string(model);
    }
  }
}

TEST(FemLoads, GravityTractionAndPressureIntegrateToTheirTotals) {
  for (int order : {1, 2}) {
    Scene s = testing::scene_from_text(R"(
domain: {box: {min: [0,0,0], max: [1,1,1]}}
boundary:
  - select: {plane: {axis: z, at: 1.0}}
    traction: [10, 0, 0]
  - select: {plane: {axis: x, at: 1.0}}
    pressure: 100
body_force: {gravity: [0, 0, -9.81]}
)");
    FemBody body(s, testing::unit_box_mesh(3, order, 0.5));
    Vector f;
    body.external_force(0.0, f);
    Vec3 total = Vec3::Zero();
    for (Index n = 0; n < body.node_count(); ++n) total += f.segment<3>(3 * n);
    // traction 10 Pa on a unit face (+x), pressure 100 Pa on the x = 1 face (-x), weight 9810 N (-z)
    EXPECT_NEAR(total.x(), 10.0 - 100.0, 1e-9) << "order " << order;
    EXPECT_NEAR(total.y(), 0.0, 1e-9);
    EXPECT_NEAR(total.z(), -9810.0, 1e-8);
  }
}

// Node by node, gravity's load is the consistent mass times g at every node
// (sum_b M_ab g = g integral of rho N_a): the mass assembled through its own
// path, corner and mid-edge nodes alike (tet10's corners pull upwards).
TEST(FemLoads, GravityIsTheConsistentMassTimesGNodeByNode) {
  for (int dim : {2, 3})
    for (int order : {1, 2}) {
      Scene s = testing::scene_from_text(dim == 3 ? "domain: {box: {min: [0,0,0], max: [1,1,1]}}\n"
                                                    "material: {density: 1200.0}\n"
                                                    "body_force: {gravity: [1.5, -2.0, -9.81]}\n"
                                                  : "dimension: 2\n"
                                                    "domain: {box: {min: [0,0], max: [1,1]}}\n"
                                                    "material: {density: 1200.0}\n"
                                                    "body_force: {gravity: [1.5, -9.81]}\n");
      FemBody body(s, testing::unit_box_mesh(dim, order, 0.5));
      const Index n = body.dof_count();
      Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(n, n);
      body.consistent_mass([&](std::span<const Index> dofs, std::span<const double> block) {
        for (std::size_t a = 0; a < dofs.size(); ++a)
          for (std::size_t b = 0; b < dofs.size(); ++b) mass(dofs[a], dofs[b]) += block[a * dofs.size() + b];
      });
      Vector g(n);
      for (Index d = 0; d < n; ++d) g[d] = s.gravity[d % dim];
      Vector f;
      body.external_force(0.0, f);
      const Vector expected = mass * g;
      EXPECT_LT((f - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff())
          << dim << "D order " << order;
    }
}

TEST(FemLoads, ConflictingPrescribedValuesAreRefused) {
  Scene s = testing::scene_from_text(R"(
domain: {box: {min: [0,0,0], max: [1,1,1]}}
boundary:
  - select: {plane: {axis: x, at: 0.0}}
    fix: [x]
  - select: {plane: {axis: x, at: 0.0}}
    displacement: [0.1, null, null]
)");
  const std::string message = testing::error_message([&] { FemBody(s, testing::unit_box_mesh(3, 1, 0.5)); });
  // Where (the second item's line), which component, both values, and the other item.
  testing::expect_mentions(message, {"test.yaml:6:", "boundary.1", "component x", "prescribed 0.1 here and 0",
                                     "test.yaml:4:", "expected one value"});
}

TEST(FemInterpolation, ReproducesNodalValuesOfALinearField) {
  FemBody body(plain_scene(3), testing::unit_box_mesh(3, 2, 0.5));
  Vector u(body.dof_count());
  for (Index n = 0; n < body.node_count(); ++n) u.segment<3>(3 * n) = 2.0 * body.mesh().nodes[n];
  Vec3 x(0.3, 0.6, 0.45);
  auto p = body.interpolation_at(x);
  ASSERT_TRUE(p);
  Vec3 value = Vec3::Zero();
  for (std::size_t k = 0; k < p->nodes.size(); ++k) value += p->weights[k] * u.segment<3>(3 * p->nodes[k]);
  EXPECT_LT((value - 2.0 * x).norm(), 1e-12);
  EXPECT_FALSE(body.interpolation_at(Vec3(2, 2, 2)));
}

}  // namespace
}  // namespace kerf
