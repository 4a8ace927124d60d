#include "solvers/sparse_assembly.h"

#include <algorithm>
#include <vector>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "geometry/neighbor_search.h"

namespace kerf {

SparseMatrix build_pattern(const DiscreteBody& body) {
  return build_pattern(body.dofs_per_node(), body.dof_count(),
                       [&](const CouplingVisitor& visit) { body.visit_couplings(visit); });
}

namespace {

/// Each visited block's nodes, ascending and distinct, in one flat list (a
/// block holds whole nodes).
NeighborLists gather_blocks(int dpn, const std::function<void(const CouplingVisitor&)>& visit_couplings) {
  NeighborLists blocks;
  visit_couplings([&](std::span<const Index> dofs) {
    KERF_DCHECK(dofs.size() % dpn == 0);
    const auto first = blocks.index.end() - blocks.index.begin();
    for (std::size_t i = 0; i < dofs.size(); i += dpn) blocks.index.push_back(dofs[i] / dpn);
    const auto begin = blocks.index.begin() + first;
    if (!std::is_sorted(begin, blocks.index.end())) std::sort(begin, blocks.index.end());
    blocks.index.erase(std::unique(begin, blocks.index.end()), blocks.index.end());
    blocks.start.push_back(static_cast<Index>(blocks.index.size()));
  });
  return blocks;
}

/// For each node, the nodes after it in the blocks holding it, ascending: the
/// upper half of the node couplings (each pair is visited from its first node
/// alone, half the visits of marking every block holding a node).
std::vector<std::vector<Index>> later_couplings(const NeighborLists& blocks, Index nodes) {
  std::vector<Index> holding_block;  // per entry of holding: the block holding the slot
  const NeighborLists holding = transpose_slots(blocks, nodes, &holding_block);  // per node: the slots holding it
  std::vector<std::vector<Index>> later(nodes);
  ParallelFailure failure;  // the lists allocate
#pragma omp parallel
  {
    std::vector<Index> marked_by;
    failure.run([&] { marked_by.assign(nodes, -1); });
#pragma omp for schedule(dynamic, 64)
    for (Index a = 0; a < nodes; ++a)
      failure.run([&] {
        std::vector<Index>& list = later[a];
        const Index last = holding.start[a + 1];
        for (Index h = holding.start[a]; h < last; ++h) {
          const Index slot = holding.index[h], end = blocks.start[holding_block[h] + 1];
          if (h + 8 < last) __builtin_prefetch(&blocks.index[holding.index[h + 8]]);  // scattered: the misses cost
          for (Index k = slot + 1; k < end; ++k) {
            const Index c = blocks.index[k];
            if (marked_by[c] != a) marked_by[c] = a, list.push_back(c);
          }
        }
        std::sort(list.begin(), list.end());
      });
  }
  failure.rethrow_if_failed();
  return later;
}

/// The whole-node pattern whose rows of `kept` nodes hold the nodes coupled to
/// them (those before, from the later lists turned round, the node, those after) and
/// whose other rows hold their diagonal alone.
SparseMatrix pattern_of(int dpn, Index n, const std::vector<std::vector<Index>>& later, const std::vector<char>& kept) {
  const Index nodes = static_cast<Index>(later.size());
  NeighborLists earlier;  // per node: the nodes before it coupled to it, ascending
  earlier.start.assign(nodes + 1, 0);
  for (Index a = 0; a < nodes; ++a)
    for (Index c : later[a]) ++earlier.start[c + 1];
  for (Index a = 0; a < nodes; ++a) earlier.start[a + 1] += earlier.start[a];
  earlier.index.resize(earlier.start[nodes]);
  std::vector<Index> next(earlier.start.begin(), earlier.start.end() - 1);
  for (Index a = 0; a < nodes; ++a)
    for (Index c : later[a]) earlier.index[next[c]++] = a;
  SparseMatrix m(n, n);
  Index* outer = m.outerIndexPtr();
  outer[0] = 0;
  for (Index a = 0; a < nodes; ++a) {
    const Index columns = kept[a] ? earlier.of(a).size() + 1 + later[a].size() : 1;
    for (int i = 0; i < dpn; ++i) outer[dpn * a + i + 1] = outer[dpn * a + i] + columns * dpn;
  }
  m.resizeNonZeros(outer[n]);
  Index* inner = m.innerIndexPtr();
#pragma omp parallel for schedule(dynamic, 64)
  for (Index a = 0; a < nodes; ++a) {
    Index* at = inner + outer[dpn * a];
    auto put = [&](Index c) {
      for (int k = 0; k < dpn; ++k) *at++ = dpn * c + k;
    };
    if (kept[a]) std::for_each(earlier.of(a).begin(), earlier.of(a).end(), put);
    put(a);  // the diagonal is always present
    if (kept[a]) std::for_each(later[a].begin(), later[a].end(), put);
    const Index* first_row = inner + outer[dpn * a];
    const Index length = outer[dpn * a + 1] - outer[dpn * a];
    for (int i = 1; i < dpn; ++i) std::copy(first_row, first_row + length, at + (i - 1) * length);
  }
  std::fill(m.valuePtr(), m.valuePtr() + outer[n], 0.0);
  return m;
}

}  // namespace

SparseMatrix build_pattern(int dpn, Index n, const std::function<void(const CouplingVisitor&)>& visit_couplings,
                           std::span<const Index> kept_nodes) {
  // Meshless bodies visit each node pair dozens of times (once per shared
  // point): each node's couplings are found once, by marking the nodes after
  // it in the blocks that hold it (those before it are the same lists turned
  // round), rather than by sorting every visit's pairs.
  const Index nodes = n / dpn;
  std::vector<char> kept(nodes, kept_nodes.empty() ? 1 : 0);
  for (Index a : kept_nodes) kept[a] = 1;
  return pattern_of(dpn, n, later_couplings(gather_blocks(dpn, visit_couplings), nodes), kept);
}

CsrView csr_view(SparseMatrix& matrix) {
  KERF_CHECK(matrix.isCompressed(), "internal: a matrix written through its arrays must be compressed");
  return {static_cast<Index>(matrix.rows()), matrix.outerIndexPtr(), matrix.innerIndexPtr(), matrix.valuePtr()};
}

BlockSink add_into(SparseMatrix& matrix, double scale, int dofs_per_node) {
  return add_into(CsrView{static_cast<Index>(matrix.rows()), matrix.outerIndexPtr(), matrix.innerIndexPtr(),
                          matrix.valuePtr()}, scale, dofs_per_node);
}

std::vector<Index> diagonal_positions(const SparseMatrix& m) {
  std::vector<Index> positions(m.rows());
  for (Index r = 0; r < m.rows(); ++r) {
    const Index* begin = m.innerIndexPtr() + m.outerIndexPtr()[r];
    const Index* end = m.innerIndexPtr() + m.outerIndexPtr()[r + 1];
    const Index* at = std::lower_bound(begin, end, r);
    KERF_CHECK(at != end && *at == r, "sparse pattern lacks the diagonal entry of row ", r);
    positions[r] = static_cast<Index>(at - m.innerIndexPtr());
  }
  return positions;
}

FreeDofs::FreeDofs(Index dof_count, const std::vector<DirichletDof>& constrained)
    : free_of_full_(dof_count, 0) {
  for (const DirichletDof& d : constrained) free_of_full_[d.dof] = -1;
  for (Index i = 0; i < dof_count; ++i)
    if (free_of_full_[i] >= 0) {
      free_of_full_[i] = static_cast<Index>(full_of_free_.size());
      full_of_free_.push_back(i);
    }
}

Vector FreeDofs::restrict_vector(const Vector& full) const {
  Vector r(free_count());
  for (Index i = 0; i < free_count(); ++i) r[i] = full[full_of_free_[i]];
  return r;
}

void FreeDofs::add_to_full(const Vector& free, Vector& full) const {
  for (Index i = 0; i < free_count(); ++i) full[full_of_free_[i]] += free[i];
}

void FreeDofs::prepare_matrix(const SparseMatrix& full) {
  // The CSR arrays written directly, rows in parallel: the free numbering
  // keeps the columns' order, so each row's entries are the full row's free ones.
  const Index n = free_count();
  const Index* full_outer = full.outerIndexPtr();
  const Index* full_inner = full.innerIndexPtr();
  restricted_ = SparseMatrix(n, n);
  Index* outer = restricted_.outerIndexPtr();
  outer[0] = 0;
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Index r = full_of_free_[i];
    Index count = 0;
    for (Index p = full_outer[r]; p < full_outer[r + 1]; ++p) count += free_of_full_[full_inner[p]] >= 0;
    outer[i + 1] = count;
  }
  for (Index i = 0; i < n; ++i) outer[i + 1] += outer[i];
  restricted_.resizeNonZeros(outer[n]);
  source_position_.resize(static_cast<std::size_t>(outer[n]));  // not zeroed: the rows below write each entry
  Index* inner = restricted_.innerIndexPtr();
  double* values = restricted_.valuePtr();
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Index r = full_of_free_[i];
    Index k = outer[i];
    for (Index p = full_outer[r]; p < full_outer[r + 1]; ++p) {
      const Index j = free_of_full_[full_inner[p]];
      if (j < 0) continue;
      inner[k] = j;
      values[k] = 0.0;
      source_position_[k++] = p;
    }
  }
  restricted_diagonal_.clear();
}

void FreeDofs::add_to_diagonal(double scale, const Vector& diagonal) {
  if (restricted_diagonal_.empty()) restricted_diagonal_ = diagonal_positions(restricted_);
  double* values = restricted_.valuePtr();
  for (std::size_t i = 0; i < full_of_free_.size(); ++i)
    values[restricted_diagonal_[i]] += scale * diagonal[full_of_free_[i]];
}

}  // namespace kerf
