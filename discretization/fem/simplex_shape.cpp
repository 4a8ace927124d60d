#include "discretization/fem/simplex_shape.h"

#include <array>

namespace kerf {
namespace {

// Corner pairs of the mid-edge nodes, in gmsh order, per dimension.
constexpr std::array<std::array<int, 2>, 1> line_edges{{{0, 1}}};
constexpr std::array<std::array<int, 2>, 3> triangle_edges{{{0, 1}, {1, 2}, {0, 2}}};
constexpr std::array<std::array<int, 2>, 6> tetrahedron_edges{{{0, 1}, {1, 2}, {0, 2}, {0, 3}, {2, 3}, {1, 3}}};

const std::array<int, 2>* edges(int dim) {
  return dim == 1 ? line_edges.data() : dim == 2 ? triangle_edges.data() : tetrahedron_edges.data();
}
int edge_count(int dim) { return dim == 1 ? 1 : dim == 2 ? 3 : 6; }

void barycentric(int dim, const Vec3& xi, double* L) {
  L[0] = 1.0;
  for (int k = 0; k < dim; ++k) {
    L[k + 1] = xi[k];
    L[0] -= xi[k];
  }
}

// dL_c / dxi_k
double barycentric_derivative(int c, int k) { return c == 0 ? -1.0 : (c == k + 1 ? 1.0 : 0.0); }

}  // namespace

int simplex_node_count(int dim, int order) { return dim + 1 + (order == 2 ? edge_count(dim) : 0); }

void simplex_shape_values(int dim, int order, const Vec3& xi, double* N) {
  double L[4];
  barycentric(dim, xi, L);
  if (order == 1) {
    for (int a = 0; a <= dim; ++a) N[a] = L[a];
    return;
  }
  for (int a = 0; a <= dim; ++a) N[a] = L[a] * (2.0 * L[a] - 1.0);
  const auto* e = edges(dim);
  for (int m = 0; m < edge_count(dim); ++m) N[dim + 1 + m] = 4.0 * L[e[m][0]] * L[e[m][1]];
}

void simplex_shape_gradients(int dim, int order, const Vec3& xi, double* dN) {
  double L[4];
  barycentric(dim, xi, L);
  for (int a = 0; a <= dim; ++a)
    for (int k = 0; k < dim; ++k)
      dN[a * dim + k] = (order == 1 ? 1.0 : 4.0 * L[a] - 1.0) * barycentric_derivative(a, k);
  if (order == 1) return;
  const auto* e = edges(dim);
  for (int m = 0; m < edge_count(dim); ++m) {
    int p = e[m][0], q = e[m][1];
    for (int k = 0; k < dim; ++k)
      dN[(dim + 1 + m) * dim + k] =
          4.0 * (L[q] * barycentric_derivative(p, k) + L[p] * barycentric_derivative(q, k));
  }
}

Vec3 simplex_node_position(int dim, int order, int a) {
  auto corner = [dim](int c) {
    Vec3 x = Vec3::Zero();
    if (c > 0) x[c - 1] = 1.0;
    (void)dim;
    return x;
  };
  if (a <= dim) return corner(a);
  const auto* e = edges(dim);
  int m = a - dim - 1;
  return 0.5 * (corner(e[m][0]) + corner(e[m][1]));
}

}  // namespace kerf
