// fem: split on real gmsh meshes (FemBody with a cut, geometry/cell_split.h):
// each piece's rigid motions give no force (any material), nor do the linear
// fields whose stress leaves the cut free (the patch test); each piece weighs
// its fragments; a tet4 copy keeps its parent's explicit step; a cut event
// carries the state exactly (energies and momentum unchanged).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "discretization/fem/fem_body.h"
#include "support/cut_geometry.h"
#include "support/test_support.h"

namespace kerf {
namespace {

struct SplitCase {
  int dim, order;
};
const SplitCase all_cases[] = {{3, 1}, {3, 2}, {2, 1}, {2, 2}};

Scene plain_scene(int dim, MaterialModel model = MaterialModel::linear) {
  Scene s = testing::scene_from_text(dim == 3 ? "domain: {box: {min: [0,0,0], max: [1,1,1]}}\n"
                                              : "dimension: 2\ndomain: {box: {min: [0,0], max: [1,1]}}\n");
  s.material.model = model;
  return s;
}

/// The cut's normal: x + 0.3 y + 0.2 z = 0.6 (2D: x + 0.3 y = 0.6) through the unit box.
Vec3 cut_normal(int dim) { return dim == 3 ? Vec3(1, 0.3, 0.2) : Vec3(1, 0.3, 0); }

FemBody split_body(const SplitCase& c, MaterialModel model = MaterialModel::linear, double size = 0.34) {
  return FemBody(plain_scene(c.dim, model), testing::unit_box_mesh(c.dim, c.order, size),
                 {}, testing::plane_cut(c.dim, cut_normal(c.dim), 0.6));
}

/// The nodal values of a field per piece: field(piece, x).
Vector piecewise(const FemBody& body, const std::function<Vec3(int, const Vec3&)>& field) {
  const std::vector<int> piece = testing::node_pieces(body.mesh());
  const int dim = body.dofs_per_node();
  Vector u = Vector::Zero(body.dof_count());
  for (Index n = 0; n < body.node_count(); ++n) {
    const Vec3 v = field(piece[n], body.node_position(n));
    for (int i = 0; i < dim; ++i) u[dim * n + i] = v[i];
  }
  return u;
}

class SplitBodyTest : public ::testing::TestWithParam<SplitCase> {};

// Each piece turned by pi/3 about its own axis and moved: no force on any
// node, originals, copies and phantoms alike. Linear elasticity is invariant
// only under infinitesimal rotations: it takes those.
TEST_P(SplitBodyTest, EachPieceMovesRigidlyWithoutForce) {
  const SplitCase c = GetParam();
  for (MaterialModel model : {MaterialModel::linear, MaterialModel::corotational, MaterialModel::neohookean}) {
    const FemBody body = split_body(c, model);
    const std::vector<int> piece = testing::node_pieces(body.mesh());
    ASSERT_EQ(*std::max_element(piece.begin(), piece.end()), 1);
    const Vec3 axes[2] = {c.dim == 3 ? Vec3(1, 2, 3).normalized() : Vec3::UnitZ(), Vec3::UnitZ()};
    const Vector u = piecewise(body, [&](int p, const Vec3& x) {
      const double angle = p == 0 ? M_PI / 3 : -M_PI / 4;
      const Vec3 shift = p == 0 ? Vec3(0.3, -0.2, 0.1) : Vec3(-0.5, 0.4, 0.2);
      const Vec3 turned = model == MaterialModel::linear ? Vec3(1e-3 * angle * axes[p].cross(x))
                                                         : Vec3(Eigen::AngleAxisd(angle, axes[p]) * x - x);
      Vec3 v = turned + shift;
      if (c.dim == 2) v.z() = 0;
      return v;
    });
    Vector f, reference;
    body.internal_force(u, f);
    body.internal_force(piecewise(body, [](int, const Vec3& x) { return Vec3(0.01 * x.x(), 0, 0); }), reference);
    EXPECT_LT(f.norm(), 1e-10 * reference.norm()) << "model " << to_string(model);
  }
}

// Per piece, a uniaxial stress along a direction in the cut's plane: the cut
// stays free of traction, so the exact field gives no force on any node off
// the box's faces (the cut's copies and phantoms included).
TEST_P(SplitBodyTest, LinearFieldsThatLeaveTheCutFreeGiveNoForceOffTheOuterFaces) {
  const SplitCase c = GetParam();
  // The cut exactly as given: snapping moves it onto nearby nodes, and there
  // its plane tilts, so that the field no longer leaves it free.
  Scene scene = plain_scene(c.dim);
  scene.discretization.fem.split_snap = 0.0;
  const FemBody body(scene, testing::unit_box_mesh(c.dim, c.order, 0.34), {},
                     testing::plane_cut(c.dim, cut_normal(c.dim), 0.6));
  const double nu = scene.material.poisson;
  const Vec3 n = cut_normal(c.dim).normalized();
  const Vec3 along[2] = {n.cross(Vec3::UnitZ()).normalized(), c.dim == 3 ? Vec3(n.cross(Vec3::UnitX()).normalized())
                                                                         : Vec3(n.cross(Vec3::UnitZ()).normalized())};
  const Vector u = piecewise(body, [&](int p, const Vec3& x) {
    // Uniaxial stress S t (x) t, s = S / E; in 2D plane strain (eps_zz = 0, sigma_zz = nu S).
    const Vec3& t = along[p];
    const double s = p == 0 ? 1e-3 : -2e-3;
    const double lateral = c.dim == 3 ? nu : nu * (1 + nu), stretch = c.dim == 3 ? 1 + nu : 1 + nu;
    Mat3 eps = s * stretch * t * t.transpose() - s * lateral * Mat3::Identity();
    if (c.dim == 2) eps.row(2).setZero(), eps.col(2).setZero();
    return Vec3(eps * x + Vec3(0.1 * p, 0.02, 0));
  });
  Vector f;
  body.internal_force(u, f);
  double largest = 0.0, off_faces = 0.0;
  for (Index k = 0; k < body.node_count(); ++k) {
    const Vec3 x = body.node_position(k);
    const bool on_face = (x.head(c.dim).array() < 1e-9).any() || (x.head(c.dim).array() > 1 - 1e-9).any();
    for (int i = 0; i < c.dim; ++i) {
      largest = std::max(largest, std::abs(f[c.dim * k + i]));
      if (!on_face) off_faces = std::max(off_faces, std::abs(f[c.dim * k + i]));
    }
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(off_faces, 1e-10 * largest);
}

// Each piece's mass is rho times its cells' and fragments' measure; the
// copies' lumped masses add up to it, as does the weight of each piece.
TEST_P(SplitBodyTest, EachPieceWeighsItsFragments) {
  const SplitCase c = GetParam();
  Scene scene = plain_scene(c.dim);
  scene.gravity = Vec3(0, -9.81, 0);
  const FemBody body(scene, testing::unit_box_mesh(c.dim, c.order, 0.34), {},
                     testing::plane_cut(c.dim, cut_normal(c.dim), 0.6));
  const CellSplit& split = *body.split();
  const std::vector<int> piece = testing::node_pieces(body.mesh());
  const double rho = scene.material.density, reference = c.dim == 3 ? 1.0 / 6.0 : 0.5;
  std::array<double, 2> measure{};
  for (Index k = 0; k < body.mesh().cell_count(); ++k) {
    const double whole = cell_measure(body.mesh(), k);
    double share = 1.0;
    if (!split.whole(k)) {
      share = 0.0;
      const auto fragment = split.fragment(k);
      for (std::size_t s = 0; s < fragment.size(); s += c.dim + 1) {
        std::array<Vec3, 4> v{};
        std::copy(fragment.begin() + s, fragment.begin() + s + c.dim + 1, v.begin());
        const Vec3* p = v.data();
        const double m = c.dim == 3 ? (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0
                                    : 0.5 * ((p[1] - p[0]).x() * (p[2] - p[0]).y() - (p[1] - p[0]).y() * (p[2] - p[0]).x());
        share += m / reference;
      }
    }
    measure[piece[body.mesh().cell(k)[0]]] += share * whole;
  }
  EXPECT_NEAR(measure[0] + measure[1] + split.dropped_measure, 1.0, 1e-12);
  const Vector lumped = body.lumped_mass();
  Vector load;
  body.external_force(0.0, load);
  std::array<double, 2> mass{}, weight{};
  for (Index k = 0; k < body.node_count(); ++k) {
    mass[piece[k]] += lumped[c.dim * k];
    weight[piece[k]] += load[c.dim * k + 1];
  }
  for (int p = 0; p < 2; ++p) {
    EXPECT_NEAR(mass[p], rho * measure[p], 1e-12 * rho) << "piece " << p;
    EXPECT_NEAR(weight[p], -9.81 * rho * measure[p], 1e-10 * rho) << "piece " << p;
  }
}

INSTANTIATE_TEST_SUITE_P(Elements, SplitBodyTest, ::testing::ValuesIn(all_cases),
                         [](const auto& info) { return std::string(info.param.dim == 3 ? "tet" : "tri") +
                                                       std::to_string(info.param.order == 1 ? info.param.dim + 1
                                                                                            : (info.param.dim == 3 ? 10 : 6)); });

// A tet4 copy lumps its parent's mass times its share, so its frequency is
// its parent's: the explicit step is the uncut body's, however small the fragments.
TEST(SplitBody, Tet4CopiesKeepTheUncutExplicitStep) {
  const Scene scene = plain_scene(3);
  const Mesh mesh = testing::unit_box_mesh(3, 1, 0.2);
  const FemBody uncut(scene, mesh);
  const FemBody cut(scene, mesh, {}, testing::plane_cut(3, cut_normal(3), 0.6));
  ASSERT_GT(cut.split()->separated_cells, 10);
  EXPECT_NEAR(cut.critical_time_step(), uncut.critical_time_step(), 1e-10 * uncut.critical_time_step());
}

/// The body cut over the triangle of the plane above z = y (its front, the
/// diagonal y = z, runs through the box), then through.
std::array<std::unique_ptr<DiscreteBody>, 2> half_then_whole(const Scene& scene, const Mesh& mesh) {
  const Vec3 n = cut_normal(3);
  std::vector<CutPiece> first;
  for (const CutPiece& p : testing::plane_cut(3, n, 0.62, 0.0))
    if (p.centre.z() > p.centre.y()) first.push_back(p);
  auto before = std::make_unique<FemBody>(scene, mesh, RankShare{}, first);
  auto after = before->split_along(scene, testing::plane_cut(3, n, 0.62));
  return {std::move(before), std::move(after)};
}

// A cut event: the copies take their originals' values, so the strain energy
// (tet4 neo-Hookean: constant F per fragment; tet10 linear: degree-2 energy),
// the kinetic energy and the momentum with the lumped mass are unchanged.
TEST(SplitBody, ACutEventCarriesTheStateExactly) {
  for (int order : {1, 2}) {
    const Scene scene = plain_scene(3, order == 1 ? MaterialModel::neohookean : MaterialModel::linear);
    const auto [before, after] = half_then_whole(scene, testing::unit_box_mesh(3, order, 0.2));
    ASSERT_GT(after->node_count(), before->node_count());
    // A dropped fragment takes its mass and energy along (reported): none here.
    ASSERT_EQ(dynamic_cast<const FemBody&>(*after).split()->dropped_measure, 0.0);
    Vector u(before->dof_count());
    for (Index k = 0; k < before->node_count(); ++k) {
      const Vec3 x = before->node_position(k);
      u.segment<3>(3 * k) = 0.05 * Vec3(std::sin(2 * x.x()) * x.y(), x.z() * x.z() - x.x(), x.x() * x.y() * x.z());
    }
    // The first cut's copies move on their own: the state jumps across it.
    const auto& first = dynamic_cast<const FemBody&>(*before);
    for (Index k = 0; k < before->node_count(); ++k)
      if (first.split()->origin[k] != k) u.segment<3>(3 * k) += Vec3(0.01, -0.02, 0.005);
    const auto& splitting = dynamic_cast<const CutsBySplitting&>(*before);
    const Vector carried = splitting.carried_to(*after, u);
    EXPECT_NEAR(after->strain_energy(carried), before->strain_energy(u), 1e-12 * before->strain_energy(u))
        << "order " << order;
    const Vector m0 = before->lumped_mass(), m1 = after->lumped_mass();
    EXPECT_NEAR(carried.dot(m1.cwiseProduct(carried)), u.dot(m0.cwiseProduct(u)), 1e-12 * u.dot(m0.cwiseProduct(u)));
    for (int i = 0; i < 3; ++i) {
      double p0 = 0, p1 = 0;
      for (Index k = 0; k < before->node_count(); ++k) p0 += m0[3 * k + i] * u[3 * k + i];
      for (Index k = 0; k < after->node_count(); ++k) p1 += m1[3 * k + i] * carried[3 * k + i];
      EXPECT_NEAR(p1, p0, 1e-12 * std::abs(p0) + 1e-15);
    }
  }
}

// fem.split_front: subdivide, the front moving on: the cells of the new front
// are subdivided and their new nodes take the parent's field where they lie,
// so the strain energy is unchanged (tet4 neo-Hookean, tet10 linear) and, a
// tet4 child lumping a quarter of its volume at each corner of a linear
// field, so is the momentum. (A lumped mass's kinetic energy is not: the
// children lump the parent's mass at other points.)
TEST(SplitBody, ASubdividedFrontMovingOnCarriesTheStateExactly) {
  for (int order : {1, 2}) {
    Scene scene = plain_scene(3, order == 1 ? MaterialModel::neohookean : MaterialModel::linear);
    scene.discretization.fem.split_front = SplitFront::subdivide;
    scene.discretization.fem.split_snap = 0.0;  // nothing dropped: every fragment kept
    const Vec3 n = cut_normal(3);
    const FemBody before(scene, testing::unit_box_mesh(3, order, 0.2), {}, testing::plane_cut_above(3, n, 0.62, 0.55));
    const auto after = before.split_along(scene, testing::plane_cut_above(3, n, 0.62, 0.3));
    const auto& next = dynamic_cast<const FemBody&>(*after);
    ASSERT_GT(before.front()->subdivided_cells, 0);
    ASSERT_GT(next.front()->subdivided_cells, 0);
    EXPECT_EQ(next.front()->unresolved_segments, 0);
    ASSERT_EQ(next.split()->dropped_measure, 0.0);
    ASSERT_EQ(before.split()->dropped_measure, 0.0);
    Vector u(before.dof_count());
    for (Index k = 0; k < before.node_count(); ++k) {
      const Vec3 x = before.node_position(k);
      u.segment<3>(3 * k) = 0.05 * Vec3(std::sin(2 * x.x()) * x.y(), x.z() * x.z() - x.x(), x.x() * x.y() * x.z());
      if (before.split()->origin[k] != k) u.segment<3>(3 * k) += Vec3(0.01, -0.02, 0.005);
    }
    const Vector carried = before.carried_to(next, u);
    EXPECT_NEAR(next.strain_energy(carried), before.strain_energy(u), 1e-12 * before.strain_energy(u))
        << "order " << order;
    if (order == 2) continue;
    const Vector m0 = before.lumped_mass(), m1 = next.lumped_mass();
    for (int i = 0; i < 3; ++i) {
      double p0 = 0, p1 = 0;
      for (Index k = 0; k < before.node_count(); ++k) p0 += m0[3 * k + i] * u[3 * k + i];
      for (Index k = 0; k < next.node_count(); ++k) p1 += m1[3 * k + i] * carried[3 * k + i];
      EXPECT_NEAR(p1, p0, 1e-12 * std::abs(p0) + 1e-15);
    }
  }
}

}  // namespace
}  // namespace kerf
