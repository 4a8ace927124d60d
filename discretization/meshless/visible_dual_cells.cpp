#include "discretization/meshless/visible_dual_cells.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace kerf {
namespace {

/// Does the segment from corner a to x cross `piece`? `tie` (m): a point
/// closer than it to the piece's plane lies on it, and counts as the + side.
bool crosses(const CutPiece& piece, int dim, const Vec3& a, const Vec3& x, double tie) {
  const Vec3& o = piece.corner[0];
  double sa = piece.normal.dot(a - o), sx = piece.normal.dot(x - o);
  if (std::abs(sa) <= tie) sa = 0.0;
  if (std::abs(sx) <= tie) sx = 0.0;
  if ((sa >= 0.0) == (sx >= 0.0)) return false;
  const Vec3 p = a + sa / (sa - sx) * (x - a);  // on the plane (a itself when a lies on it)
  if (dim == 2) {
    const Vec3 t = piece.corner[1] - o;
    const double along = (p - o).dot(t) / t.squaredNorm();
    return along >= -tie / t.norm() && along <= 1.0 + tie / t.norm();
  }
  for (int k = 0; k < 3; ++k) {  // inside the triangle, its edges included
    const Vec3& v = piece.corner[k];
    const Vec3 edge = piece.corner[(k + 1) % 3] - v;
    if (piece.normal.dot(edge.cross(p - v)) < -tie * edge.norm()) return false;
  }
  return true;
}

/// One cell as the refinement sees it: its corners, the pieces near it, and
/// what turns a point into barycentric coordinates.
struct CellView {
  int dim = 3;
  std::array<Vec3, 4> corner;
  std::span<const CutPiece* const> pieces;
  Eigen::Matrix3d to_barycentric;  // lambda_1.. = M (x - corner 0)
  double tie = 0.0;

  bool sees(int a, const Vec3& x) const {
    for (const CutPiece* piece : pieces)
      if (crosses(*piece, dim, corner[a], x, tie)) return false;
    return true;
  }
  /// The corner x's volume goes to: `owner` when it sees x, else the seeing
  /// corner with the largest barycentric coordinate (`owner` when none sees it).
  int taker(int owner, const Vec3& x) const {
    if (sees(owner, x)) return owner;
    const Vec3 l = to_barycentric * (x - corner[0]);
    std::array<double, 4> lambda{1.0 - l[0] - l[1] - (dim == 3 ? l[2] : 0.0), l[0], l[1], l[2]};
    int best = owner;
    double largest = -1.0;
    for (int b = 0; b <= dim; ++b)
      if (b != owner && lambda[b] > largest && sees(b, x)) best = b, largest = lambda[b];
    return best;
  }
};

using Simplex = std::array<Vec3, 4>;

/// The 2^dim children of equal measure (regular refinement; Bey's in 3D),
/// as corners of the parent's points: its corners 0..dim, then its edges'
/// midpoints in the order of mid_edge_corners (2D: 01 12 02; 3D: 01 12 02 03 23 13).
constexpr std::array<std::array<int, 3>, 4> triangle_children{{{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}}};
constexpr std::array<std::array<int, 4>, 8> tetrahedron_children{{{0, 4, 6, 7},
                                                                  {4, 1, 5, 9},
                                                                  {6, 5, 2, 8},
                                                                  {7, 9, 8, 3},
                                                                  {4, 6, 7, 9},
                                                                  {4, 6, 5, 9},
                                                                  {6, 7, 9, 8},
                                                                  {6, 5, 9, 8}}};

/// Gives the simplex `s` (a part of corner `owner`'s dual cell), whose
/// corners go to `takers`, to the corners that take it, refining where its
/// corners' takers differ (each new point's taker found once).
void hand_over(const CellView& cell, int owner, const Simplex& s, const std::array<int, 4>& takers, double measure,
               int levels, VisibleDualCells::CellShares& shares) {
  const int n = cell.dim + 1;
  Vec3 centre = Vec3::Zero();
  for (int k = 0; k < n; ++k) centre += s[k] / n;
  const int at_centre = cell.taker(owner, centre);
  bool uniform = true;
  for (int k = 0; k < n && uniform; ++k) uniform = takers[k] == at_centre;
  if (uniform || levels == 0) {
    Simplex y;
    for (int k = 0; k < n; ++k) y[k] = s[k] - cell.corner[at_centre];
    shares[at_centre].volume += measure;
    shares[at_centre].first += measure * centre;
    shares[at_centre].moment += simplex_second_moment(std::span<const Vec3>(y.data(), n), measure);
    return;
  }
  std::array<Vec3, 10> point;
  std::array<int, 10> taker{};
  for (int k = 0; k < n; ++k) point[k] = s[k], taker[k] = takers[k];
  const auto edges = mid_edge_corners(cell.dim);
  for (std::size_t e = 0; e < edges.size(); ++e) {
    point[n + e] = 0.5 * (s[edges[e][0]] + s[edges[e][1]]);
    taker[n + e] = cell.taker(owner, point[n + e]);
  }
  auto refine = [&](const auto& corners) {
    Simplex child{};
    std::array<int, 4> child_takers{};
    for (int k = 0; k < n; ++k) child[k] = point[corners[k]], child_takers[k] = taker[corners[k]];
    hand_over(cell, owner, child, child_takers, measure / (cell.dim == 3 ? 8 : 4), levels - 1, shares);
  };
  if (cell.dim == 3)
    for (const auto& c : tetrahedron_children) refine(c);
  else
    for (const auto& c : triangle_children) refine(c);
}

bool boxes_meet(const Vec3& lo, const Vec3& hi, const CutPiece& piece, int dim, double pad) {
  for (int i = 0; i < 3; ++i) {
    double plo = piece.corner[0][i], phi = plo;
    for (int k = 1; k < dim; ++k) plo = std::min(plo, piece.corner[k][i]), phi = std::max(phi, piece.corner[k][i]);
    if (phi < lo[i] - pad || plo > hi[i] + pad) return false;
  }
  return true;
}

}  // namespace

// Separating axes of two convex bodies: the normals of both and, in 3D, the edges' cross products.
bool piece_meets_cell(const CutPiece& piece, const Mesh& cells, Index c, double tie) {
  const int dim = cells.dimension;
  auto n = cells.cell(c);
  std::array<Vec3, 4> cell{};
  for (int a = 0; a <= dim; ++a) cell[a] = cells.nodes[n[a]];
  const std::span<const Vec3> A(piece.corner.data(), dim), B(cell.data(), dim + 1);
  auto separated = [&](const Vec3& axis) {
    if (axis.squaredNorm() < 1e-30) return false;
    double alo = 1e300, ahi = -1e300, blo = 1e300, bhi = -1e300;
    for (const Vec3& p : A) alo = std::min(alo, axis.dot(p)), ahi = std::max(ahi, axis.dot(p));
    for (const Vec3& p : B) blo = std::min(blo, axis.dot(p)), bhi = std::max(bhi, axis.dot(p));
    const double pad = tie * axis.norm();
    return ahi < blo - pad || bhi < alo - pad;
  };
  std::vector<Vec3> edges_a, edges_b;
  for (std::size_t i = 0; i < A.size(); ++i)
    for (std::size_t j = i + 1; j < A.size(); ++j) edges_a.push_back(A[j] - A[i]);
  for (std::size_t i = 0; i < B.size(); ++i)
    for (std::size_t j = i + 1; j < B.size(); ++j) edges_b.push_back(B[j] - B[i]);
  if (dim == 2) {  // the edges' normals in the plane
    for (const auto* edges : {&edges_a, &edges_b})
      for (const Vec3& e : *edges)
        if (separated(Vec3(-e.y(), e.x(), 0.0))) return false;
    return true;
  }
  if (separated(piece.normal)) return false;
  for (int f = 0; f < 4; ++f)  // the cell's faces: the face opposite corner f
    if (separated((B[(f + 2) % 4] - B[(f + 1) % 4]).cross(B[(f + 3) % 4] - B[(f + 1) % 4]))) return false;
  for (const Vec3& ea : edges_a)
    for (const Vec3& eb : edges_b)
      if (separated(ea.cross(eb))) return false;
  return true;
}

VisibleDualCells::VisibleDualCells(const Mesh& cells, int depth)
    : depth_(depth), volume_(dual_cell_volumes(cells)), moment_(dual_cell_second_moments(cells)) {}

// Without pieces, every part stays with its corner: the plain dual cell's shares.
VisibleDualCells::CellShares VisibleDualCells::visible_parts(const Mesh& cells, Index c,
                                                             std::span<const CutPiece* const> pieces) const {
  const int dim = cells.dimension;
  auto n = cells.cell(c);
  CellView view;
  view.dim = dim;
  view.pieces = pieces;
  double size = 0.0;
  Eigen::Matrix3d edges = Eigen::Matrix3d::Identity();
  for (int a = 0; a <= dim; ++a) view.corner[a] = cells.nodes[n[a]];
  for (int a = 1; a <= dim; ++a) {
    edges.col(a - 1) = view.corner[a] - view.corner[0];
    size = std::max(size, edges.col(a - 1).norm());
  }
  if (dim == 2) edges(2, 2) = 1.0;  // z is not a direction of a 2D cell
  view.to_barycentric = edges.inverse();
  view.tie = 1e-9 * size;
  CellShares shares;
  for_each_barycentric_piece(cells, c, [&](int a, std::span<const Vec3> vertices, double measure) {
    Simplex s{};
    std::array<int, 4> takers{};
    for (std::size_t k = 0; k < vertices.size(); ++k) s[k] = vertices[k], takers[k] = view.taker(a, s[k]);
    hand_over(view, a, s, takers, measure, depth_, shares);
  });
  return shares;
}

VisibleDualCells::CellShares VisibleDualCells::shares(const Mesh& cells, Index c) const {
  const auto split = split_.find(c);
  return split != split_.end() ? split->second : visible_parts(cells, c, {});
}

std::vector<Index> VisibleDualCells::split_cells() const {
  std::vector<Index> out;
  out.reserve(split_.size());
  for (const auto& [c, shares] : split_) out.push_back(c);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Index> VisibleDualCells::update(const Mesh& cells, std::span<const Index> near,
                                            std::span<const CutPiece> pieces) {
  const int dim = cells.dimension;
  std::vector<Index> changed;
  std::vector<const CutPiece*> local;
  for (Index c : near) {
    auto n = cells.cell(c);
    Vec3 lo = cells.nodes[n[0]], hi = lo;
    for (int a = 1; a <= dim; ++a) lo = lo.cwiseMin(cells.nodes[n[a]]), hi = hi.cwiseMax(cells.nodes[n[a]]);
    local.clear();
    const double tie = 1e-9 * (hi - lo).norm();
    for (const CutPiece& piece : pieces)
      if (boxes_meet(lo, hi, piece, dim, tie) && piece_meets_cell(piece, cells, c, tie)) local.push_back(&piece);
    const auto before = split_.find(c);
    if (local.empty() && before == split_.end()) continue;
    const CellShares old = before != split_.end() ? before->second : visible_parts(cells, c, {});
    const CellShares now = visible_parts(cells, c, local);
    bool differs = false;
    for (int a = 0; a <= dim; ++a) {
      const double moved = now[a].volume - old[a].volume;
      if (moved == 0.0) continue;
      volume_[n[a]] += moved;
      moment_[n[a]] += now[a].moment - old[a].moment;
      changed.push_back(n[a]);
      differs = true;
    }
    if (differs)
      split_[c] = now;
    else if (local.empty())
      split_.erase(c);
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  return changed;
}

}  // namespace kerf
