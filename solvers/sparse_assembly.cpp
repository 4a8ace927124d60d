#include "solvers/sparse_assembly.h"

#include <algorithm>
#include <vector>

#include "core/check.h"
#include "core/parallel_failure.h"

namespace kerf {

SparseMatrix build_pattern(const DiscreteBody& body) {
  return build_pattern(body.dofs_per_node(), body.dof_count(),
                       [&](const CouplingVisitor& visit) { body.visit_couplings(visit); });
}

namespace {

/// Each visited block's nodes, in one flat list (a block holds whole nodes).
struct BlockNodes {
  std::vector<Index> start{0};
  std::vector<Index> nodes;
};

BlockNodes gather_blocks(int dpn, const std::function<void(const CouplingVisitor&)>& visit_couplings) {
  BlockNodes blocks;
  visit_couplings([&](std::span<const Index> dofs) {
    KERF_DCHECK(dofs.size() % dpn == 0);
    for (std::size_t i = 0; i < dofs.size(); i += dpn) blocks.nodes.push_back(dofs[i] / dpn);
    blocks.start.push_back(static_cast<Index>(blocks.nodes.size()));
  });
  return blocks;
}

/// For each node, the blocks holding it (a counting sort of the blocks' nodes).
std::vector<std::vector<Index>> blocks_of_nodes(const BlockNodes& blocks, Index nodes) {
  std::vector<std::vector<Index>> of(nodes);
  const Index count = static_cast<Index>(blocks.start.size()) - 1;
  for (Index b = 0; b < count; ++b)
    for (Index k = blocks.start[b]; k < blocks.start[b + 1]; ++k) of[blocks.nodes[k]].push_back(b);
  return of;
}

}  // namespace

SparseMatrix build_pattern(int dpn, Index n, const std::function<void(const CouplingVisitor&)>& visit_couplings,
                           std::span<const Index> kept_nodes) {
  // Meshless bodies visit each node pair dozens of times (once per shared
  // point): each node's couplings are found once, by marking the nodes of the
  // blocks that hold it, rather than by sorting every visit's pairs.
  const Index nodes = n / dpn;
  const BlockNodes blocks = gather_blocks(dpn, visit_couplings);
  const std::vector<std::vector<Index>> holding = blocks_of_nodes(blocks, nodes);
  std::vector<char> kept(nodes, kept_nodes.empty() ? 1 : 0);
  for (Index a : kept_nodes) kept[a] = 1;
  std::vector<std::vector<Index>> adjacent(nodes);
  ParallelFailure failure;  // the lists allocate
#pragma omp parallel
  {
    std::vector<Index> marked_by;
    failure.run([&] { marked_by.assign(nodes, -1); });
#pragma omp for schedule(dynamic, 64)
    for (Index a = 0; a < nodes; ++a)
      failure.run([&] {
        auto& list = adjacent[a];
        list.push_back(a);  // the diagonal is always present
        if (!kept[a]) return;
        marked_by[a] = a;
        for (Index b : holding[a])
          for (Index k = blocks.start[b]; k < blocks.start[b + 1]; ++k) {
            const Index c = blocks.nodes[k];
            if (marked_by[c] != a) marked_by[c] = a, list.push_back(c);
          }
        std::sort(list.begin(), list.end());
      });
  }
  failure.rethrow_if_failed();
  SparseMatrix m(n, n);
  Index nonzeros = 0;
  for (Index a = 0; a < nodes; ++a) nonzeros += static_cast<Index>(adjacent[a].size()) * dpn * dpn;
  m.resizeNonZeros(nonzeros);
  Index* outer = m.outerIndexPtr();
  Index* inner = m.innerIndexPtr();
  Index at = 0;
  for (Index a = 0; a < nodes; ++a)
    for (int i = 0; i < dpn; ++i) {
      outer[dpn * a + i] = at;
      for (Index c : adjacent[a])
        for (int k = 0; k < dpn; ++k) inner[at++] = dpn * c + k;
    }
  outer[n] = at;
  std::fill(m.valuePtr(), m.valuePtr() + nonzeros, 0.0);
  return m;
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
  source_position_.resize(static_cast<std::size_t>(outer[n]));
  Index* inner = restricted_.innerIndexPtr();
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Index r = full_of_free_[i];
    Index k = outer[i];
    for (Index p = full_outer[r]; p < full_outer[r + 1]; ++p) {
      const Index j = free_of_full_[full_inner[p]];
      if (j < 0) continue;
      inner[k] = j;
      source_position_[k++] = p;
    }
  }
  std::fill(restricted_.valuePtr(), restricted_.valuePtr() + outer[n], 0.0);
  restricted_diagonal_.clear();
}

void FreeDofs::add_to_diagonal(double scale, const Vector& diagonal) {
  if (restricted_diagonal_.empty()) restricted_diagonal_ = diagonal_positions(restricted_);
  double* values = restricted_.valuePtr();
  for (std::size_t i = 0; i < full_of_free_.size(); ++i)
    values[restricted_diagonal_[i]] += scale * diagonal[full_of_free_[i]];
}

}  // namespace kerf
