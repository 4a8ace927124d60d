// The global pattern and the sink that adds blocks into it: every block a body
// visits is in the pattern, blocks land where they belong whatever the order
// of their dofs, and a block reaching outside the pattern may only hold zeros.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include <Eigen/Dense>

#include "core/check.h"
#include "solvers/sparse_assembly.h"

namespace kerf {
namespace {

/// Six 2-dof nodes on a line; blocks couple nodes {0,1,2}, {2,3} and {4,5}.
SparseMatrix line_pattern() {
  return build_pattern(2, 12, [](const CouplingVisitor& visit) {
    const std::vector<std::vector<Index>> blocks = {{0, 1, 2, 3, 4, 5}, {4, 5, 6, 7}, {8, 9, 10, 11}};
    for (const auto& dofs : blocks) visit(dofs);
  });
}

/// The pattern's node-level structure: (a, b) when some row of node a holds a column of node b.
std::set<std::pair<Index, Index>> node_structure(const SparseMatrix& m, int dpn) {
  std::set<std::pair<Index, Index>> pairs;
  for (Index r = 0; r < m.rows(); ++r)
    for (SparseMatrix::InnerIterator it(m, r); it; ++it) pairs.insert({r / dpn, static_cast<Index>(it.col()) / dpn});
  return pairs;
}

/// A block over `dofs` whose entry (i, j) is 100 dofs[i] + dofs[j].
std::vector<double> numbered_block(const std::vector<Index>& dofs) {
  std::vector<double> block;
  for (Index r : dofs)
    for (Index c : dofs) block.push_back(100.0 * r + c);
  return block;
}

TEST(SparseAssembly, PatternHoldsEveryVisitedPairAndTheDiagonalOnly) {
  SparseMatrix m = line_pattern();
  Eigen::MatrixXi structure = Eigen::MatrixXi::Zero(12, 12);
  for (Index r = 0; r < 12; ++r)
    for (SparseMatrix::InnerIterator it(m, r); it; ++it) structure(r, it.col()) = 1;
  auto coupled = [](Index a, Index b) {  // nodes
    auto in = [](Index n, std::initializer_list<Index> set) { return std::find(set.begin(), set.end(), n) != set.end(); };
    return a == b || (in(a, {0, 1, 2}) && in(b, {0, 1, 2})) || (in(a, {2, 3}) && in(b, {2, 3})) ||
           (in(a, {4, 5}) && in(b, {4, 5}));
  };
  for (Index r = 0; r < 12; ++r)
    for (Index c = 0; c < 12; ++c) EXPECT_EQ(structure(r, c), coupled(r / 2, c / 2) ? 1 : 0) << r << " " << c;
  EXPECT_EQ(m.norm(), 0.0);  // values start at zero
}

// An MPI rank's partial pattern: the kept nodes' rows whole, every other row its diagonal.
TEST(SparseAssembly, PatternOfKeptNodesHoldsTheirRowsWholeAndOnlyTheDiagonalElsewhere) {
  const SparseMatrix whole = line_pattern();
  const std::vector<Index> kept = {1, 2};
  const SparseMatrix part = build_pattern(2, 12, [](const CouplingVisitor& visit) {
    const std::vector<std::vector<Index>> blocks = {{0, 1, 2, 3, 4, 5}, {4, 5, 6, 7}, {8, 9, 10, 11}};
    for (const auto& dofs : blocks) visit(dofs);
  }, kept);
  std::set<std::pair<Index, Index>> expected;
  for (const auto& [a, b] : node_structure(whole, 2))
    if (a == b || a == 1 || a == 2) expected.insert({a, b});
  EXPECT_EQ(node_structure(part, 2), expected);
  EXPECT_EQ(part.nonZeros(), 4 * static_cast<Index>(expected.size()));  // 2 x 2 entries a node pair
}

// build_pattern marks each node's later neighbours and turns them round for
// the earlier ones: against every pair of every block, for blocks in any
// order, holding a node twice, of one node, with some nodes kept.
TEST(SparseAssembly, PatternEqualsThePairsOfEveryBlockForBlocksInAnyOrder) {
  std::srand(7);
  const Index nodes = 60;
  std::vector<std::vector<Index>> blocks;  // of nodes
  for (int b = 0; b < 200; ++b) {
    std::vector<Index> block;
    const Index centre = std::rand() % nodes, size = 1 + std::rand() % 9;
    for (Index k = 0; k < size; ++k) block.push_back(std::clamp<Index>(centre + std::rand() % 11 - 5, 0, nodes - 1));
    blocks.push_back(block);  // unsorted, sometimes a node twice
  }
  for (const std::vector<Index>& kept : {std::vector<Index>{}, std::vector<Index>{3, 17, 18, 40, 59}}) {
    const SparseMatrix m = build_pattern(3, 3 * nodes, [&](const CouplingVisitor& visit) {
      for (const std::vector<Index>& block : blocks) {
        std::vector<Index> dofs;
        for (Index n : block)
          for (int i = 0; i < 3; ++i) dofs.push_back(3 * n + i);
        visit(dofs);
      }
    }, kept);
    std::set<std::pair<Index, Index>> expected;
    auto is_kept = [&](Index a) { return kept.empty() || std::count(kept.begin(), kept.end(), a) > 0; };
    for (Index a = 0; a < nodes; ++a) expected.insert({a, a});
    for (const std::vector<Index>& block : blocks)
      for (Index a : block)
        for (Index b : block)
          if (is_kept(a)) expected.insert({a, b});
    EXPECT_EQ(node_structure(m, 3), expected) << kept.size() << " kept";
    EXPECT_EQ(m.nonZeros(), 9 * static_cast<Index>(expected.size()));
    for (Index r = 0; r < m.rows(); ++r)  // sorted, distinct columns
      for (Index k = m.outerIndexPtr()[r] + 1; k < m.outerIndexPtr()[r + 1]; ++k)
        EXPECT_LT(m.innerIndexPtr()[k - 1], m.innerIndexPtr()[k]) << "row " << r;
  }
}

TEST(SparseAssembly, BlocksLandInPlaceWhateverTheOrderOfTheirDofs) {
  for (const std::vector<Index>& dofs : {std::vector<Index>{0, 1, 2, 3, 4, 5}, std::vector<Index>{4, 5, 0, 1, 2, 3},
                                         std::vector<Index>{5, 0, 3, 1, 4, 2}}) {
    SparseMatrix m = line_pattern();
    add_into(m, 2.0)(dofs, numbered_block(dofs));
    const Eigen::MatrixXd dense(m);
    for (Index r = 0; r < 12; ++r)
      for (Index c = 0; c < 12; ++c)
        EXPECT_EQ(dense(r, c), r < 6 && c < 6 ? 2.0 * (100.0 * r + c) : 0.0) << r << " " << c;
  }
}

// Long rows: a column is sought forward from the one before by doubling steps.
TEST(SparseAssembly, BlocksLandInPlaceInLongRows) {
  const Index n = 64;
  auto star = [&](const CouplingVisitor& visit) {  // every node with node 0 and with its successor
    for (Index k = 1; k < n; ++k) {
      visit(std::vector<Index>{0, k});
      if (k + 1 < n) visit(std::vector<Index>{k, k + 1});
    }
  };
  for (const std::vector<Index>& dofs : {std::vector<Index>{0, 1, 2, 5, 12, 13, 40, 63},
                                         std::vector<Index>{0, 7, 8, 9, 10, 11, 12, 30, 31, 62, 63}}) {
    SparseMatrix m = build_pattern(1, n, star);
    std::vector<double> block = numbered_block(dofs);
    for (std::size_t i = 1; i < dofs.size(); ++i)  // keep row 0 and column 0 and the pairs the pattern holds
      for (std::size_t j = 1; j < dofs.size(); ++j)
        if (std::abs(dofs[i] - dofs[j]) > 1) block[i * dofs.size() + j] = 0.0;
    add_into(m)(dofs, block);
    const Eigen::MatrixXd dense(m);
    for (std::size_t i = 0; i < dofs.size(); ++i)
      for (std::size_t j = 0; j < dofs.size(); ++j)
        EXPECT_EQ(dense(dofs[i], dofs[j]), block[i * dofs.size() + j]) << dofs[i] << " " << dofs[j];
    EXPECT_EQ(dense.sum(), Eigen::Map<const Eigen::VectorXd>(block.data(), block.size()).sum());
  }
}

// A cell's Gauss points summed over the union of their nodes give a block
// whose node pairs that share no point are zero and may lie outside the pattern.
TEST(SparseAssembly, ZerosOutsideThePatternAreSkippedAndNonzerosRefused) {
  const std::vector<Index> dofs = {2, 3, 4, 5, 6, 7};  // nodes 1, 2, 3: the pair (1, 3) is not in the pattern
  std::vector<double> block = numbered_block(dofs);
  auto outside = [](Index r, Index c) { return (r / 2 == 1 && c / 2 == 3) || (r / 2 == 3 && c / 2 == 1); };
  for (std::size_t i = 0; i < dofs.size(); ++i)
    for (std::size_t j = 0; j < dofs.size(); ++j)
      if (outside(dofs[i], dofs[j])) block[i * dofs.size() + j] = 0.0;
  SparseMatrix m = line_pattern();
  add_into(m)(dofs, block);
  const Eigen::MatrixXd dense(m);
  for (Index r = 0; r < 12; ++r)
    for (Index c = 0; c < 12; ++c) {
      const bool in_block = r >= 2 && r < 8 && c >= 2 && c < 8 && !outside(r, c);
      EXPECT_EQ(dense(r, c), in_block ? 100.0 * r + c : 0.0) << r << " " << c;
    }
  block[0 * dofs.size() + 5] = 1.0;  // (2, 7): node 1 with node 3
  EXPECT_THROW(add_into(m)(dofs, block), Error);
}

/// The dofs of `nodes` (3 a node), in their order.
std::vector<Index> node_dofs(const std::vector<Index>& nodes) {
  std::vector<Index> dofs;
  for (Index a : nodes)
    for (Index k = 0; k < 3; ++k) dofs.push_back(3 * a + k);
  return dofs;
}

// The node-pair path (dofs_per_node 3) writes what the entry path writes, on
// whole and partial (an MPI rank's) patterns, with nodes in any order, pairs
// outside the pattern holding zeros, and blocks that are not whole nodes.
TEST(SparseAssembly, NodePairsLandWhereTheEntryPathPutsThem) {
  const Index nodes = 20;
  auto windows = [&](const CouplingVisitor& visit) {  // nodes k..k+3, and every node with node 0
    for (Index k = 0; k + 3 < nodes; ++k) visit(node_dofs({k, k + 1, k + 2, k + 3}));
    for (Index k = 1; k < nodes; ++k) visit(node_dofs({0, k}));
  };
  const std::vector<std::vector<Index>> blocks = {
      node_dofs({0, 3, 4, 5}), node_dofs({7, 5, 6, 0}), node_dofs({2, 9, 3, 4, 5, 1}), node_dofs({19, 0, 18, 17}),
      {4, 5, 6, 7, 8, 9}, {10, 3, 11, 12}};  // the last two: not whole nodes (offset by one; a lone dof)
  for (const std::vector<Index>& kept : {std::vector<Index>{}, std::vector<Index>{2, 3, 5, 18}}) {
    SparseMatrix by_entry = build_pattern(3, 3 * nodes, windows, kept), by_node = by_entry;
    const Eigen::MatrixXd present = Eigen::MatrixXd(by_entry).cwiseAbs();  // pattern: values start at zero
    SparseMatrix marks = by_entry;
    std::fill(marks.valuePtr(), marks.valuePtr() + marks.nonZeros(), 1.0);
    const Eigen::MatrixXd in_pattern(marks);
    EXPECT_EQ(present.sum(), 0.0);
    for (const auto& dofs : blocks) {
      std::vector<double> block = numbered_block(dofs);
      for (std::size_t i = 0; i < dofs.size(); ++i)
        for (std::size_t j = 0; j < dofs.size(); ++j)
          if (in_pattern(dofs[i], dofs[j]) == 0.0) block[i * dofs.size() + j] = 0.0;
      add_into(by_entry, 0.5)(dofs, block);
      add_into(by_node, 0.5, 3)(dofs, block);
    }
    const Eigen::MatrixXd expected(by_entry), got(by_node);
    EXPECT_EQ((got - expected).cwiseAbs().maxCoeff(), 0.0) << kept.size() << " kept";
    EXPECT_GT(got.cwiseAbs().sum(), 0.0);
    // A nonzero outside the pattern is refused on this path too.
    const std::vector<Index> dofs = node_dofs({1, 9});
    std::vector<double> block(dofs.size() * dofs.size(), 1.0);
    EXPECT_THROW(add_into(by_node, 1.0, 3)(dofs, block), Error);
  }
  // A pattern whose rows of one node differ (not build_pattern's): each row
  // of such a node is written by its own search, present columns and all.
  std::vector<Eigen::Triplet<double, Index>> entries;
  for (Index r = 0; r < 9; ++r)
    for (Index c = 0; c < 9; ++c)
      if (r != 4 || c < 3 || c > 6) entries.emplace_back(r, c, 0.0);  // row 4 lacks node 1's columns 3..5 and 6
  SparseMatrix by_entry(9, 9);
  by_entry.setFromTriplets(entries.begin(), entries.end());
  by_entry.makeCompressed();
  SparseMatrix by_node = by_entry;
  const std::vector<Index> dofs = node_dofs({2, 1, 0});
  std::vector<double> block = numbered_block(dofs);
  for (std::size_t i = 0; i < dofs.size(); ++i)
    for (std::size_t j = 0; j < dofs.size(); ++j)
      if (dofs[i] == 4 && dofs[j] >= 3 && dofs[j] <= 6) block[i * dofs.size() + j] = 0.0;
  add_into(by_entry)(dofs, block);
  add_into(by_node, 1.0, 3)(dofs, block);
  EXPECT_EQ((Eigen::MatrixXd(by_node) - Eigen::MatrixXd(by_entry)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(Eigen::MatrixXd(by_node)(3, 5), 100.0 * 3 + 5);
}

}  // namespace
}  // namespace kerf
