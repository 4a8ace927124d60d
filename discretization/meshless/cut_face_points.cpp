#include "discretization/meshless/cut_face_points.h"

#include <algorithm>
#include <cmath>

namespace kerf {
namespace {

/// The corner of the located cell whose barycentric coordinate is the largest:
/// the node whose dual cell holds x (-1 outside the cells).
Index owner(const Mesh& mesh, const CellLocator& locator, const Vec3& x) {
  const auto at = locator.locate(mesh, x, 0.0);
  if (!at) return -1;
  const int dim = mesh.dimension;
  double lambda[4] = {1.0, 0.0, 0.0, 0.0};
  for (int k = 0; k < dim; ++k) lambda[k + 1] = at->local[k], lambda[0] -= at->local[k];
  return mesh.cell(at->cell)[std::max_element(lambda, lambda + dim + 1) - lambda];
}

}  // namespace

CutPoints::CutPoints(const Mesh& mesh, const CellLocator& locator)
    : mesh_(mesh), locator_(locator), box_(bounding_box(mesh)) {
  const double margin = 1e-9 * (box_[1] - box_[0]).norm();
  box_[0].array() -= margin, box_[1].array() += margin;
}

void CutPoints::of_piece(const CutPiece& piece, int dim, double length, std::vector<CutPoint>& out) {
  out.clear();
  const Vec3 &c0 = piece.corner[0], &c1 = piece.corner[1], &c2 = piece.corner[2];
  if (dim == 2) {
    const int n = std::max(1, static_cast<int>(std::ceil((c1 - c0).norm() / length)));
    for (int i = 0; i < n; ++i)
      segment(c0 + (double(i) / n) * (c1 - c0), c0 + (double(i + 1) / n) * (c1 - c0), 40, out);
    return;
  }
  const double longest = std::max({(c1 - c0).norm(), (c2 - c1).norm(), (c0 - c2).norm()});
  const int n = std::max(1, static_cast<int>(std::ceil(longest / length)));
  auto at = [&](int i, int j) { return Vec3(c0 + (double(i) / n) * (c1 - c0) + (double(j) / n) * (c2 - c0)); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      triangle(at(i, j), at(i + 1, j), at(i, j + 1), 5, out);
      if (i + j < n - 1) triangle(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), 5, out);
    }
}

/// Points off the mesh's box are rejected at once (the locator would search every cell).
Index CutPoints::cell_of(const Vec3& x) const {
  for (int k = 0; k < mesh_.dimension; ++k)
    if (x[k] < box_[0][k] || x[k] > box_[1][k]) return -1;
  return owner(mesh_, locator_, x);
}

void CutPoints::emit(const Vec3& x, double weight, std::vector<CutPoint>& out) const {
  const Index cell = cell_of(x);
  if (cell >= 0) out.push_back({x, weight, cell});  // parts beyond the body are dropped
}

void CutPoints::segment(const Vec3& a, const Vec3& b, int depth, std::vector<CutPoint>& out) const {
  if (depth > 0 && cell_of(a) != cell_of(b)) {
    const Vec3 m = 0.5 * (a + b);
    segment(a, m, depth - 1, out);
    segment(m, b, depth - 1, out);
    return;
  }
  const double offset = 0.5 / std::sqrt(3.0), w = 0.5 * (b - a).norm();
  for (double t : {0.5 - offset, 0.5 + offset}) emit(a + t * (b - a), w, out);
}

void CutPoints::triangle(const Vec3& a, const Vec3& b, const Vec3& c, int depth, std::vector<CutPoint>& out) const {
  const Index ca = cell_of(a);
  if (depth > 0 && (cell_of(b) != ca || cell_of(c) != ca)) {
    const Vec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca_ = 0.5 * (c + a);
    triangle(a, ab, ca_, depth - 1, out);
    triangle(ab, b, bc, depth - 1, out);
    triangle(ca_, bc, c, depth - 1, out);
    triangle(ab, bc, ca_, depth - 1, out);
    return;
  }
  emit((a + b + c) / 3.0, 0.5 * (b - a).cross(c - a).norm(), out);
}

}  // namespace kerf
