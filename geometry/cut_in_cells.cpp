#include "geometry/cut_in_cells.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"

namespace kerf {
namespace {

/// A half-space n . x >= offset (n: the inward normal of a cell's face or edge).
struct HalfSpace {
  Vec3 normal;
  double offset;
};

/// The half-spaces whose intersection is straight cell c (3D: 4 faces; 2D: 3 edges).
int cell_half_spaces(const Mesh& mesh, Index c, HalfSpace* out) {
  auto n = mesh.cell(c);
  const int corners = mesh.dimension + 1;
  for (int k = 0; k < corners; ++k) {
    // The face (edge) opposite corner k, its normal turned towards corner k.
    Vec3 p[3];
    for (int j = 0, m = 0; j < corners; ++j)
      if (j != k) p[m++] = mesh.nodes[n[j]];
    Vec3 normal = mesh.dimension == 3 ? Vec3((p[1] - p[0]).cross(p[2] - p[0]))
                                      : Vec3(-(p[1] - p[0]).y(), (p[1] - p[0]).x(), 0.0);
    normal.normalize();
    if (normal.dot(mesh.nodes[n[k]] - p[0]) < 0.0) normal = -normal;
    out[k] = {normal, normal.dot(p[0])};
  }
  return corners;
}

/// Clips a convex polygon (3D, in order) or a segment (2D, open: 2 points)
/// to the half-space, deciding each point as if moved by `shift` (m) along
/// `towards` (the piece's normal).
void clip(std::vector<Vec3>& polygon, bool closed, const HalfSpace& h, const Vec3& towards, double shift,
          std::vector<Vec3>& scratch) {
  const double lift = shift * h.normal.dot(towards);
  auto distance = [&](const Vec3& x) { return h.normal.dot(x) - h.offset + lift; };
  scratch.clear();
  const std::size_t count = polygon.size();
  const std::size_t edges = closed ? count : count - 1;
  if (!closed && count == 2) {
    const double da = distance(polygon[0]), db = distance(polygon[1]);
    if (da < 0.0 && db < 0.0) return polygon.clear();
    if (da >= 0.0 && db >= 0.0) return;
    const Vec3 cross = polygon[0] + (da / (da - db)) * (polygon[1] - polygon[0]);
    (da < 0.0 ? polygon[0] : polygon[1]) = cross;
    return;
  }
  for (std::size_t i = 0; i < edges; ++i) {
    const Vec3 &a = polygon[i], &b = polygon[(i + 1) % count];
    const double da = distance(a), db = distance(b);
    if (da >= 0.0) scratch.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) scratch.push_back(a + (da / (da - db)) * (b - a));
  }
  polygon.swap(scratch);
}

double polygon_area(const std::vector<Vec3>& p) {
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 1; i + 1 < p.size(); ++i) sum += (p[i] - p[0]).cross(p[i + 1] - p[0]);
  return 0.5 * sum.norm();
}

}  // namespace

NodeCells node_cells(const Mesh& mesh) {
  NodeCells out;
  const int corners = mesh.dimension + 1;
  std::vector<Index> count(mesh.node_count() + 1, 0);
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (int k = 0; k < corners; ++k) ++count[mesh.cell(c)[k] + 1];
  for (Index i = 0; i < mesh.node_count(); ++i) count[i + 1] += count[i];
  out.start = count;
  out.cells.resize(count.back());
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (int k = 0; k < corners; ++k) out.cells[count[mesh.cell(c)[k]]++] = c;
  return out;
}

std::vector<Index> cells_near(const NodeCells& around, std::span<const Index> near_nodes) {
  std::vector<Index> cells;
  for (Index n : near_nodes)
    cells.insert(cells.end(), around.cells.begin() + around.start[n], around.cells.begin() + around.start[n + 1]);
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

std::vector<CutPart> cut_parts(const Mesh& mesh, std::span<const Index> cells, const CutPiece& piece, double tie) {
  KERF_CHECK(mesh.order == 1, "internal: cut parts need a linear mesh");
  const int dim = mesh.dimension;
  std::vector<CutPart> parts;
  std::vector<Vec3> polygon, scratch;
  HalfSpace faces[4];
  for (Index c : cells) {
    if (dim == 3)
      polygon.assign(piece.corner.begin(), piece.corner.end());
    else
      polygon.assign(piece.corner.begin(), piece.corner.begin() + 2);
    const int count = cell_half_spaces(mesh, c, faces);
    for (int k = 0; k < count && !polygon.empty(); ++k) clip(polygon, dim == 3, faces[k], piece.normal, tie, scratch);
    const double measure = dim == 3 ? (polygon.size() >= 3 ? polygon_area(polygon) : 0.0)
                                    : (polygon.size() == 2 ? (polygon[1] - polygon[0]).norm() : 0.0);
    if (measure > 0.0) parts.push_back({c, polygon});
  }
  return parts;
}

void part_quadrature(const CutPart& part, int dimension, PartPoints& out) {
  out.position.clear();
  out.weight.clear();
  const auto& p = part.corners;
  if (dimension == 2) {
    const double offset = 0.5 / std::sqrt(3.0), half = 0.5 * (p[1] - p[0]).norm();
    for (double t : {0.5 - offset, 0.5 + offset}) {
      out.position.push_back(p[0] + t * (p[1] - p[0]));
      out.weight.push_back(half);
    }
    return;
  }
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const Vec3 &a = p[0], &b = p[i], &c = p[i + 1];
    const double third = 0.5 * (b - a).cross(c - a).norm() / 3.0;
    if (third == 0.0) continue;
    for (const auto& [wa, wb, wc] : {std::array<double, 3>{2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6},
                                     {1.0 / 6, 1.0 / 6, 2.0 / 3}}) {
      out.position.push_back(wa * a + wb * b + wc * c);
      out.weight.push_back(third);
    }
  }
}

}  // namespace kerf
