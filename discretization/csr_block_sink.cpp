#include "discretization/csr_block_sink.h"

#include <algorithm>
#include <vector>

#include "core/check.h"

namespace kerf {

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

BlockSink add_into(const CsrView& matrix, double scale, int dofs_per_node) {
  const SinkTarget target{matrix.outer, matrix.inner, matrix.values, scale};
  return [=](std::span<const Index> dofs, std::span<const double> block) {
    if (dofs_per_node == 3 && whole_nodes(dofs, 3)) return target.add_node_block<3>(dofs, block);
    if (dofs_per_node == 2 && whole_nodes(dofs, 2)) return target.add_node_block<2>(dofs, block);
    target.add_block(dofs, block);
  };
}

}  // namespace kerf
