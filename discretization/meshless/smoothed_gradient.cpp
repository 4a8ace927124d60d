#include "discretization/meshless/smoothed_gradient.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "geometry/boundary_facets.h"
#include "geometry/point_location.h"

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

/// Samples of one part: two Gauss points (segment) or the centroid (triangle).
/// With cuts, a part that a cut crosses is halved (segment, up to 40 times:
/// the crossing is found to round-off) or quartered (triangle, when a cut
/// crosses an edge; up to 5 times), so no sample straddles a jump.
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

/// A point on a cut with its quadrature weight (m or m^2) and the cell holding it.
struct CutPoint {
  Vec3 x;
  double weight;
  Index cell;
};

/// Integration points of one cut piece that follow the cells' borders: the
/// piece is cut into parts about `length` long, and a part whose corners lie
/// in different cells is halved (2D, up to 40 times: the border is found to
/// round-off) or quartered (3D, up to 5 times); a part then gets two Gauss
/// points (2D) or its centroid (3D), each in the cell holding it.
class CutPoints {
 public:
  CutPoints(const Mesh& mesh, const CellLocator& locator) : mesh_(mesh), locator_(locator), box_(bounding_box(mesh)) {
    const double margin = 1e-9 * (box_[1] - box_[0]).norm();
    box_[0].array() -= margin, box_[1].array() += margin;
  }

  void of_piece(const CutPiece& piece, int dim, double length, std::vector<CutPoint>& out) {
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

 private:
  /// Points off the mesh's box are rejected at once (the locator would search every cell).
  Index cell_of(const Vec3& x) const {
    for (int k = 0; k < mesh_.dimension; ++k)
      if (x[k] < box_[0][k] || x[k] > box_[1][k]) return -1;
    return owner(mesh_, locator_, x);
  }

  void emit(const Vec3& x, double weight, std::vector<CutPoint>& out) const {
    const Index cell = cell_of(x);
    if (cell >= 0) out.push_back({x, weight, cell});  // parts beyond the body are dropped
  }

  void segment(const Vec3& a, const Vec3& b, int depth, std::vector<CutPoint>& out) const {
    if (depth > 0 && cell_of(a) != cell_of(b)) {
      const Vec3 m = 0.5 * (a + b);
      segment(a, m, depth - 1, out);
      segment(m, b, depth - 1, out);
      return;
    }
    const double offset = 0.5 / std::sqrt(3.0), w = 0.5 * (b - a).norm();
    for (double t : {0.5 - offset, 0.5 + offset}) emit(a + t * (b - a), w, out);
  }

  void triangle(const Vec3& a, const Vec3& b, const Vec3& c, int depth, std::vector<CutPoint>& out) const {
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

  const Mesh& mesh_;
  const CellLocator& locator_;
  std::array<Vec3, 2> box_;
};

}  // namespace

struct SmoothedGradients::Row {
  PointShapes shapes;
  std::vector<Index> near;
  std::vector<Vec3> sum;       // per node, dense: the boundary integral so far
  std::vector<char> seen;      // per node, dense
  std::vector<Index> nodes;    // the row's neighbours (sorted at the end)
  std::vector<Index> at_node;  // the nodes covering the node itself
  std::vector<double> at_node_value, at_node_factor;
  double condition = 0.0;
};

SmoothedGradients::~SmoothedGradients() = default;

SmoothedGradients::SmoothedGradients(const NodeSet& nodes, const SupportIndex& index) : index_(index) {
  const Mesh& mesh = nodes.cells;
  KERF_CHECK(mesh.node_count() == nodes.size() && mesh.order == 1 && mesh.cell_count() > 0,
             "smoothed gradients need linear cells on the nodes (", mesh.node_count(), " cell nodes for ", nodes.size(),
             " nodes)");
  Parts cells(nodes.size());
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.dimension == 2)
      triangle_cells(mesh, c, cells);
    else
      tet_cells(mesh, c, cells);
  }
  boundary_cells(mesh, cells);
  samples_.resize(nodes.size());
  radius_.assign(nodes.size(), 0.0);
  for (Index I = 0; I < nodes.size(); ++I) {
    for (const CellPart& part : cells[I]) {
      parts_.push_back(part);
      sample_part(part, nullptr, 0, samples_[I]);
      for (int k = 0; k < part.corners; ++k)
        radius_[I] = std::max(radius_[I], (part.corner[k] - nodes.positions[I]).norm());
    }
    parts_start_.push_back(static_cast<Index>(parts_.size()));
  }
  largest_radius_ = *std::max_element(radius_.begin(), radius_.end());
  on_cuts_.assign(nodes.size(), {});
}

void SmoothedGradients::set_cuts(const CutWeights& cuts, const NodeSet& nodes) {
  if (!locator_) locator_ = std::make_unique<CellLocator>(nodes.cells);
  CutPoints cut_points(nodes.cells, *locator_);
  const double spacing = *std::min_element(nodes.spacing.begin(), nodes.spacing.end());
  // The faces are sampled a hair off the cut, where the enrichment tells the sides apart
  // (the offset costs hair / spacing in the gradient of a linear field).
  const double hair = 1e-10 * spacing;
  pieces_done_.resize(cuts.cut_count(), 0);
  std::vector<CutPoint> points;
  std::vector<char> crossed(nodes.size(), 0);
  std::vector<Index> near;
  for (Index c = 0; c < cuts.cut_count(); ++c) {
    const CutSurface& surface = cuts.surface(c);
    for (Index p = pieces_done_[c]; p < cuts.pieces(c); ++p) {
      const CutPiece& piece = surface.pieces[p];
      cut_points.of_piece(piece, nodes.dimension, 0.5 * spacing, points);
      for (const CutPoint& q : points) {
        // - (phi+ - phi-) n w: the cut's faces as part of the cell's boundary.
        on_cuts_[q.cell].push_back({q.x + hair * piece.normal, -q.weight * piece.normal});
        on_cuts_[q.cell].push_back({q.x - hair * piece.normal, q.weight * piece.normal});
      }
      // The cells the new piece may cross: their boundaries are sampled again, split at the cut.
      double reach = 0.0;
      for (int k = 0; k < nodes.dimension; ++k) reach = std::max(reach, (piece.corner[k] - piece.centre).norm());
      index_.within(piece.centre, reach + largest_radius_, near);
      for (Index I : near)
        if (distance_to_cut(surface, p, p + 1, nodes.positions[I]) < radius_[I]) crossed[I] = 1;
    }
    pieces_done_[c] = cuts.pieces(c);
  }
  // 40 halvings find a crossing to round-off on a segment; 5 quarterings follow it to 1/32 of a triangle.
  const int depth = nodes.dimension == 2 ? 40 : 5;
  const Index N = nodes.size();
  ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 16)
  for (Index I = 0; I < N; ++I) {
    if (!crossed[I]) continue;
    failure.run([&] {
      samples_[I].clear();
      for (Index k = parts_start_[I]; k < parts_start_[I + 1]; ++k)
        sample_part(parts_[k], &cuts, depth, samples_[I]);
    });
  }
  failure.rethrow_if_failed();
}

std::vector<CellSample> SmoothedGradients::samples_of(Index node) const {
  std::vector<CellSample> out = samples_[node];
  out.insert(out.end(), on_cuts_[node].begin(), on_cuts_[node].end());
  return out;
}

void SmoothedGradients::compute_row(Index I, const NodeSet& nodes, MlsBasis basis, const EnrichmentRule* enrichment,
                                    const std::string& context, const std::string& remedy, Row& row) const {
  const int dim = nodes.dimension;
  if (row.sum.empty()) row.sum.assign(nodes.size(), Vec3::Zero()), row.seen.assign(nodes.size(), 0);
  auto covering = [&](const Vec3& x) {
    index_.reaching(x, 0.0, row.near);
  };
  // The point is named only when its moment matrix is singular (no string per sample).
  auto evaluate = [&](const Vec3& x, bool at_node) {
    covering(x);
    if (row.shapes.evaluate(nodes, basis, x, row.near, enrichment)) return;
    const std::string what = at_node ? "the node" : "a point of the smoothing cell of node " + std::to_string(I);
    throw Error(singular_moment_message(dim, basis, x, static_cast<Index>(row.near.size()), row.shapes.shape.condition,
                                        what, context, remedy));
  };
  auto visit = [&](Index K) {
    if (!row.seen[K]) row.seen[K] = 1, row.nodes.push_back(K);
  };
  row.nodes.clear();
  evaluate(nodes.positions[I], true);
  row.at_node = row.near;
  row.at_node_value = row.shapes.shape.value;
  row.at_node_factor = row.shapes.weight_factor;
  row.condition = row.shapes.shape.condition;
  for (Index K : row.at_node) visit(K);
  auto integrate = [&](const CellSample& sample) {
    evaluate(sample.position, false);
    for (std::size_t k = 0; k < row.near.size(); ++k) {
      visit(row.near[k]);
      row.sum[row.near[k]] += row.shapes.shape.value[k] * sample.weighted_normal;
    }
  };
  for (const CellSample& sample : samples_[I]) integrate(sample);
  for (const CellSample& sample : on_cuts_[I]) integrate(sample);
  std::sort(row.nodes.begin(), row.nodes.end());
  for (Index K : row.nodes) row.sum[K] /= nodes.volume[I];
}

template <class Store>
void SmoothedGradients::compute_rows(std::span<const Index> rows, const NodeSet& nodes, MlsBasis basis,
                                     const EnrichmentRule* enrichment, const std::string& context,
                                     const std::string& remedy, Store store) const {
  const Index count = static_cast<Index>(rows.size());
  ParallelFailure failure;
#pragma omp parallel
  {
    Row row;
#pragma omp for schedule(dynamic, 16)
    for (Index r = 0; r < count; ++r) {
      failure.run([&] {
        compute_row(rows[r], nodes, basis, enrichment, context, remedy, row);
        store(r, row);
      });
      // Leave the dense scratch clean for the next row.
      for (Index K : row.nodes) row.sum[K] = Vec3::Zero(), row.seen[K] = 0;
    }
  }
  failure.rethrow_if_failed();
}

ShapeTable SmoothedGradients::table(const NodeSet& nodes, MlsBasis basis, const EnrichmentRule* enrichment,
                                    const std::string& context, const std::string& remedy) const {
  const int dim = nodes.dimension;
  const Index N = nodes.size();
  struct Result {
    std::vector<Index> nodes;
    std::vector<double> value, factor, gradient;
    double condition = 0.0;
  };
  std::vector<Result> results(N);
  std::vector<Index> all(N);
  for (Index I = 0; I < N; ++I) all[I] = I;
  compute_rows(all, nodes, basis, enrichment, context, remedy, [&](Index I, const Row& row) {
    Result& r = results[I];
    r.nodes = row.nodes;
    r.value.assign(row.nodes.size(), 0.0);
    r.factor.assign(row.nodes.size(), 1.0);
    for (std::size_t k = 0, j = 0; k < row.nodes.size(); ++k) {
      for (int i = 0; i < dim; ++i) r.gradient.push_back(row.sum[row.nodes[k]][i]);
      if (j < row.at_node.size() && row.at_node[j] == row.nodes[k])
        r.value[k] = row.at_node_value[j], r.factor[k] = row.at_node_factor[j], ++j;
    }
    r.condition = row.condition;
  });
  ShapeTable t;
  t.dimension = dim;
  t.condition.resize(N);
  for (Index I = 0; I < N; ++I) {
    Result& r = results[I];
    t.neighbours.index.insert(t.neighbours.index.end(), r.nodes.begin(), r.nodes.end());
    t.neighbours.start.push_back(static_cast<Index>(t.neighbours.index.size()));
    t.value.insert(t.value.end(), r.value.begin(), r.value.end());
    t.gradient.insert(t.gradient.end(), r.gradient.begin(), r.gradient.end());
    if (enrichment) t.weight_factor.insert(t.weight_factor.end(), r.factor.begin(), r.factor.end());
    t.condition[I] = r.condition;
    r = Result{};
  }
  return t;
}

void SmoothedGradients::refresh(ShapeTable& table, std::span<const Index> rows, const NodeSet& nodes, MlsBasis basis,
                                const EnrichmentRule& enrichment, const std::string& context,
                                const std::string& remedy) const {
  const int dim = nodes.dimension;
  if (table.weight_factor.empty()) table.weight_factor.assign(table.neighbours.index.size(), 1.0);
  compute_rows(rows, nodes, basis, &enrichment, context, remedy, [&](Index r, const Row& row) {
    const Index I = rows[r];
    auto slots = table.neighbours.of(I);
    const Index s0 = table.neighbours.start[I];
    // The row keeps its slots: a cut changes the weights, not which supports cover the cell.
    for (std::size_t k = 0; k < slots.size(); ++k) {
      table.value[s0 + k] = 0.0;
      table.weight_factor[s0 + k] = 1.0;
      for (int i = 0; i < dim; ++i) table.gradient[dim * (s0 + k) + i] = 0.0;
    }
    auto slot_of = [&](Index K) {
      auto it = std::lower_bound(slots.begin(), slots.end(), K);
      KERF_CHECK(it != slots.end() && *it == K, "smoothed gradients: node ", K, " covers the cell of node ", I,
                 " only after the cut grew");
      return s0 + static_cast<Index>(it - slots.begin());
    };
    for (Index K : row.nodes)
      for (int i = 0; i < dim; ++i) table.gradient[dim * slot_of(K) + i] = row.sum[K][i];
    for (std::size_t j = 0; j < row.at_node.size(); ++j) {
      const Index s = slot_of(row.at_node[j]);
      table.value[s] = row.at_node_value[j];
      table.weight_factor[s] = row.at_node_factor[j];
    }
    table.condition[I] = row.condition;
  });
}

}  // namespace kerf
