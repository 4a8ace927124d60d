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

namespace {

/// The position of `column` in the sorted row [begin, end), known to lie at or
/// after `from`: tried there first, then by doubling steps and a binary search.
Index search_forward(const Index* begin, const Index* end, Index from, Index column) {
  const Index length = static_cast<Index>(end - begin);
  if (from >= length) return length;  // past the row's last entry: absent
  if (begin[from] >= column) return from;
  Index step = 1, low = from;  // begin[low] < column
  while (low + step < length && begin[low + step] < column) low += step, step *= 2;
  const Index high = std::min(length, low + step);  // begin[high] >= column, or the row's end
  return static_cast<Index>(std::lower_bound(begin + low + 1, begin + high, column) - begin);
}

/// The matrix's arrays as the sinks below write into them.
struct SinkTarget {
  const Index* outer;
  const Index* inner;
  double* values;
  double scale;

  /// A block may span node pairs the pattern leaves out (a cell's points
  /// summed over the union of their nodes) if it holds zeros there.
  static void refuse_nonzero_outside(Index row, Index column, double value) {
    KERF_CHECK(value == 0.0, "internal: a block writes ", value, " at (", row, ", ", column,
               "), outside the matrix's pattern");
  }

  /// Adds scale * in[m] at (row, column + m) for m < count, found by one bisection.
  void add_run(Index row, Index column, const double* in, int count) const {
    const Index* end = inner + outer[row + 1];
    const Index* at = std::lower_bound(inner + outer[row], end, column);
    for (int m = 0; m < count; ++m) {
      if (at != end && *at == column + m) {
        values[at++ - inner] += scale * in[m];
        continue;
      }
      refuse_nonzero_outside(row, column + m, in[m]);
    }
  }

  /// Any block: each entry sought in its row.
  void add_block(std::span<const Index> dofs, std::span<const double> block) const;
  /// A block of whole nodes of W dofs (dofs[W t + k] = dofs[W t] + k) into a
  /// pattern of whole node pairs: one search a node pair, W x W entries written.
  template <int W>
  void add_node_block(std::span<const Index> dofs, std::span<const double> block) const;
};

void SinkTarget::add_block(std::span<const Index> dofs, std::span<const double> block) const {
  const std::size_t n = dofs.size();
  // The position of column dofs[j] relative to the row start (absent: the one before).
  thread_local std::vector<Index> offsets;
  if (offsets.size() < n) offsets.resize(n);
  Index* offset = offsets.data();
  for (std::size_t i = 0; i < n; ++i) {
    const Index row = dofs[i];
    const Index* begin = inner + outer[row];
    const Index* end = inner + outer[row + 1];
    const Index length = static_cast<Index>(end - begin);
    // Consecutive dofs of one node share their column pattern, so offsets
    // found for the previous row are tried first; within a row, a block's
    // columns usually come sorted, so each is sought forward from the last.
    const bool same_pattern = i > 0 && row == dofs[i - 1] + 1 && length == outer[row] - outer[row - 1];
    for (std::size_t j = 0; j < n; ++j) {
      const Index column = dofs[j];
      Index at;
      if (same_pattern && offset[j] >= 0 && begin[offset[j]] == column)
        at = offset[j];
      else if (j > 0 && column > dofs[j - 1])
        at = search_forward(begin, end, offset[j - 1] + 1, column);
      else
        at = static_cast<Index>(std::lower_bound(begin, end, column) - begin);
      if (at < length && begin[at] == column) {
        offset[j] = at;
        values[outer[row] + at] += scale * block[i * n + j];
        continue;
      }
      refuse_nonzero_outside(row, column, block[i * n + j]);
      offset[j] = at - 1;
    }
  }
}

template <int W>
void SinkTarget::add_node_block(std::span<const Index> dofs, std::span<const double> block) const {
  const std::size_t n = dofs.size(), nodes = n / W;
  for (std::size_t t = 0; t < nodes; ++t) {
    const Index r = dofs[W * t];
    const Index* begin = inner + outer[r];
    const Index* end = inner + outer[r + 1];
    const Index length = static_cast<Index>(end - begin);
    Index from = 0;
    for (std::size_t s = 0; s < nodes; ++s) {
      const Index c = dofs[W * s];
      const Index at = s > 0 && c > dofs[W * (s - 1)] ? search_forward(begin, end, from, c)
                                                      : static_cast<Index>(std::lower_bound(begin, end, c) - begin);
      // Sorted, distinct columns: c and c + W - 1 W places apart hold the node's W columns. Each row of
      // the node must hold them at the same place (an MPI rank's untouched rows hold their diagonal alone).
      bool whole = at + W <= length && begin[at] == c && begin[at + W - 1] == c + W - 1;
      for (int k = 1; k < W && whole; ++k) {
        const Index* row_k = inner + outer[r + k];
        whole = outer[r + k + 1] - outer[r + k] == length && row_k[at] == c && row_k[at + W - 1] == c + W - 1;
      }
      from = whole ? at + W : at;  // the next, larger column lies at or after it
      for (int k = 0; k < W; ++k) {
        const double* in = block.data() + (W * t + k) * n + W * s;
        if (!whole) {  // a pair the pattern leaves out, or rows unlike the node's first
          add_run(r + k, c, in, W);
          continue;
        }
        double* out = values + outer[r + k] + at;
        for (int m = 0; m < W; ++m) out[m] += scale * in[m];
      }
    }
  }
}

/// Whether `dofs` are whole nodes of `w` dofs each, in order within each node.
bool whole_nodes(std::span<const Index> dofs, int w) {
  if (dofs.size() % w != 0) return false;
  for (std::size_t t = 0; t < dofs.size(); t += w) {
    if (dofs[t] % w != 0) return false;
    for (int k = 1; k < w; ++k)
      if (dofs[t + k] != dofs[t] + k) return false;
  }
  return true;
}

}  // namespace

BlockSink add_into(SparseMatrix& matrix, double scale, int dofs_per_node) {
  const SinkTarget target{matrix.outerIndexPtr(), matrix.innerIndexPtr(), matrix.valuePtr(), scale};
  return [=](std::span<const Index> dofs, std::span<const double> block) {
    if (dofs_per_node == 3 && whole_nodes(dofs, 3)) return target.add_node_block<3>(dofs, block);
    if (dofs_per_node == 2 && whole_nodes(dofs, 2)) return target.add_node_block<2>(dofs, block);
    target.add_block(dofs, block);
  };
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
