// Convergence of the FEM under mesh refinement for a manufactured solution of
// linear elasticity on the unit square/cube:
//   u = (sin(pi x) sin(pi y) [sin(pi z)], 0, 0),  b = -div sigma(u),
// with u imposed on the whole boundary. The L2 error falls as h^(p+1) and the
// H1 seminorm error as h^p for elements of order p; the rates are asserted.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <numbers>

#include "discretization/fem/simplex_quadrature.h"
#include "discretization/fem/simplex_shape.h"
#include "support/test_support.h"

namespace kerf {
namespace {

constexpr double pi = std::numbers::pi;

struct Manufactured {
  int dim;
  double lambda, mu;
  double f(const Vec3& x) const {
    double v = std::sin(pi * x.x()) * std::sin(pi * x.y());
    return dim == 3 ? v * std::sin(pi * x.z()) : v;
  }
  Vec3 u(const Vec3& x) const { return Vec3(f(x), 0, 0); }
  /// grad u (3x3, row i = grad of u_i); only u_x is non-zero.
  Mat3 grad(const Vec3& x) const {
    double sx = std::sin(pi * x.x()), cx = std::cos(pi * x.x()), sy = std::sin(pi * x.y()), cy = std::cos(pi * x.y());
    double sz = dim == 3 ? std::sin(pi * x.z()) : 1.0, cz = dim == 3 ? std::cos(pi * x.z()) : 0.0;
    Mat3 g = Mat3::Zero();
    g(0, 0) = pi * cx * sy * sz;
    g(0, 1) = pi * sx * cy * sz;
    if (dim == 3) g(0, 2) = pi * sx * sy * cz;
    return g;
  }
  /// b = -(lambda + mu) grad(div u) - mu laplace(u).
  Vec3 body_force(const Vec3& x) const {
    double sx = std::sin(pi * x.x()), cx = std::cos(pi * x.x()), sy = std::sin(pi * x.y()), cy = std::cos(pi * x.y());
    double sz = dim == 3 ? std::sin(pi * x.z()) : 1.0, cz = dim == 3 ? std::cos(pi * x.z()) : 0.0;
    double p2 = pi * pi;
    Vec3 grad_div(-p2 * sx * sy * sz, p2 * cx * cy * sz, dim == 3 ? p2 * cx * sy * cz : 0.0);
    Vec3 laplace(-dim * p2 * f(x), 0, 0);
    return -(lambda + mu) * grad_div - mu * laplace;
  }
};

struct Errors {
  double h, l2, h1;
};

Errors solve_and_measure(int dim, int order, double size) {
  Scene scene = testing::scene_from_text(dim == 3 ? "domain: {box: {min: [0,0,0], max: [1,1,1]}}\n"
                                                  : "dimension: 2\ndomain: {box: {min: [0,0], max: [1,1]}}\n");
  FemBody body(scene, testing::unit_box_mesh(dim, order, size));
  const Mesh& mesh = body.mesh();
  Lame lame = Lame::from_young_poisson(scene.material.young, scene.material.poisson);
  Manufactured m{dim, lame.lambda, lame.mu};
  const int npc = mesh.nodes_per_cell();

  // Load vector of the manufactured body force, integrated with a high-order rule.
  QuadratureRule rule = simplex_quadrature(dim, 2 * order + 4);
  Vector load = Vector::Zero(body.dof_count());
  std::vector<double> N(npc), dN(npc * dim);
  auto map_point = [&](Index c, const Vec3& xi, Eigen::MatrixXd& J) {
    auto n = mesh.cell(c);
    simplex_shape_values(dim, order, xi, N.data());
    simplex_shape_gradients(dim, order, xi, dN.data());
    Vec3 x = Vec3::Zero();
    J = Eigen::MatrixXd::Zero(dim, dim);
    for (int a = 0; a < npc; ++a) {
      x += N[a] * mesh.nodes[n[a]];
      for (int i = 0; i < dim; ++i)
        for (int k = 0; k < dim; ++k) J(i, k) += mesh.nodes[n[a]][i] * dN[a * dim + k];
    }
    return x;
  };
  Eigen::MatrixXd J;
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    auto n = mesh.cell(c);
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      Vec3 x = map_point(c, rule.points[q], J);
      Vec3 b = m.body_force(x);
      double w = rule.weights[q] * J.determinant();
      for (int a = 0; a < npc; ++a)
        for (int i = 0; i < dim; ++i) load[dim * n[a] + i] += w * N[a] * b[i];
    }
  }
  // Exact values on the boundary, solve for the interior.
  BoundaryFacets facets = boundary_facets(mesh);
  std::vector<char> on_boundary = boundary_node_flags(mesh, facets);
  std::vector<DirichletDof> fixed;
  Vector boundary_values = Vector::Zero(body.dof_count());
  for (Index node = 0; node < mesh.node_count(); ++node)
    if (on_boundary[node])
      for (int i = 0; i < dim; ++i) {
        double v = m.u(mesh.nodes[node])[i];
        fixed.push_back({dim * node + i, v});
        boundary_values[dim * node + i] = v;
      }
  SparseMatrix K = testing::assemble_stiffness(body, Vector::Zero(body.dof_count()));
  FreeDofs free(body.dof_count(), fixed);
  free.prepare_matrix(K);
  free.restrict_values(K);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(Eigen::SparseMatrix<double>(free.restricted()));
  Vector u = boundary_values;
  free.add_to_full(solver.solve(free.restrict_vector(load - K * boundary_values)), u);

  // Errors by quadrature.
  double l2 = 0.0, h1 = 0.0, volume = 0.0;
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    auto n = mesh.cell(c);
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      Vec3 x = map_point(c, rule.points[q], J);
      double w = rule.weights[q] * J.determinant();
      Eigen::MatrixXd Jinv = J.inverse();
      Vec3 uh = Vec3::Zero();
      Mat3 gh = Mat3::Zero();
      for (int a = 0; a < npc; ++a) {
        Vec3 ua = Vec3::Zero();
        for (int i = 0; i < dim; ++i) ua[i] = u[dim * n[a] + i];
        uh += N[a] * ua;
        for (int l = 0; l < dim; ++l) {
          double dNdX = 0.0;
          for (int k = 0; k < dim; ++k) dNdX += dN[a * dim + k] * Jinv(k, l);
          gh.col(l) += ua * dNdX;
        }
      }
      l2 += w * (uh - m.u(x)).squaredNorm();
      h1 += w * (gh - m.grad(x)).squaredNorm();
      volume += w;
    }
  }
  double h = std::pow(volume / mesh.cell_count(), 1.0 / dim);
  return {h, std::sqrt(l2), std::sqrt(h1)};
}

struct ConvergenceCase {
  ElementType element;
  int dim, order;
  std::vector<double> sizes;
};

class FemConvergenceTest : public ::testing::TestWithParam<ConvergenceCase> {};

TEST_P(FemConvergenceTest, ErrorFallsAtTheExpectedRate) {
  const ConvergenceCase& c = GetParam();
  std::vector<Errors> levels;
  for (double size : c.sizes) levels.push_back(solve_and_measure(c.dim, c.order, size));
  for (std::size_t k = 1; k < levels.size(); ++k) {
    double ratio = std::log(levels[k - 1].h / levels[k].h);
    double l2_rate = std::log(levels[k - 1].l2 / levels[k].l2) / ratio;
    double h1_rate = std::log(levels[k - 1].h1 / levels[k].h1) / ratio;
    std::printf("%s h %.4f -> %.4f: L2 %.3e -> %.3e (rate %.2f), H1 %.3e -> %.3e (rate %.2f)\n",
                to_string(c.element), levels[k - 1].h, levels[k].h, levels[k - 1].l2, levels[k].l2, l2_rate,
                levels[k - 1].h1, levels[k].h1, h1_rate);
    if (k + 1 == levels.size()) {  // asymptotic rates on the finest pair
      EXPECT_GT(l2_rate, c.order + 1 - 0.3) << to_string(c.element);
      EXPECT_GT(h1_rate, c.order - 0.2) << to_string(c.element);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllElements, FemConvergenceTest,
    ::testing::Values(ConvergenceCase{ElementType::tri3, 2, 1, {0.1, 0.05, 0.025}},
                      ConvergenceCase{ElementType::tri6, 2, 2, {0.2, 0.1, 0.05}},
                      ConvergenceCase{ElementType::tet4, 3, 1, {0.25, 0.125, 0.0625}},
                      ConvergenceCase{ElementType::tet10, 3, 2, {0.5, 0.25, 0.125}}),
    [](const auto& info) { return std::string(to_string(info.param.element)); });

}  // namespace
}  // namespace kerf
