#pragma once
// The linear functions of a quadratic mesh (tet10, tri6) as a subspace of its
// quadratic ones: the coarse space of p-multigrid. A linear function is given
// by its values at the cells' corners; at a mid-edge node it is the mean of
// the edge's two corners (also on curved cells: linear in the reference cell).
#include <span>

#include "geometry/mesh.h"
#include "solvers/sparse_assembly.h"

namespace kerf {

/// P (free dofs x coarse dofs), u_free = P u_coarse: the coarse dofs are the
/// free dofs of the corner nodes (every node that is a corner of some cell)
/// and of `own_nodes`, in ascending order. Such a node's free dof takes its own
/// coarse dof (weight 1), a mid-edge node's the two corners' of its edge (1/2
/// each), leaving out the constrained ones. `own_nodes` are nodes the coarse
/// level solves exactly: those of split cells, whose small fragments hold
/// soft local modes no smoother reaches. Needs a quadratic mesh (order 2)
/// whose nodes carry `dofs_per_node` dofs each, node-major.
SparseMatrix corner_prolongation(const Mesh& mesh, const FreeDofs& free, int dofs_per_node,
                                 std::span<const Index> own_nodes = {});

}  // namespace kerf
