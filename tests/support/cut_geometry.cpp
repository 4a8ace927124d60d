#include "support/cut_geometry.h"

#include <numeric>

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

namespace {
/// The plane n . x = d over y in [y0, y1] (3D: and z in [z0, z1]; 2D: the
/// line at z = 0), its pieces' normal along n.
std::vector<CutPiece> plane_pieces(int dimension, const Vec3& n, double d, double y0, double y1, double z0, double z1) {
  const auto at = [&](double y, double z) { return Vec3((d - n.y() * y - n.z() * z) / n.x(), y, z); };
  std::vector<CutPiece> pieces;
  if (dimension == 2) {
    CutPiece line;
    line.corner = {at(y0, 0), at(y1, 0), Vec3::Zero()};
    const Vec3 t = line.corner[1] - line.corner[0];
    line.normal = Vec3(-t.y(), t.x(), 0).normalized();
    line.size = t.norm();
    line.centre = 0.5 * (line.corner[0] + line.corner[1]);
    pieces.push_back(line);
  } else {
    pieces = {triangle_piece(at(y0, z0), at(y1, z0), at(y1, z1)), triangle_piece(at(y0, z0), at(y1, z1), at(y0, z1))};
  }
  if (pieces[0].normal.dot(n) < 0)
    for (CutPiece& p : pieces) {
      std::swap(p.corner[0], p.corner[dimension - 1]);
      p.normal = -p.normal;
    }
  return pieces;
}
}  // namespace

std::vector<CutPiece> plane_cut(int dimension, const Vec3& n, double d, double reach) {
  return plane_pieces(dimension, n, d, -reach, 1 + reach, -reach, 1 + reach);
}

std::vector<CutPiece> plane_cut_above(int dimension, const Vec3& n, double d, double front) {
  return dimension == 2 ? plane_pieces(2, n, d, front, 1.5, 0, 0) : plane_pieces(3, n, d, -0.5, 1.5, front, 1.5);
}

std::vector<int> node_pieces(const Mesh& mesh) {
  std::vector<Index> root(mesh.node_count());
  std::iota(root.begin(), root.end(), 0);
  const auto find = [&](Index a) {
    while (root[a] != a) a = root[a] = root[root[a]];
    return a;
  };
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (Index n : mesh.cell(c)) {
      const Index a = find(n), b = find(mesh.cell(c)[0]);
      root[std::max(a, b)] = std::min(a, b);
    }
  std::vector<char> used(mesh.node_count(), 0);
  for (Index n : mesh.cells) used[n] = 1;
  std::vector<int> label(mesh.node_count(), -1), of_root(mesh.node_count(), -1);
  int count = 0;
  for (Index n = 0; n < mesh.node_count(); ++n) {
    if (!used[n]) continue;
    int& l = of_root[find(n)];
    if (l < 0) l = count++;
    label[n] = l;
  }
  return label;
}

}  // namespace kerf::testing
