#pragma once
// Lagrange shape functions on the reference simplex of dimension 1, 2 or 3,
// order 1 or 2, in gmsh node order (corners, then mid-edge nodes; see geometry/mesh.h).
// Reference coordinates xi = (xi, eta, zeta); barycentric L0 = 1 - sum(xi), L_k = xi_{k-1}.
#include "core/types.h"

namespace kerf {

/// Number of nodes: dim + 1 corners, plus one per edge for order 2.
int simplex_node_count(int dim, int order);

/// N (count) at xi.
void simplex_shape_values(int dim, int order, const Vec3& xi, double* N);

/// dN/dxi at xi, row-major count x dim.
void simplex_shape_gradients(int dim, int order, const Vec3& xi, double* dN);

/// Reference coordinates of node a (for tests and point location).
Vec3 simplex_node_position(int dim, int order, int a);

}  // namespace kerf
