#include "discretization/meshless/dual_cell_boundaries.h"

#include <cmath>

#include "geometry/boundary_facets.h"

namespace kerf {
namespace {

using Parts = std::vector<std::vector<CellPart>>;

/// Adds the part to cell `a` and, with the normal reversed, to cell `b` (b < 0: none).
void add(Parts& cells, Index a, Index b, CellPart part) {
  cells[a].push_back(part);
  if (b >= 0) part.weighted_normal = -part.weighted_normal, cells[b].push_back(part);
}

Vec3 perpendicular(const Vec3& d) { return Vec3(d.y(), -d.x(), 0.0); }

/// The segment p -> q (2D) with its normal turned to point along `towards`.
void add_segment(Parts& cells, Index a, Index b, const Vec3& p, const Vec3& q, const Vec3& towards) {
  Vec3 normal = perpendicular(q - p);
  if (normal.dot(towards) < 0.0) normal = -normal;
  add(cells, a, b, {{p, q, Vec3::Zero()}, 2, normal});
}

/// The triangle (p0, p1, p2) (3D) with its area vector turned to point along `towards`.
void add_triangle(Parts& cells, Index a, Index b, const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& towards) {
  Vec3 area = 0.5 * (p1 - p0).cross(p2 - p0);
  if (area.dot(towards) < 0.0) area = -area;
  add(cells, a, b, {{p0, p1, p2}, 3, area});
}

/// The dual segments (edge midpoint to centroid) of one triangle, from a's cell to b's.
void triangle_cells(const Mesh& mesh, Index c, Parts& cells) {
  auto n = mesh.cell(c);
  const Vec3 g = (mesh.nodes[n[0]] + mesh.nodes[n[1]] + mesh.nodes[n[2]]) / 3.0;
  for (auto [a, b] : {std::array<int, 2>{0, 1}, {1, 2}, {0, 2}}) {
    const Vec3 &pa = mesh.nodes[n[a]], &pb = mesh.nodes[n[b]];
    add_segment(cells, n[a], n[b], 0.5 * (pa + pb), g, pb - pa);
  }
}

/// The dual quadrilaterals (edge midpoint, face centroid, centroid, face centroid) of one tet.
void tet_cells(const Mesh& mesh, Index c, Parts& cells) {
  auto n = mesh.cell(c);
  const Vec3* p[4] = {&mesh.nodes[n[0]], &mesh.nodes[n[1]], &mesh.nodes[n[2]], &mesh.nodes[n[3]]};
  const Vec3 g = (*p[0] + *p[1] + *p[2] + *p[3]) / 4.0;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) {
      int others[2], k = 0;
      for (int o = 0; o < 4; ++o)
        if (o != a && o != b) others[k++] = o;
      const Vec3 m = 0.5 * (*p[a] + *p[b]);
      const Vec3 f1 = (*p[a] + *p[b] + *p[others[0]]) / 3.0, f2 = (*p[a] + *p[b] + *p[others[1]]) / 3.0;
      const Vec3 towards = *p[b] - *p[a];
      add_triangle(cells, n[a], n[b], m, f1, g, towards);
      add_triangle(cells, n[a], n[b], m, g, f2, towards);
    }
}

/// Each corner's part of the boundary facets, outward.
void boundary_cells(const Mesh& mesh, Parts& cells) {
  const BoundaryFacets facets = boundary_facets(mesh);
  const int dim = mesh.dimension;
  for (Index f = 0; f < facets.count(); ++f) {
    auto v = facets.facet(f);
    auto cell = mesh.cell(facets.cell[f]);
    Vec3 inside = Vec3::Zero(), centre = Vec3::Zero();
    for (int a = 0; a <= dim; ++a) inside += mesh.nodes[cell[a]] / (dim + 1);
    for (int a = 0; a < dim; ++a) centre += mesh.nodes[v[a]] / dim;
    const Vec3 out = centre - inside;
    if (dim == 2) {
      add_segment(cells, v[0], -1, mesh.nodes[v[0]], centre, out);
      add_segment(cells, v[1], -1, centre, mesh.nodes[v[1]], out);
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      const Vec3& pa = mesh.nodes[v[a]];
      const Vec3 m1 = 0.5 * (pa + mesh.nodes[v[(a + 1) % 3]]), m2 = 0.5 * (pa + mesh.nodes[v[(a + 2) % 3]]);
      add_triangle(cells, v[a], -1, pa, m1, centre, out);
      add_triangle(cells, v[a], -1, pa, centre, m2, out);
    }
  }
}

/// Does the segment a-b cross a piece of one of the cuts present?
bool crosses_cuts(const CutWeights& cuts, const Vec3& a, const Vec3& b) {
  for (Index c = 0; c < cuts.cut_count(); ++c)
    if (segment_crosses_cut(cuts.surface(c), 0, cuts.pieces(c), a, b)) return true;
  return false;
}

}  // namespace

std::vector<std::vector<CellPart>> dual_cell_parts(const Mesh& mesh) {
  Parts cells(mesh.node_count());
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.dimension == 2)
      triangle_cells(mesh, c, cells);
    else
      tet_cells(mesh, c, cells);
  }
  boundary_cells(mesh, cells);
  return cells;
}

void sample_part(const CellPart& part, const CutWeights* cuts, int depth, std::vector<CellSample>& out) {
  const auto& p = part.corner;
  if (part.corners == 2) {
    if (cuts && depth > 0 && crosses_cuts(*cuts, p[0], p[1])) {
      const Vec3 m = 0.5 * (p[0] + p[1]);
      sample_part({{p[0], m, Vec3::Zero()}, 2, 0.5 * part.weighted_normal}, cuts, depth - 1, out);
      sample_part({{m, p[1], Vec3::Zero()}, 2, 0.5 * part.weighted_normal}, cuts, depth - 1, out);
      return;
    }
    const double offset = 0.5 / std::sqrt(3.0);
    for (double t : {0.5 - offset, 0.5 + offset}) out.push_back({p[0] + t * (p[1] - p[0]), 0.5 * part.weighted_normal});
    return;
  }
  if (cuts && depth > 0 &&
      (crosses_cuts(*cuts, p[0], p[1]) || crosses_cuts(*cuts, p[1], p[2]) || crosses_cuts(*cuts, p[2], p[0]))) {
    const Vec3 m01 = 0.5 * (p[0] + p[1]), m12 = 0.5 * (p[1] + p[2]), m20 = 0.5 * (p[2] + p[0]);
    const Vec3 quarter = 0.25 * part.weighted_normal;
    for (const auto& t : {std::array<Vec3, 3>{p[0], m01, m20}, {m01, p[1], m12}, {m20, m12, p[2]}, {m01, m12, m20}})
      sample_part({t, 3, quarter}, cuts, depth - 1, out);
    return;
  }
  out.push_back({(p[0] + p[1] + p[2]) / 3.0, part.weighted_normal});
}

}  // namespace kerf
