// p-multigrid's two pieces: the coarse space (the linear functions of
// quadratic cells, linear_prolongation.h) and its Galerkin matrix P^T A P.
#include <gtest/gtest.h>

#include <random>

#include "solvers/galerkin_product.h"
#include "solvers/linear_prolongation.h"
#include "support/test_support.h"

namespace kerf {
namespace {

/// The coarse dofs' (node, component), in linear_prolongation.h's order.
std::vector<std::pair<Index, int>> coarse_dofs(const Mesh& mesh, const FreeDofs& free, const std::vector<char>& own) {
  std::vector<std::pair<Index, int>> dofs;
  for (Index n = 0; n < mesh.node_count(); ++n)
    if (own[n])
      for (int i = 0; i < mesh.dimension; ++i)
        if (free.free_index(mesh.dimension * n + i) >= 0) dofs.emplace_back(n, i);
  return dofs;
}

std::vector<char> corners_of(const Mesh& mesh) {
  std::vector<char> corner(static_cast<std::size_t>(mesh.node_count()), 0);
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (int k = 0; k <= mesh.dimension; ++k) corner[mesh.cell(c)[k]] = 1;
  return corner;
}

/// max |P c - u| over the free dofs, c the field's values at the coarse dofs.
template <class Field>
double linear_field_error(const Mesh& mesh, const FreeDofs& free, const SparseMatrix& P,
                          const std::vector<std::pair<Index, int>>& coarse, const Field& field) {
  Vector c(static_cast<Index>(coarse.size()));
  for (std::size_t k = 0; k < coarse.size(); ++k) c[k] = field(mesh.nodes[coarse[k].first])[coarse[k].second];
  const Vector fine = P * c;
  double error = 0.0;
  for (Index r = 0; r < free.free_count(); ++r) {
    const Index dof = free.free_dofs()[r];
    error = std::max(error, std::abs(fine[r] - field(mesh.nodes[dof / mesh.dimension])[dof % mesh.dimension]));
  }
  return error;
}

// On straight-sided tri6 and tet10 cells every affine field is its corner
// values prolongated; with the x = 0 face held, every field that vanishes there.
TEST(LinearProlongation, CornerValuesGiveEveryLinearField) {
  for (int dim : {2, 3}) {
    const Mesh mesh = testing::unit_box_mesh(dim, 2, 0.25);
    const auto affine = [](const Vec3& x) { return Vec3(0.3 + x[0] - 2 * x[1] + 0.5 * x[2], -1 + 3 * x[0] + x[1],
                                                        2 - x[0] + 0.25 * x[1] - x[2]); };
    const FreeDofs all(dim * mesh.node_count(), {});
    const SparseMatrix P = corner_prolongation(mesh, all, dim);
    const auto coarse = coarse_dofs(mesh, all, corners_of(mesh));
    ASSERT_EQ(P.cols(), static_cast<Index>(coarse.size())) << dim;
    EXPECT_LT(linear_field_error(mesh, all, P, coarse, affine), 1e-14) << dim;

    std::vector<DirichletDof> held;
    for (Index n = 0; n < mesh.node_count(); ++n)
      if (mesh.nodes[n][0] == 0.0)
        for (int i = 0; i < dim; ++i) held.push_back({dim * n + i, 0.0});
    const FreeDofs free(dim * mesh.node_count(), held);
    const SparseMatrix Q = corner_prolongation(mesh, free, dim);
    const auto free_coarse = coarse_dofs(mesh, free, corners_of(mesh));
    ASSERT_EQ(Q.rows(), free.free_count());
    ASSERT_EQ(Q.cols(), static_cast<Index>(free_coarse.size()));
    const auto vanishing = [](const Vec3& x) { return Vec3(x[0], -2 * x[0], 0.5 * x[0]); };
    EXPECT_LT(linear_field_error(mesh, free, Q, free_coarse, vanishing), 1e-14) << dim;
  }
}

// Nodes asked to keep their own coarse dofs (a split cell's) are unit rows;
// the coarse space still holds every affine field.
TEST(LinearProlongation, OwnNodesKeepTheirDofs) {
  const Mesh mesh = testing::unit_box_mesh(3, 2, 0.25);
  const FreeDofs all(3 * mesh.node_count(), {});
  const std::vector<Index> kept(mesh.cell(0).begin(), mesh.cell(0).end());
  const SparseMatrix P = corner_prolongation(mesh, all, 3, kept);
  std::vector<char> own = corners_of(mesh);
  for (Index n : kept) own[n] = 1;
  const auto coarse = coarse_dofs(mesh, all, own);
  ASSERT_EQ(P.cols(), static_cast<Index>(coarse.size()));
  ASSERT_GT(P.cols(), corner_prolongation(mesh, all, 3).cols()) << "the cell's mid-edge nodes are coarse dofs";
  for (Index n : kept)
    for (int i = 0; i < 3; ++i) {
      const Index row = 3 * n + i;
      EXPECT_EQ(P.row(row).nonZeros(), 1);
      EXPECT_EQ(P.row(row).sum(), 1.0);
    }
  const auto affine = [](const Vec3& x) { return Vec3(1 + x[2], x[0] - x[1], 2 * x[1]); };
  EXPECT_LT(linear_field_error(mesh, all, P, coarse, affine), 1e-14);
}

// P^T A P for two matrices of one pattern (the values change, as they do
// from one Newton iteration to the next), against the dense product.
TEST(GalerkinProduct, EqualsTheTripleProductForEachNewMatrix) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_int_distribution<Index> fine_index(0, 59), coarse_index(0, 14);
  const Index n = 60, m = 15;
  std::vector<Eigen::Triplet<double, Index>> a, p;
  for (int k = 0; k < 200; ++k) {
    const Index i = fine_index(random), j = fine_index(random);
    a.emplace_back(i, j, 1.0), a.emplace_back(j, i, 1.0);
  }
  for (Index i = 0; i < n; ++i) {
    a.emplace_back(i, i, 1.0);
    p.emplace_back(i, coarse_index(random), value(random));
    if (i % 3) p.emplace_back(i, coarse_index(random), value(random));
  }
  SparseMatrix A(n, n), P(n, m);
  A.setFromTriplets(a.begin(), a.end());
  P.setFromTriplets(p.begin(), p.end());
  GalerkinProduct product(P, A);
  for (int round = 0; round < 2; ++round) {
    for (Index k = 0; k < A.nonZeros(); ++k) A.valuePtr()[k] = value(random);
    const Eigen::MatrixXd expected = Eigen::MatrixXd(P).transpose() * Eigen::MatrixXd(A) * Eigen::MatrixXd(P);
    const SparseMatrix& coarse = product.compute(A);
    EXPECT_LT((Eigen::MatrixXd(coarse) - expected).cwiseAbs().maxCoeff(), 1e-13) << "round " << round;
  }
}

}  // namespace
}  // namespace kerf
