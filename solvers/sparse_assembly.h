#pragma once
// Global sparse matrices over all dofs (row-major CSR, full symmetric storage),
// filled through the body's BlockSink, and their restriction to the free dofs.
#include <Eigen/SparseCore>
#include <span>
#include <vector>

#include "core/threads_worth_waking.h"
#include "core/uninitialized_vector.h"
#include "discretization/body_capabilities.h"
#include "discretization/csr_block_sink.h"

namespace kerf {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, Index>;

/// The pattern of every block the body will write, values zero; diagonal always present.
SparseMatrix build_pattern(const DiscreteBody& body);
/// The same for any n dofs (dofs_per_node each) whose couplings `visit_couplings`
/// names; with `kept_nodes` (sorted) only their rows are whole, every other row
/// holds its diagonal alone (an MPI rank's partial matrix: its touched rows).
SparseMatrix build_pattern(int dofs_per_node, Index n,
                           const std::function<void(const CouplingVisitor&)>& visit_couplings,
                           std::span<const Index> kept_nodes = {});

/// The sink of csr_block_sink.h on the matrix's arrays.
BlockSink add_into(SparseMatrix& matrix, double scale = 1.0, int dofs_per_node = 1);

/// The matrix's arrays as a body writes into them (MatrixAssembly).
CsrView csr_view(SparseMatrix& matrix);

/// Positions of the diagonal entries in matrix.valuePtr().
std::vector<Index> diagonal_positions(const SparseMatrix& matrix);

/// The split of dofs into free and constrained, and the restriction A -> A_ff.
class FreeDofs {
 public:
  FreeDofs(Index dof_count, const std::vector<DirichletDof>& constrained);
  Index free_count() const { return static_cast<Index>(full_of_free_.size()); }
  /// -1 for a constrained dof.
  Index free_index(Index dof) const { return free_of_full_[dof]; }
  const std::vector<Index>& free_dofs() const { return full_of_free_; }

  Vector restrict_vector(const Vector& full) const;
  void add_to_full(const Vector& free, Vector& full) const;

  /// Builds the free-free pattern of `full` once; `restrict_values` then copies values.
  void prepare_matrix(const SparseMatrix& full);
  const SparseMatrix& restricted() const { return restricted_; }
  void restrict_values(const SparseMatrix& full) {
    const double* in = full.valuePtr();
    restrict_values_with([in](Index p) { return in[p]; });
  }
  /// Each restricted value as value_of(p), p its position in the full
  /// matrix's values: a combination of full matrices without forming it.
  template <class ValueOf>
  void restrict_values_with(const ValueOf& value_of) {
    double* out = restricted_.valuePtr();
    const Index* source = source_position_.data();
    const std::ptrdiff_t count = static_cast<std::ptrdiff_t>(source_position_.size());
#pragma omp parallel for schedule(static) if (worth_threads(static_cast<Index>(count / 512)))  // an item: 512 values
    for (std::ptrdiff_t k = 0; k < count; ++k) out[k] = value_of(source[k]);
  }
  /// Adds scale * diagonal[d] to the restricted matrix's diagonal at each free dof d.
  void add_to_diagonal(double scale, const Vector& diagonal);

 private:
  std::vector<Index> free_of_full_;
  std::vector<Index> full_of_free_;
  SparseMatrix restricted_;
  UninitializedVector<Index> source_position_;  // for each restricted value, its position in the full matrix
  std::vector<Index> restricted_diagonal_;  // by free dof, found at the first add_to_diagonal
};

}  // namespace kerf
