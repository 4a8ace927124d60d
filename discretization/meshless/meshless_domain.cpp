#include "discretization/meshless/meshless_domain.h"

#include <algorithm>
#include <limits>
#include <sstream>

#include "core/check.h"
#include "discretization/enrichment/enrichment_grid.h"
#include "discretization/fem/simplex_quadrature.h"
#include "discretization/meshless/integration_constraint.h"
#include "discretization/meshless/mls_shape.h"
#include "discretization/prescribed_dofs.h"
#include "geometry/neighbor_search.h"
#include "geometry/point_location.h"
#include "problem/selection.h"

namespace kerf {
namespace {

/// How near the front a cell is integrated by its parts: its centroid within
/// this many times its own radius (largest corner distance) of a front edge.
/// Measured on the cut block (h 2 / 3 mm, sag): 1 radius -3.9 / -13.6%, 2:
/// -3.9 / -12.4%, 4: -0.8 / -7.7%, 8: +1.2 / -6.0%; 24 points a cell instead
/// of 4 changed them by under 1 point: what the nodes' points just outside the
/// zone miss, not the zone's own rule, is what is left.
constexpr double front_reach = 4.0;

}  // namespace
namespace {

std::string support_context(const Scene& scene) {
  std::ostringstream s;
  s << scene.file << ": key 'discretization.meshless.support': value " << scene.discretization.meshless.support
    << " (x spacing, " << to_string(scene.discretization.meshless.basis) << " basis): ";
  return s.str();
}

}  // namespace

MeshlessDomain::MeshlessDomain(const Scene& scene, SharedCuts cuts, NodeSet nodes, std::optional<Box> box,
                               std::optional<Mesh> background)
    : nodes_(std::move(nodes)),
      box_(std::move(box)),
      background_(std::move(background)),
      basis_(scene.discretization.meshless.basis),
      error_context_(support_context(scene)) {
  KERF_CHECK(box_ || background_, "a meshless domain needs a box or a background mesh");
  if (box_) {
    domain_size_ = (box_->max - box_->min).norm();
  } else {
    auto bb = bounding_box(*background_);
    domain_size_ = (bb[1] - bb[0]).norm();
  }
  facets_ = boundary_facets(boundary_mesh());
  background_on_boundary_ = boundary_node_flags(boundary_mesh(), facets_);
  index_ = std::make_unique<SupportIndex>(nodes_.positions, nodes_.support);
  growing_ = cuts->grows();
  if (cuts->cut_count() > 0)
    enrichment_ = std::make_unique<CutWeights>(std::move(cuts), *index_, 0.0);
  if (growing_) {
    std::vector<Vec3> points;
    for (const BoundaryCondition& bc : scene.boundary)
      if (!bc.is_dirichlet()) {
        BoundaryPoints b = boundary_points(facets_in(bc.select, false), 3);
        points.insert(points.end(), b.position.begin(), b.position.end());
      }
    load_points_ = std::make_unique<PointIndex>(std::move(points));
  }
  if (scene.discretization.method == Method::nodal &&
      scene.discretization.meshless.gradient == NodalGradient::smoothed) {
    smoothing_ = std::make_unique<SmoothedGradients>(nodes_, *index_);
    if (enrichment()) smoothing_->set_cuts(*enrichment_, nodes_);
    at_nodes_ = smoothing_->table(nodes_, basis_, enrichment(), error_context_, mls_remedy());
  } else {  // refreshed row by row when a cut grows: the factors' gradients are kept
    at_nodes_ = shape_table(nodes_, *index_, basis_, nodes_.positions, "the node", error_context_, mls_remedy(),
                            enrichment(), true);
  }
  build_boundary_terms(scene);
  if (enrichment_ && scene.discretization.method == Method::nodal && !smoothing_ &&
      cut_cells_of(scene) == CutCells::split) {
    visible_cells_ = std::make_unique<VisibleDualCells>(nodes_.cells);
    volumes_taken_.assign(enrichment_->cut_count(), 0);
    update_visible_cells();
  }
}

BoundaryQuadrature MeshlessDomain::closed_boundary_facets(const Scene& scene) const {
  // 2 points a direction (nodal integration's weak conditions' rule), 3 where loads act (their rule).
  std::vector<int> per_direction(facets_.count(), 2);
  for (const BoundaryCondition& bc : scene.boundary)
    if (!bc.is_dirichlet())
      for (Index f : facets_in(bc.select, false)) per_direction[f] = 3;
  return facet_quadrature(boundary_mesh(), facets_, per_direction);
}

std::vector<Index> MeshlessDomain::cells_near_piece(const CutPiece& piece) const {
  double reach = 0.0;
  for (int k = 0; k < dimension(); ++k) reach = std::max(reach, (piece.corner[k] - piece.centre).norm());
  std::vector<Index> near;
  index_->within(piece.centre, reach + longest_edge_, near);
  return cells_near(cells_around_, near);
}

BoundaryQuadrature MeshlessDomain::cut_faces(Index cut, Index first_piece, Index end_piece) const {
  const double hair = 1e-10 * *std::min_element(nodes_.spacing.begin(), nodes_.spacing.end());
  BoundaryQuadrature out;
  for (Index p = first_piece; p < end_piece; ++p) {
    const CutPiece& piece = enrichment_->surface(cut).pieces[p];
    out.append(cut_face_quadrature(nodes_.cells, cells_near_piece(piece), piece, hair));
  }
  return out;
}

std::vector<Index> MeshlessDomain::front_cells() const {
  // The front: the pieces' edges (2D: ends) no other piece shares.
  const int dim = dimension();
  std::vector<std::array<Vec3, 2>> front;
  for (Index c = 0; c < enrichment_->cut_count(); ++c) {
    const std::vector<CutPiece>& pieces = enrichment_->surface(c).pieces;
    std::vector<std::array<Vec3, 2>> edges;
    for (Index p = 0; p < enrichment_->pieces(c); ++p)
      for (int k = 0; k < dim; ++k) {
        Vec3 a = pieces[p].corner[k], b = dim == 3 ? pieces[p].corner[(k + 1) % 3] : a;
        if (std::lexicographical_compare(b.data(), b.data() + 3, a.data(), a.data() + 3)) std::swap(a, b);
        edges.push_back({a, b});
      }
    auto less = [](const std::array<Vec3, 2>& x, const std::array<Vec3, 2>& y) {
      return std::lexicographical_compare(x[0].data(), x[0].data() + 3, y[0].data(), y[0].data() + 3) ||
             (x[0] == y[0] && std::lexicographical_compare(x[1].data(), x[1].data() + 3, y[1].data(), y[1].data() + 3));
    };
    std::sort(edges.begin(), edges.end(), less);
    for (std::size_t e = 0; e < edges.size();) {
      std::size_t f = e + 1;
      while (f < edges.size() && edges[f] == edges[e]) ++f;
      if (f - e == 1) front.push_back(edges[e]);
      e = f;
    }
  }
  // Only where the front runs inside the body (a blade's ends and entry lie
  // outside it): each edge sampled half the shortest spacing apart, and each
  // run of samples inside the body taken as one segment.
  const double step = 0.5 * *std::min_element(nodes_.spacing.begin(), nodes_.spacing.end());
  std::vector<Index> out, near;
  auto take_cells_near = [&](const Vec3& a, const Vec3& b) {
    index_->within(0.5 * (a + b), 0.5 * (b - a).norm() + (front_reach + 1.0) * longest_edge_, near);
    const Vec3 ab = b - a;
    for (Index c : cells_near(cells_around_, near)) {
      const auto [centre, radius] = cell_ball(c);
      const double t = ab.squaredNorm() > 0.0 ? std::clamp((centre - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      if ((a + t * ab - centre).norm() <= front_reach * radius) out.push_back(c);
    }
  };
  for (const auto& [a, b] : front) {
    const int samples = 1 + static_cast<int>(std::ceil((b - a).norm() / step));
    int run_start = -1;
    for (int k = 0; k <= samples + 1; ++k) {
      bool inside = false;
      if (k <= samples) {
        const Vec3 x = a + (b - a) * (static_cast<double>(k) / samples);
        index_->within(x, longest_edge_, near);  // a cell holding x has its corners this near
        const std::vector<Index> holding = cells_near(cells_around_, near);
        inside = std::any_of(holding.begin(), holding.end(), [&](Index c) { return holds(c, x); });
      }
      if (inside && run_start < 0) run_start = k;
      if (!inside && run_start >= 0) {
        const double t0 = std::max(0.0, (run_start - 1.0) / samples), t1 = std::min(1.0, static_cast<double>(k) / samples);
        take_cells_near(a + t0 * (b - a), a + t1 * (b - a));
        run_start = -1;
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool MeshlessDomain::holds(Index c, const Vec3& x) const {
  const int dim = dimension();
  auto n = nodes_.cells.cell(c);
  Mat3 edges = Mat3::Identity();
  for (int k = 1; k <= dim; ++k) edges.col(k - 1) = nodes_.cells.nodes[n[k]] - nodes_.cells.nodes[n[0]];
  const Vec3 l = edges.inverse() * (x - nodes_.cells.nodes[n[0]]);
  const double tolerance = 1e-9;
  double sum = 0.0;
  for (int k = 0; k < dim; ++k) {
    if (l[k] < -tolerance) return false;
    sum += l[k];
  }
  return sum <= 1.0 + tolerance;
}

std::pair<Vec3, double> MeshlessDomain::cell_ball(Index c) const {
  const int corners = dimension() + 1;
  auto n = nodes_.cells.cell(c);
  Vec3 centre = Vec3::Zero();
  for (int k = 0; k < corners; ++k) centre += nodes_.cells.nodes[n[k]] / corners;
  double radius = 0.0;
  for (int k = 0; k < corners; ++k) radius = std::max(radius, (nodes_.cells.nodes[n[k]] - centre).norm());
  return {centre, radius};
}

void MeshlessDomain::visit_cut_cell_reach(const std::function<void(std::span<const Index>)>& visit) const {
  if (!cut_cell_points_grow()) return;
  std::vector<Index> cells, near, reaching;
  for (Index c = 0; c < enrichment_->cut_count(); ++c)
    for (const CutPiece& piece : enrichment_->surface(c).pieces) {  // every piece, present or to come
      double reach = 0.0;
      for (int k = 0; k < dimension(); ++k) reach = std::max(reach, (piece.corner[k] - piece.centre).norm());
      index_->within(piece.centre, reach + (front_reach + 1.0) * longest_edge_, near);
      const std::vector<Index> around = cells_near(cells_around_, near);
      cells.insert(cells.end(), around.begin(), around.end());
    }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  for (Index c : cells) {
    const auto [centre, radius] = cell_ball(c);
    index_->reaching(centre, radius, reaching);
    visit(reaching);
  }
}

MeshlessDomain::CutCellPoints MeshlessDomain::cut_cell_points() const {
  // One point a part: one point a front cell instead (a quarter of the
  // points) swung the cut block from -6 to +34% (3 and 2.5 mm), soft modes
  // where the nodes' own points (and their hourglass pairs) had no weight left.
  CutCellPoints out;
  if (!visible_cells_) return out;
  std::vector<Index> cells = front_cells();
  const std::vector<Index> split = visible_cells_->split_cells();
  cells.insert(cells.end(), split.begin(), split.end());
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  out.node_volume = nodes_.volume;
  out.node_moment = visible_cells_->second_moment();
  out.cells = static_cast<Index>(cells.size());
  for (Index c : cells) {
    auto n = nodes_.cells.cell(c);
    const VisibleDualCells::CellShares shares = visible_cells_->shares(nodes_.cells, c);
    const double whole = std::abs(cell_measure(nodes_.cells, c));
    for (int a = 0; a <= dimension(); ++a) {
      const VisibleDualCells::Share& part = shares[a];
      out.node_volume[n[a]] -= part.volume;
      out.node_moment[n[a]] -= part.moment;
      if (part.volume <= 1e-9 * whole) continue;  // a sliver no MLS may fit; its volume is negligible
      out.position.push_back(part.first / part.volume);
      out.weight.push_back(part.volume);
    }
  }
  return out;
}

std::vector<Index> MeshlessDomain::update_visible_cells() {
  if (!visible_cells_) return {};
  std::vector<Index> near;
  std::vector<CutPiece> present;
  for (Index c = 0; c < enrichment_->cut_count(); ++c) {
    const std::vector<CutPiece>& pieces = enrichment_->surface(c).pieces;
    present.insert(present.end(), pieces.begin(), pieces.begin() + enrichment_->pieces(c));
    for (Index p = volumes_taken_[c]; p < enrichment_->pieces(c); ++p)
      for (Index cell : cells_near_piece(pieces[p]))  // only the cells a new piece meets change
        if (piece_meets_cell(pieces[p], nodes_.cells, cell, 1e-9 * longest_edge_)) near.push_back(cell);
    volumes_taken_[c] = enrichment_->pieces(c);
  }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  std::vector<Index> changed = visible_cells_->update(nodes_.cells, near, present);
  for (Index I : changed) nodes_.volume[I] = visible_cells_->volume()[I];
  return changed;
}

namespace {

/// Per node the slots of `lists` holding it, and per slot its row: what
/// lists_holding needs to find the rows a set of nodes appears in.
void transpose_rows(const NeighborLists& lists, Index node_count, NeighborLists& users, std::vector<Index>& slot_row) {
  users = transpose_slots(lists, node_count);
  slot_row.resize(lists.index.size());
  for (Index p = 0; p < lists.size(); ++p)
    std::fill(slot_row.begin() + lists.start[p], slot_row.begin() + lists.start[p + 1], p);
}

}  // namespace

ShapeTable MeshlessDomain::boundary_shapes_at(std::span<const Vec3> points) const {
  // A figure must not stop a run: a point no MLS fits (every node hidden by a
  // cut there) is left out and counted.
  return shape_table(nodes_, *index_, basis_, points, "a point of the boundary (integration constraint)",
                     error_context_, mls_remedy(), enrichment(), growing_, &boundary_singular_);
}

void MeshlessDomain::build_boundary_terms(const Scene& scene) {
  boundary_terms_.assign(dimension() * nodes_.size(), 0.0);
  BoundaryQuadrature points = closed_boundary_facets(scene);
  if (enrichment_) {
    cells_around_ = node_cells(nodes_.cells);
    const int corners = dimension() + 1;
    for (Index c = 0; c < nodes_.cells.cell_count(); ++c)
      for (int a = 0; a < corners; ++a)
        for (int b = a + 1; b < corners; ++b)
          longest_edge_ = std::max(longest_edge_, (nodes_.cells.nodes[nodes_.cells.cell(c)[a]] -
                                                   nodes_.cells.nodes[nodes_.cells.cell(c)[b]]).norm());
    faces_taken_.assign(enrichment_->cut_count(), 0);
    for (Index c = 0; c < enrichment_->cut_count(); ++c) {
      points.append(cut_faces(c, 0, enrichment_->pieces(c)));
      faces_taken_[c] = enrichment_->pieces(c);
    }
  }
  if (!growing_) {
    add_boundary_terms(boundary_shapes_at(points.position), points, boundary_terms_);
    return;
  }
  // A growing cut: every point's shape functions are kept, to refresh the
  // rows holding a node whose weights a growth changes (as at the nodes).
  boundary_points_ = std::move(points);
  boundary_shapes_ = boundary_shapes_at(boundary_points_.position);
  add_boundary_terms(boundary_shapes_, boundary_points_, boundary_terms_);
}

void MeshlessDomain::update_boundary_terms() {
  if (!growing_) return;
  const std::vector<Index> changed = std::move(boundary_pending_);
  boundary_pending_.clear();
  const std::string what = "a point of the boundary (integration constraint)";
  if (boundary_users_.size() == 0)
    transpose_rows(boundary_shapes_.neighbours, nodes_.size(), boundary_users_, boundary_slot_row_);
  const std::vector<Index> rows =
      lists_holding(boundary_users_, boundary_slot_row_, boundary_shapes_.point_count(), changed);
  if (!rows.empty())
    refresh_shape_rows(boundary_shapes_, nodes_, basis_, boundary_points_.position, rows, *enrichment_, what,
                       error_context_, mls_remedy(), &boundary_singular_);
  // The faces of the new pieces join the points.
  BoundaryQuadrature added;
  for (Index c = 0; c < enrichment_->cut_count(); ++c) {
    added.append(cut_faces(c, faces_taken_[c], enrichment_->pieces(c)));
    faces_taken_[c] = enrichment_->pieces(c);
  }
  if (added.size() > 0) {
    append_rows(boundary_shapes_, boundary_shapes_at(added.position));
    boundary_points_.append(added);
    boundary_users_ = {};  // rebuilt with the new rows at the next growth
  }
  boundary_terms_.assign(boundary_terms_.size(), 0.0);
  add_boundary_terms(boundary_shapes_, boundary_points_, boundary_terms_);
}

MeshlessDomain::~MeshlessDomain() = default;
MeshlessDomain::MeshlessDomain(MeshlessDomain&&) noexcept = default;

const Mesh& MeshlessDomain::background() const {
  KERF_CHECK(background_, "this meshless domain has no background mesh");
  return *background_;
}

ShapeTable MeshlessDomain::shapes_at(std::span<const Vec3> points, const std::string& what) const {
  return shape_table(nodes_, *index_, basis_, points, what, error_context_, mls_remedy(), enrichment(), growing_);
}

std::vector<Index> MeshlessDomain::refresh_rows(ShapeTable& table, std::span<const Vec3> points,
                                                std::span<const Index> rows, const std::string& what) const {
  if (!enrichment_ || rows.empty()) return {};
  return refresh_shape_rows(table, nodes_, basis_, points, rows, *enrichment_, what, error_context_, mls_remedy());
}

std::string MeshlessDomain::mls_remedy() const {
  return enrichment_ ? "expected a larger support, a linear basis, or more nodes there (a cut hides the nodes on "
                       "its other side)"
                     : "expected a larger support, a linear basis, or more nodes there";
}

std::vector<Index> MeshlessDomain::update_shapes_for_cuts(double t, std::vector<Index>* rows,
                                                          std::vector<Index>* volumes) {
  if (!enrichment_) return {};
  std::vector<Index> changed = enrichment_->advance_to(t);
  if (changed.empty()) return changed;
  if (volumes) *volumes = update_visible_cells();
  // The rows a changed node appears in, from the transposed neighbour lists.
  if (covered_.size() == 0) transpose_rows(at_nodes_.neighbours, nodes_.size(), covered_, slot_row_);
  std::vector<Index> touched = lists_holding(covered_, slot_row_, nodes_.size(), changed);
  if (smoothing_) {
    smoothing_->set_cuts(*enrichment_, nodes_);
    smoothing_->refresh(at_nodes_, touched, nodes_, basis_, *enrichment_, error_context_, mls_remedy());
  } else {
    // Only the rows whose factors changed: phi moved at their point.
    touched = refresh_shape_rows(at_nodes_, nodes_, basis_, nodes_.positions, touched, *enrichment_, "the node",
                                 error_context_, mls_remedy());
  }
  if (rows) *rows = std::move(touched);
  if (growing_) {  // the boundary terms wait for update_boundary_terms (costly: only VCI needs them each growth)
    boundary_pending_.insert(boundary_pending_.end(), changed.begin(), changed.end());
    std::sort(boundary_pending_.begin(), boundary_pending_.end());
    boundary_pending_.erase(std::unique(boundary_pending_.begin(), boundary_pending_.end()), boundary_pending_.end());
  }
  return changed;
}

bool MeshlessDomain::boundary_loads_touch(std::span<const Index> nodes) const {
  if (!load_points_) return false;
  std::vector<Index> near;
  for (Index I : nodes) {
    load_points_->within(nodes_.positions[I], nodes_.support[I], near);
    if (!near.empty()) return true;
  }
  return false;
}

MomentConditioning MeshlessDomain::conditioning() const {
  MomentConditioning c;
  const std::vector<double>& k = at_nodes_.condition;
  if (k.empty()) return c;
  std::vector<double> sorted = k;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  c.median = sorted[sorted.size() / 2];
  c.max = *std::max_element(k.begin(), k.end());
  c.reduced_basis = at_nodes_.reduced_basis_points();
  const CutWeights* cuts = enrichment();
  if (!cuts) return c;
  // The ends of each cut as it stands: a polyline's two end vertices, a
  // strip's first and last edges (the blade's entry and its front).
  std::vector<Vec3> tips;
  for (Index i = 0; i < cuts->cut_count(); ++i) {
    const CutSurface& s = cuts->surface(i);
    const Index n = cuts->pieces(i);
    if (n == 0) continue;
    const std::vector<Index> ends = dimension() == 2 ? std::vector<Index>{0, n} : std::vector<Index>{0, 1, n, n + 1};
    for (Index v : ends) tips.push_back(s.vertices[v]);
  }
  for (Index I = 0; I < nodes_.size(); ++I) {
    if (cuts->enriches(I)) c.near_cut_max = std::max(c.near_cut_max, k[I]);
    for (const Vec3& tip : tips)
      if ((tip - nodes_.positions[I]).norm() <= nodes_.support[I]) c.near_tip_max = std::max(c.near_tip_max, k[I]);
  }
  return c;
}

double MeshlessDomain::mean_neighbors() const {
  const Index N = nodes_.size();
  return N ? static_cast<double>(at_nodes_.neighbours.index.size() - N) / N : 0.0;
}

std::vector<Index> MeshlessDomain::select_nodes(const Selection& selection) const {
  return select_points(selection, nodes_.positions, nodes_.on_boundary, domain_size_);
}

std::optional<PointInterpolation> MeshlessDomain::interpolation_at(const Vec3& x) const {
  const double tolerance = 1e-6 * domain_size_;
  bool inside = false;
  if (box_) {
    inside = true;
    for (int a = 0; a < dimension(); ++a)
      inside &= x[a] >= box_->min[a] - tolerance && x[a] <= box_->max[a] + tolerance;
  } else {
    inside = locate_point(*background_, x, tolerance).has_value();
  }
  if (!inside) return std::nullopt;
  ShapeTable t = shapes_at(std::span<const Vec3>(&x, 1), "the point");
  PointInterpolation p;
  auto near = t.neighbours.of(0);
  p.nodes.assign(near.begin(), near.end());
  p.weights.assign(t.value.begin(), t.value.end());
  return p;
}

std::vector<Index> MeshlessDomain::facets_in(const Selection& selection, bool required) const {
  const Mesh& mesh = boundary_mesh();
  std::vector<char> selected(mesh.nodes.size(), 0);
  for (Index n : select_points(selection, mesh.nodes, background_on_boundary_, domain_size_)) selected[n] = 1;
  const int corners = dimension();
  std::vector<Index> out;
  for (Index f = 0; f < facets_.count(); ++f) {
    auto fn = facets_.facet(f);
    if (std::all_of(fn.begin(), fn.begin() + corners, [&](Index n) { return selected[n]; })) out.push_back(f);
  }
  KERF_CHECK(!out.empty() || !required, selection.where.describe(),
             ": the selection holds boundary points but no whole boundary face, so the condition has "
             "nowhere to act; expected a plane or box covering at least one face");
  return out;
}

BoundaryPoints MeshlessDomain::boundary_points(std::span<const Index> facets, int points_per_direction) const {
  const int dim = dimension(), fdim = dim - 1;
  const Mesh& mesh = boundary_mesh();
  QuadratureRule rule = collapsed_gauss(fdim, points_per_direction);
  BoundaryPoints out;
  for (Index f : facets) {
    auto fn = facets_.facet(f);
    const Vec3 a = mesh.nodes[fn[0]], b = mesh.nodes[fn[1]];
    const Vec3 c = fdim == 2 ? mesh.nodes[fn[2]] : a;
    // Outward area normal of the straight facet; |.| = d(area)/d(reference area).
    Vec3 area_normal = fdim == 2 ? Vec3((b - a).cross(c - a)) : Vec3((b - a).y(), -(b - a).x(), 0.0);
    const double jacobian = area_normal.norm();
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      const Vec3& r = rule.points[q];
      out.position.push_back(Vec3(a + r.x() * (b - a) + (fdim == 2 ? r.y() : 0.0) * (c - a)));
      out.normal.push_back(area_normal / jacobian);
      out.weight.push_back(rule.weights[q] * jacobian);
    }
  }
  return out;
}

SurfaceSamples MeshlessDomain::surface_samples(const Box& region, int points_per_direction) const {
  const Mesh& mesh = boundary_mesh();
  const int corners = dimension();
  std::vector<Index> facets;
  SurfaceSamples out;
  for (Index f = 0; f < facets_.count(); ++f) {
    auto fn = facets_.facet(f);
    if (std::none_of(fn.begin(), fn.begin() + corners, [&](Index n) { return region.contains(mesh.nodes[n], 0.0); }))
      continue;
    facets.push_back(f);
    const Vec3 a = mesh.nodes[fn[0]], b = mesh.nodes[fn[1]], c = corners == 3 ? mesh.nodes[fn[2]] : b;
    out.facets.push_back({a, b, c});
  }
  const BoundaryPoints points = boundary_points(facets, points_per_direction);
  const ShapeTable shapes = shapes_at(points.position, "the boundary point");
  const std::size_t per_facet = facets.empty() ? 0 : points.position.size() / facets.size();
  for (std::size_t q = 0; q < points.position.size(); ++q) {
    const auto& [a, b, c] = out.facets[q / per_facet];
    SurfacePoint p;
    p.position = points.position[q];
    p.weight = points.weight[q];
    p.size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const Index begin = shapes.neighbours.start[q], end = shapes.neighbours.start[q + 1];
    p.interpolation.nodes.assign(shapes.neighbours.index.begin() + begin, shapes.neighbours.index.begin() + end);
    p.interpolation.weights.assign(shapes.value.begin() + begin, shapes.value.begin() + end);
    out.points.push_back(std::move(p));
  }
  return out;
}

std::vector<DirichletDof> MeshlessDomain::nodal_constraints(const Scene& scene,
                                                            bool (*take)(const BoundaryCondition&)) const {
  return prescribed_dofs(
      scene, dimension(), [this](const Selection& s) { return select_nodes(s); }, nodes_.positions, take);
}

void MeshlessDomain::add_boundary_loads(std::span<const BoundaryCondition> conditions, Vector& load) const {
  const int dim = dimension();
  for (const BoundaryCondition& bc : conditions) {
    if (bc.is_dirichlet()) continue;
    BoundaryPoints points = boundary_points(facets_in(bc.select), 3);
    ShapeTable t = shapes_at(points.position, "the boundary quadrature point");
    for (Index q = 0; q < t.point_count(); ++q) {
      Vec3 traction = Vec3::Zero();
      if (bc.traction) traction += *bc.traction;
      if (bc.pressure) traction -= *bc.pressure * points.normal[q];
      auto near = t.neighbours.of(q);
      const double* phi = t.values_of(q);
      for (std::size_t k = 0; k < near.size(); ++k)
        for (int i = 0; i < dim; ++i) load[dim * near[k] + i] += points.weight[q] * phi[k] * traction[i];
    }
  }
}

void MeshlessDomain::snapshot(const Vector& u, const MaterialLaw& law, BodySnapshot& out) const {
  const Index N = nodes_.size();
  out = BodySnapshot{};
  out.points = nodes_.positions;
  for (Index n = 0; n < N; ++n) {
    out.connectivity.push_back(n);
    out.offsets.push_back(n + 1);
    out.cell_types.push_back(1);  // VTK_VERTEX
  }
  OutputField displacement{"displacement", 3, std::vector<double>(3 * N, 0.0)};
  OutputField stress{"stress", 9, std::vector<double>(9 * N, 0.0)};
  OutputField mises{"von_mises", 1, std::vector<double>(N, 0.0)};
  OutputField radius{"support_radius", 1, nodes_.support};
  OutputField volume{"nodal_volume", 1, nodes_.volume};
  OutputField condition{"mls_condition", 1, at_nodes_.condition};
  for (Index n = 0; n < N; ++n) {
    const Vec3 uh = interpolated_displacement(at_nodes_, n, u);
    for (int i = 0; i < 3; ++i) displacement.values[3 * n + i] = uh[i];
    Mat3 sigma = law.cauchy_stress(deformation_gradient(at_nodes_, n, u));
    for (int k = 0; k < 9; ++k) stress.values[9 * n + k] = sigma(k / 3, k % 3);
    mises.values[n] = von_mises(sigma);
  }
  for (OutputField* f : {&displacement, &stress, &mises, &radius, &volume, &condition})
    out.point_fields.push_back(std::move(*f));
}

std::vector<LatticeSnapshot> MeshlessDomain::enrichment_lattices() const {
  std::vector<LatticeSnapshot> out;
  if (!enrichment_) return out;
  for (Index c = 0; c < enrichment_->cut_count(); ++c) {
    const EnrichmentGrid* grid = enrichment_->grid(c);
    if (!grid) continue;
    LatticeSnapshot l;
    l.name = "phi_cut" + std::to_string(c);
    l.origin = grid->lattice_origin();
    l.axes = grid->lattice_axes();
    l.count = grid->lattice_count();
    l.spacing = grid->spacing();
    l.values = grid->lattice_phi();
    out.push_back(std::move(l));
  }
  return out;
}

}  // namespace kerf
