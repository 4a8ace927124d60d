#include "support/kuhn_mesh.h"

namespace kerf::testing {

Mesh kuhn_cubes(int n, double h) {
  Mesh mesh;
  const int m = n + 1;
  auto node = [m](int i, int j, int k) { return static_cast<Index>(i + m * j + m * m * k); };
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) mesh.nodes.emplace_back(i * h, j * h, k * h);
  const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& path : paths) {
          int c[3] = {i, j, k};
          mesh.cells.push_back(node(c[0], c[1], c[2]));
          for (int axis : path) {
            ++c[axis];
            mesh.cells.push_back(node(c[0], c[1], c[2]));
          }
        }
  orient_cells(mesh);
  return mesh;
}

CutPiece triangle_piece(const Vec3& a, const Vec3& b, const Vec3& c) {
  CutPiece p;
  p.corner = {a, b, c};
  const Vec3 n = (b - a).cross(c - a);
  p.normal = n.normalized();
  p.size = 0.5 * n.norm();
  p.centre = (a + b + c) / 3.0;
  return p;
}

}  // namespace kerf::testing
