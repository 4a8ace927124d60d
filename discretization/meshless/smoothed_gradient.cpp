#include "discretization/meshless/smoothed_gradient.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "discretization/meshless/cut_face_points.h"
#include "geometry/point_location.h"

namespace kerf {

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
  const std::vector<std::vector<CellPart>> cells = dual_cell_parts(mesh);
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
