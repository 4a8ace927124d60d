#include "geometry/lattice_cells.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace kerf {
namespace {

/// The cube's 5 tetrahedra; `at` holds its nodes by corner, bit 2 the x
/// offset, bit 1 y, bit 0 z. The central tet is on the corners whose offsets
/// sum to an even number, or to an odd one where the cube's own place is odd
/// (`odd`): either way the corners of even parity over the whole lattice.
void split_cube(const Index (&at)[8], bool odd, std::vector<Index>& cells) {
  int central[4], other[4], e = 0, o = 0;
  for (int c = 0; c < 8; ++c) {
    const bool even_sum = ((c >> 2) + ((c >> 1) & 1) + (c & 1)) % 2 == 0;
    (even_sum != odd ? central[e++] : other[o++]) = c;
  }
  for (int c : central) cells.push_back(at[c]);
  // Each other corner with its three edge neighbours (one bit away), all of them the central tet's.
  for (int c : other) {
    cells.push_back(at[c]);
    for (int bit : {4, 2, 1}) cells.push_back(at[c ^ bit]);
  }
}

}  // namespace

std::array<int, 3> lattice_intervals(int dim, const Vec3& min, const Vec3& max, double spacing) {
  std::array<int, 3> count = {0, 0, 0};
  for (int a = 0; a < dim; ++a) count[a] = std::max(1, static_cast<int>(std::lround((max[a] - min[a]) / spacing)));
  return count;
}

double lattice_cell_count(int dim, const std::array<int, 3>& intervals) {
  return dim == 3 ? 5.0 * intervals[0] * intervals[1] * intervals[2] : 2.0 * intervals[0] * intervals[1];
}

double lattice_edge_count(int dim, const std::array<int, 3>& intervals) {
  const double x = intervals[0], y = intervals[1], z = dim == 3 ? intervals[2] : 0;
  const double along = x * (y + 1) * (z + 1) + (x + 1) * y * (z + 1) + (x + 1) * (y + 1) * z;
  const double squares = x * y * (z + 1) + x * (y + 1) * z + (x + 1) * y * z;
  return along + squares;
}

Mesh lattice_cells(int dim, const Vec3& min, const Vec3& max, double spacing) {
  KERF_CHECK(dim == 2 || dim == 3, "lattice cells: dimension ", dim, ", expected 2 or 3");
  KERF_CHECK(spacing > 0.0, "lattice cells: spacing ", spacing, ", expected > 0");
  const std::array<int, 3> count = lattice_intervals(dim, min, max, spacing);
  Mesh mesh;
  mesh.dimension = dim;
  mesh.order = 1;
  const int nz = dim == 3 ? count[2] : 0;
  auto node = [&](int i, int j, int k) { return static_cast<Index>((i * (count[1] + 1) + j) * (nz + 1) + k); };
  for (int i = 0; i <= count[0]; ++i)
    for (int j = 0; j <= count[1]; ++j)
      for (int k = 0; k <= nz; ++k) {
        // Where lattice_nodes puts them, to the bit: min + index * (length / intervals).
        Vec3 p = Vec3::Zero();
        const int index[3] = {i, j, k};
        for (int a = 0; a < dim; ++a) p[a] = min[a] + index[a] * ((max[a] - min[a]) / count[a]);
        mesh.nodes.push_back(p);
      }
  for (int i = 0; i < count[0]; ++i)
    for (int j = 0; j < count[1]; ++j) {
      if (dim == 2) {
        // The diagonal joins the square's corners of even i + j.
        const Index a = node(i, j, 0), b = node(i + 1, j, 0), c = node(i + 1, j + 1, 0), d = node(i, j + 1, 0);
        if ((i + j) % 2 == 0) mesh.cells.insert(mesh.cells.end(), {a, b, c, a, c, d});
        else mesh.cells.insert(mesh.cells.end(), {a, b, d, b, c, d});
        continue;
      }
      for (int k = 0; k < nz; ++k) {
        Index at[8];
        for (int c = 0; c < 8; ++c) at[c] = node(i + (c >> 2), j + ((c >> 1) & 1), k + (c & 1));
        split_cube(at, (i + j + k) % 2 != 0, mesh.cells);
      }
    }
  orient_cells(mesh);
  return mesh;
}

}  // namespace kerf
