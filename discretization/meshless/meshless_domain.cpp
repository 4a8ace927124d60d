#include "discretization/meshless/meshless_domain.h"

#include <algorithm>
#include <limits>
#include <sstream>

#include "core/check.h"
#include "core/parallel_failure.h"
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
  if (enrichment_) cell_search_ = std::make_unique<NodeCellSearch>(nodes_.cells, *index_);
  build_boundary_terms(scene);
  if (enrichment_ && scene.discretization.method == Method::nodal && !smoothing_ &&
      cut_cells_of(scene) == CutCells::split)
    cut_cells_ = std::make_unique<CutCellIntegration>(nodes_, *cell_search_, *enrichment_);
}

BoundaryQuadrature MeshlessDomain::closed_boundary_facets(const Scene& scene) const {
  // 2 points a direction (nodal integration's weak conditions' rule), 3 where loads act (their rule).
  std::vector<int> per_direction(facets_.count(), 2);
  for (const BoundaryCondition& bc : scene.boundary)
    if (!bc.is_dirichlet())
      for (Index f : facets_in(bc.select, false)) per_direction[f] = 3;
  return facet_quadrature(boundary_mesh(), facets_, per_direction);
}

BoundaryQuadrature MeshlessDomain::cut_faces(Index cut, Index first_piece, Index end_piece) const {
  const double hair = 1e-10 * *std::min_element(nodes_.spacing.begin(), nodes_.spacing.end());
  BoundaryQuadrature out;
  for (Index p = first_piece; p < end_piece; ++p) {
    const CutPiece& piece = enrichment_->surface(cut).pieces[p];
    out.append(cut_face_quadrature(nodes_.cells, cell_search_->near_piece(piece, dimension()), piece, hair));
  }
  return out;
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

MeshlessDomain::CutCellPoints MeshlessDomain::cut_cell_points() const {
  return cut_cells_ ? cut_cells_->points(nodes_, *cell_search_, *enrichment_) : CutCellPoints{};
}

void MeshlessDomain::visit_cut_cell_reach(const std::function<void(std::span<const Index>)>& visit) const {
  if (cut_cell_points_grow()) cut_cells_->visit_reach(nodes_, *cell_search_, *enrichment_, visit);
}

MeshlessDomain::~MeshlessDomain() = default;
MeshlessDomain::MeshlessDomain(MeshlessDomain&&) noexcept = default;

const Mesh& MeshlessDomain::background() const {
  KERF_CHECK(background_, "this meshless domain has no background mesh");
  return *background_;
}

ShapeTable MeshlessDomain::shapes_at(std::span<const Vec3> points, const std::string& what, Index group_size) const {
  return shape_table(nodes_, *index_, basis_, points, what, error_context_, mls_remedy(), enrichment(), growing_,
                     nullptr, group_size);
}

NeighborLists MeshlessDomain::supports_covering(std::span<const Vec3> points, Index group_size) const {
  return covering_supports(*index_, points, group_size);
}

std::vector<Index> MeshlessDomain::refresh_rows(ShapeTable& table, std::span<const Vec3> points,
                                                std::span<const Index> rows, const std::string& what) const {
  if (!enrichment_ || rows.empty()) return {};
  return refresh_shape_rows(table, nodes_, basis_, points, rows, *enrichment_, what, error_context_, mls_remedy());
}

std::vector<Index> MeshlessDomain::rows_the_growth_may_change(const ShapeTable& table, std::span<const Vec3> points,
                                                              std::span<const Index> rows) const {
  if (!enrichment_) return {};
  std::vector<Index> out;
  out.reserve(rows.size());
  for (Index p : rows)
    if (enrichment_->growth_may_change(points[p], table.neighbours.of(p))) out.push_back(p);
  return out;
}

std::string MeshlessDomain::mls_remedy() const {
  return enrichment_ ? "expected a larger support, a linear basis, or more nodes there (a cut hides the nodes on "
                       "its other side)"
                     : "expected a larger support, a linear basis, or more nodes there";
}

std::vector<Index> MeshlessDomain::update_shapes_for_cuts(double t, std::vector<Index>* rows,
                                                          std::vector<Index>* volumes,
                                                          const std::function<void(Index)>& after_row) {
  if (!enrichment_) return {};
  std::vector<Index> changed = enrichment_->advance_to(t);
  if (changed.empty()) return changed;
  if (volumes) *volumes = cut_cells_ ? cut_cells_->update(nodes_, *cell_search_, *enrichment_) : std::vector<Index>{};
  // The rows a changed node appears in, from the transposed neighbour lists.
  if (covered_.size() == 0) transpose_rows(at_nodes_.neighbours, nodes_.size(), covered_, slot_row_);
  std::vector<Index> touched = lists_holding(covered_, slot_row_, nodes_.size(), changed);
  if (smoothing_) {
    smoothing_->set_cuts(*enrichment_, nodes_);
    smoothing_->refresh(at_nodes_, touched, nodes_, basis_, *enrichment_, error_context_, mls_remedy());
    if (after_row) {  // on the region's threads, as refresh_shape_rows calls it
      const Index count = static_cast<Index>(touched.size());
      ParallelFailure failure;
#pragma omp parallel for schedule(dynamic, 16)
      for (Index i = 0; i < count; ++i) failure.run([&] { after_row(touched[i]); });
      failure.rethrow_if_failed();
    }
  } else {
    // Only the rows whose factors changed: phi moved at their point.
    touched = refresh_shape_rows(at_nodes_, nodes_, basis_, nodes_.positions,
                                 rows_the_growth_may_change(at_nodes_, nodes_.positions, touched), *enrichment_,
                                 "the node", error_context_, mls_remedy(), nullptr, after_row);
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
  return boundary_points(facets, collapsed_gauss(dimension() - 1, points_per_direction));
}

BoundaryPoints MeshlessDomain::boundary_points(std::span<const Index> facets, const QuadratureRule& rule) const {
  const int fdim = dimension() - 1;
  const Mesh& mesh = boundary_mesh();
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
