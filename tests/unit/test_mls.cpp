// MLS shape functions and neighbour search: the quartic weight's derivatives,
// partition of unity and reproduction of linear (and, with the quadratic
// basis, quadratic) fields to round-off with their derivatives, on uniform
// and irregular node sets in 2D and 3D; derivatives against finite
// differences; a support too small to invert is reported, not patched;
// the fallback a cut's flap or a node it isolates gets (mls_spanned_linear).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "discretization/meshless/mls_shape.h"
#include "geometry/support_index.h"

namespace kerf {
namespace {

struct NodeSet {
  std::vector<Vec3> nodes;
  std::vector<double> radii;
};

/// A lattice of spacing h over [0, 1]^dim, jittered by `jitter` * h, support 2.2 h.
NodeSet lattice(int dim, double h, double jitter, unsigned seed = 3) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-jitter * h, jitter * h);
  NodeSet s;
  int n = static_cast<int>(std::round(1.0 / h));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= (dim == 3 ? n : 0); ++k) {
        Vec3 x(i * h + offset(random), j * h + offset(random), dim == 3 ? k * h + offset(random) : 0.0);
        s.nodes.push_back(x);
        s.radii.push_back(2.2 * h * (1.0 + 0.5 * x.x()));  // graded supports
      }
  return s;
}

/// The shape functions at x of the nodes whose supports cover it.
struct Evaluation {
  std::vector<Index> neighbors;
  MlsShape shape;
  bool ok = false;
};
Evaluation evaluate(int dim, MlsBasis basis, const NodeSet& s, const Vec3& x, bool hessians = true) {
  Evaluation e;
  std::vector<Vec3> near;
  std::vector<double> radii;
  for (std::size_t i = 0; i < s.nodes.size(); ++i)
    if ((x - s.nodes[i]).norm() < s.radii[i]) {
      e.neighbors.push_back(static_cast<Index>(i));
      near.push_back(s.nodes[i]);
      radii.push_back(s.radii[i]);
    }
  e.ok = mls_shape_functions(dim, basis, x, near, radii, hessians, e.shape);
  return e;
}

TEST(QuarticWeight, ValuesAndDerivatives) {
  const Vec3 node(0.1, 0.2, 0.3);
  EXPECT_DOUBLE_EQ(quartic_weight(node, node, 0.5).value, 1.0);
  EXPECT_EQ(quartic_weight(node + Vec3(0.5, 0, 0), node, 0.5).value, 0.0);
  EXPECT_NEAR(quartic_weight(node + Vec3(0.499999, 0, 0), node, 0.5).gradient.norm(), 0.0, 1e-9);  // C1 at the edge
  const double h = 1e-6;
  for (const Vec3& x : {Vec3(0.3, 0.1, 0.4), Vec3(0.15, 0.25, 0.3), Vec3(0.1, 0.2, 0.31)}) {
    WeightValue w = quartic_weight(x, node, 0.5);
    EXPECT_EQ(quartic_weight_value(x, node, 0.5), w.value);  // the value-only form agrees to the bit
    for (int k = 0; k < 3; ++k) {
      Vec3 e = h * Vec3::Unit(k);
      WeightValue p = quartic_weight(x + e, node, 0.5), m = quartic_weight(x - e, node, 0.5);
      EXPECT_NEAR(w.gradient[k], (p.value - m.value) / (2 * h), 1e-7);
      for (int l = 0; l < 3; ++l) EXPECT_NEAR(w.hessian(l, k), (p.gradient[l] - m.gradient[l]) / (2 * h), 1e-6);
    }
  }
}

struct Case {
  int dim;
  MlsBasis basis;
  double jitter;
};

class MlsReproduction : public ::testing::TestWithParam<Case> {};

TEST_P(MlsReproduction, ReproducesItsBasisToRoundOff) {
  const auto [dim, basis, jitter] = GetParam();
  NodeSet s = lattice(dim, dim == 3 ? 0.25 : 0.125, jitter);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> inside(0.1, 0.9);
  for (int trial = 0; trial < 10; ++trial) {
    Vec3 x(inside(random), inside(random), dim == 3 ? inside(random) : 0.0);
    Evaluation e = evaluate(dim, basis, s, x);
    ASSERT_TRUE(e.ok) << "condition " << e.shape.condition;
    double sum = 0.0;
    Vec3 position = Vec3::Zero(), gradient_sum = Vec3::Zero();
    Mat3 jacobian = Mat3::Zero(), hessian_sum = Mat3::Zero();
    Mat3 second_moment = Mat3::Zero();
    std::vector<Mat3> second_of_products(9, Mat3::Zero());  // d2/dxk dxl of sum phi x_a x_b
    for (std::size_t I = 0; I < e.neighbors.size(); ++I) {
      const Vec3& xi = s.nodes[e.neighbors[I]];
      const double phi = e.shape.value[I];
      sum += phi;
      position += phi * xi;
      gradient_sum += e.shape.gradient[I];
      jacobian += xi * e.shape.gradient[I].transpose();
      hessian_sum += e.shape.hessian[I];
      second_moment += phi * xi * xi.transpose();
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) second_of_products[3 * a + b] += xi[a] * xi[b] * e.shape.hessian[I];
    }
    Mat3 identity = Mat3::Zero();
    identity.topLeftCorner(dim, dim).setIdentity();
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_LT((position - x).norm(), 1e-12);
    EXPECT_LT(gradient_sum.norm(), 1e-10);
    EXPECT_LT((jacobian - identity).norm(), 1e-10);
    EXPECT_LT(hessian_sum.norm(), 1e-8);
    if (basis != MlsBasis::quadratic) continue;
    // x_a x_b is reproduced, and so is its Hessian, delta_ak delta_bl + delta_al delta_bk.
    EXPECT_LT((second_moment - x * x.transpose()).norm(), 1e-12);
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b) {
        Mat3 expected = Mat3::Zero();
        expected(a, b) += 1.0;
        expected(b, a) += 1.0;
        EXPECT_LT((second_of_products[3 * a + b] - expected).norm(), 1e-8) << a << b;
      }
  }
}

TEST_P(MlsReproduction, DerivativesMatchFiniteDifferences) {
  const auto [dim, basis, jitter] = GetParam();
  NodeSet s = lattice(dim, dim == 3 ? 0.25 : 0.125, jitter);
  const Vec3 x(0.43, 0.57, dim == 3 ? 0.38 : 0.0);
  Evaluation e = evaluate(dim, basis, s, x);
  ASSERT_TRUE(e.ok);
  const double h = 1e-6;
  for (int k = 0; k < dim; ++k) {
    Vec3 step = h * Vec3::Unit(k);
    // The same node list on both sides (the step is far from any support edge here).
    std::vector<Vec3> near;
    std::vector<double> radii;
    for (Index i : e.neighbors) near.push_back(s.nodes[i]), radii.push_back(s.radii[i]);
    MlsShape plus, minus;
    ASSERT_TRUE(mls_shape_functions(dim, basis, x + step, near, radii, false, plus));
    ASSERT_TRUE(mls_shape_functions(dim, basis, x - step, near, radii, false, minus));
    for (std::size_t I = 0; I < near.size(); ++I) {
      EXPECT_NEAR(e.shape.gradient[I][k], (plus.value[I] - minus.value[I]) / (2 * h), 1e-6);
      for (int l = 0; l < dim; ++l)
        EXPECT_NEAR(e.shape.hessian[I](l, k), (plus.gradient[I][l] - minus.gradient[I][l]) / (2 * h), 1e-4);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(UniformAndIrregular, MlsReproduction,
                         ::testing::Values(Case{2, MlsBasis::linear, 0.0}, Case{2, MlsBasis::quadratic, 0.0},
                                           Case{3, MlsBasis::linear, 0.0}, Case{3, MlsBasis::quadratic, 0.0},
                                           Case{2, MlsBasis::linear, 0.3}, Case{2, MlsBasis::quadratic, 0.3},
                                           Case{3, MlsBasis::linear, 0.3}, Case{3, MlsBasis::quadratic, 0.3}),
                         [](const auto& info) {
                           return std::to_string(info.param.dim) + "d_" +
                                  (info.param.basis == MlsBasis::linear ? "linear" : "quadratic") +
                                  (info.param.jitter > 0 ? "_irregular" : "_uniform");
                         });

TEST(Mls, SupportTooSmallToInvertIsReported) {
  // Three collinear nodes cannot fix a linear field in 3D.
  std::vector<Vec3> nodes{Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.2, 0, 0)};
  std::vector<double> radii(3, 0.5);
  MlsShape shape;
  EXPECT_FALSE(mls_shape_functions(3, MlsBasis::linear, Vec3(0.1, 0.01, 0), nodes, radii, false, shape));
  EXPECT_GT(shape.condition, 1e12);
  EXPECT_FALSE(mls_shape_functions(3, MlsBasis::linear, Vec3(5, 5, 5), nodes, radii, false, shape));
}

/// Where a cut leaves a point too few nodes for the full basis: the linear
/// fields along the directions the nodes span are reproduced (values and
/// gradients, to round-off), the gradient across them is zero, constants
/// always; the derivatives agree with finite differences.
void expect_spanned_reproduction(const std::vector<Vec3>& nodes, const Vec3& x, const std::vector<Vec3>& spanned,
                                 int directions) {
  std::vector<WeightValue> w;
  for (const Vec3& node : nodes) w.push_back(quartic_weight(x, node, 0.5));
  MlsShape shape;
  ASSERT_TRUE(mls_spanned_linear(3, x, nodes, w, node_spread(3, x, nodes, w, 0.5), 0.5, true, shape));
  EXPECT_EQ(shape.spanned_directions, directions);
  double sum = 0.0;
  Vec3 gradient_sum = Vec3::Zero();
  for (std::size_t I = 0; I < nodes.size(); ++I) sum += shape.value[I], gradient_sum += shape.gradient[I];
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_LT(gradient_sum.norm(), 1e-10);
  Mat3 across = Mat3::Identity();
  for (const Vec3& t : spanned) {
    double value = 0.0;
    Vec3 gradient = Vec3::Zero();
    for (std::size_t I = 0; I < nodes.size(); ++I)
      value += shape.value[I] * t.dot(nodes[I]), gradient += shape.gradient[I] * t.dot(nodes[I]);
    EXPECT_NEAR(value, t.dot(x), 1e-12);
    EXPECT_LT((gradient - t).norm(), 1e-10);
    across -= t * t.transpose();
  }
  // Across the spanned directions a linear field's gradient is zero.
  for (int k = 0; k < 3; ++k) {
    const Vec3 n = across.col(k);
    if (n.norm() < 1e-12) continue;
    Vec3 gradient = Vec3::Zero();
    for (std::size_t I = 0; I < nodes.size(); ++I) gradient += shape.gradient[I] * n.dot(nodes[I]);
    EXPECT_LT(gradient.norm(), 1e-10);
  }
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    MlsShape plus, minus;
    std::vector<WeightValue> wp, wm;
    for (const Vec3& node : nodes) {
      wp.push_back(quartic_weight(x + h * Vec3::Unit(k), node, 0.5));
      wm.push_back(quartic_weight(x - h * Vec3::Unit(k), node, 0.5));
    }
    // The directions held fixed, as at x (they are a property of the point's nodes).
    const NodeSpread spread = node_spread(3, x, nodes, w, 0.5);
    ASSERT_TRUE(mls_spanned_linear(3, x + h * Vec3::Unit(k), nodes, wp, spread, 0.5, false, plus));
    ASSERT_TRUE(mls_spanned_linear(3, x - h * Vec3::Unit(k), nodes, wm, spread, 0.5, false, minus));
    for (std::size_t I = 0; I < nodes.size(); ++I)
      EXPECT_NEAR(shape.gradient[I][k], (plus.value[I] - minus.value[I]) / (2 * h), 1e-6);
  }
}

TEST(Mls, ACutsFlapOneNodeLayerThickKeepsItsInPlaneLinearFields) {
  // A plane of nodes (z = 0.2) that a cut parted from the rest: the point on
  // it (a node, as nodal integration asks) and one just off it.
  std::vector<Vec3> plane;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) plane.push_back(Vec3(0.1 * i + 0.02 * j * j, 0.1 * j, 0.2));
  std::vector<Vec3> spanned{Vec3::UnitX(), Vec3::UnitY()};
  expect_spanned_reproduction(plane, Vec3(0.0, 0.0, 0.2), spanned, 2);
  expect_spanned_reproduction(plane, Vec3(0.03, -0.04, 0.21), spanned, 2);
  // A tilted line of nodes: one direction.
  std::vector<Vec3> line;
  const Vec3 along = Vec3(1, 2, 2) / 3.0;
  for (int i = -3; i <= 3; ++i) line.push_back(Vec3(0.1, 0.2, 0.3) + 0.07 * i * along);
  expect_spanned_reproduction(line, Vec3(0.1, 0.2, 0.3), {along}, 1);
  // A full linear basis on this flap is singular: the fallback is what keeps it.
  std::vector<double> radii(plane.size(), 0.5);
  MlsShape shape;
  EXPECT_FALSE(mls_shape_functions(3, MlsBasis::linear, Vec3(0.0, 0.0, 0.2), plane, radii, false, shape));
}

TEST(Mls, ANodeACutLeavesAloneMovesAsItsOwnTranslation) {
  std::vector<Vec3> alone{Vec3(0.3, 0.1, 0.2)};
  expect_spanned_reproduction(alone, Vec3(0.3, 0.1, 0.2), {}, 0);
  expect_spanned_reproduction(alone, Vec3(0.32, 0.1, 0.19), {}, 0);
  MlsShape shape;
  std::vector<WeightValue> none(1);  // no weight at all: nothing to fall back on
  EXPECT_FALSE(mls_spanned_linear(3, Vec3(0.3, 0.1, 0.2), alone, none, node_spread(3, Vec3(0.3, 0.1, 0.2), alone, none, 0.5),
                                  0.5, false, shape));
}

TEST(NeighborSearch, MatchesBruteForce) {
  NodeSet s = lattice(3, 0.1, 0.4);
  SupportIndex index(s.nodes, s.radii);
  std::vector<Vec3> queries{Vec3(0.5, 0.5, 0.5), Vec3(0, 0, 0), Vec3(0.93, 0.11, 0.42), Vec3(2, 2, 2)};
  NeighborLists lists = covering_supports(index, queries);
  ASSERT_EQ(lists.size(), static_cast<Index>(queries.size()));
  for (std::size_t q = 0; q < queries.size(); ++q) {
    std::vector<Index> expected;
    for (std::size_t i = 0; i < s.nodes.size(); ++i)
      if ((queries[q] - s.nodes[i]).norm() < s.radii[i]) expected.push_back(static_cast<Index>(i));
    auto found = lists.of(static_cast<Index>(q));
    EXPECT_EQ(std::vector<Index>(found.begin(), found.end()), expected) << q;
  }
  EXPECT_TRUE(lists.of(3).empty());
  std::vector<Index> close;
  index.within(Vec3(0.5, 0.5, 0.5), 0.15, close);
  for (Index i : close) EXPECT_LT((s.nodes[i] - Vec3(0.5, 0.5, 0.5)).norm(), 0.15);
}

// Radii over five octaves (a graded set's supports): each radius group is
// searched with its own largest radius, and the union must still be exact.
TEST(NeighborSearch, GradedSupportsMatchBruteForce) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> nodes;
  std::vector<double> radii;
  for (int i = 0; i < 2000; ++i) {
    nodes.emplace_back(unit(random), unit(random), unit(random));
    radii.push_back(0.01 * std::pow(2.0, 5.0 * unit(random)));
  }
  SupportIndex index(nodes, radii);
  std::vector<Index> found;
  for (int q = 0; q < 200; ++q) {
    const Vec3 x(unit(random), unit(random), unit(random));
    const double extra = q % 2 ? 0.0 : 0.05 * unit(random);
    std::vector<Index> reaching, near;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const double d = (x - nodes[i]).norm();
      if (d < radii[i] + extra) reaching.push_back(static_cast<Index>(i));
      if (d < 0.1) near.push_back(static_cast<Index>(i));
    }
    index.reaching(x, extra, found);
    EXPECT_EQ(found, reaching) << q;
    index.within(x, 0.1, found);
    EXPECT_EQ(found, near) << q;
  }
}

}  // namespace
}  // namespace kerf
