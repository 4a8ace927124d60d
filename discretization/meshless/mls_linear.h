#pragma once
// The MLS shape functions every nodal table, EFG point and cut update asks for
// most: a linear basis, values and gradients, no second derivatives. Written
// for that case alone (the general mls_shape_functions serves the rest): one
// pass over the nodes accumulates the moment matrix and its derivatives (upper
// triangles), a Cholesky factor solves, and the condition number comes from
// the eigenvalues by Jacobi rotations (no eigenvectors: only the general
// path's solve needs them). The same shape functions and condition numbers as
// mls_shape_functions, to the system's condition times round-off (tested).
#include <span>

#include "discretization/meshless/mls_shape.h"

namespace kerf {

/// Linear-basis shape functions at x (dimension `dim`, 2 or 3) of `nodes`
/// with weights `w`; `scale` (m) scales the basis. Same contract as
/// mls_shape_functions: false when the moment matrix cannot be inverted,
/// out.condition its condition number; out.hessian is left empty.
bool mls_linear_shape_functions(int dim, const Vec3& x, std::span<const Vec3> nodes,
                                std::span<const WeightWithGradient> w, double scale, MlsShape& out);

/// The eigenvalues of a symmetric m x m matrix (m <= 4, row-major, full,
/// entries below 1e150 in size), ascending, by Jacobi rotations; `a` is overwritten.
void symmetric_eigenvalues(int m, double (&a)[4][4], double (&lambda)[4]);

}  // namespace kerf
