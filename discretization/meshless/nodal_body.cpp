#include "discretization/meshless/nodal_body.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>

#include "core/check.h"
#include "discretization/meshless/mls_shape.h"
#include "discretization/meshless/point_integration.h"

namespace kerf {
namespace {

/// Node I's part of the terms (its slots and its sums), overwritten.
void pair_row(const NodeSet& nodes, const ShapeTable& table, std::span<const double> volume, double c, double mu,
              Index I, StabilizationPairs& t) {
  const int dim = nodes.dimension;
  auto near = table.neighbours.of(I);
  const Index s0 = table.neighbours.start[I];
  const Vec3& xI = nodes.positions[I];
  // One pass: the pair weights w_IJ and, unscaled, sum w X and sum w X X^T
  // (X = x_J - x_I); the scale c mu V_I / sum w |X|^2 is known at the end.
  double normaliser = 0.0, sum[3] = {}, moment[3][3] = {};
  for (std::size_t j = 0; j < near.size(); ++j) {
    const Vec3& xJ = nodes.positions[near[j]];
    double w = near[j] == I ? 0.0 : quartic_weight_value(xJ, xI, nodes.support[I]);
    if (!table.weight_factor.empty()) w *= table.weight_factor[s0 + j];  // no pairs across a cut
    t.stiffness[s0 + j] = w;
    const Vec3 X = xJ - xI;
    normaliser += w * X.squaredNorm();
    for (int i = 0; i < dim; ++i) {
      sum[i] += w * X[i];
      for (int l = 0; l < dim; ++l) moment[i][l] += w * X[i] * X[l];
    }
  }
  // A node a cut left alone on its side has no pairs (and no normaliser).
  const double scale = normaliser > 0.0 ? c * mu * volume[I] / normaliser : 0.0;
  for (std::size_t j = 0; j < near.size(); ++j) t.stiffness[s0 + j] *= scale;
  for (int i = 0; i < 3; ++i) {
    t.lever_sum[3 * I + i] = scale * sum[i];
    for (int l = 0; l < 3; ++l) t.lever_moment[9 * I + 3 * i + l] = scale * moment[i][l];
  }
}

}  // namespace

NodalBody::NodalBody(const Scene& scene, MeshlessDomain domain, RankShare share)
    : MeshlessBody(scene, std::move(domain)),
      stabilized_(scene.discretization.meshless.stabilization == NodalStabilization::hourglass),
      vci_(scene.discretization.meshless.vci == VciOrder::linear) {
  const NodeSet& nodes = domain_.nodes();
  const EssentialMethod essential = essential_method(scene.discretization.meshless, Method::nodal);
  if (essential != EssentialMethod::parameters)
    // 2 points a direction: the closed boundary's rule there (integration constraint).
    constraints_ = std::make_unique<WeakBoundaryConditions>(
        scene, domain_, law_, essential == EssentialMethod::nitsche, collapsed_gauss(domain_.dimension() - 1, 2),
        WeakBoundaryConditions::VolumePoints{domain_.at_nodes(), nodes.volume, nodes.positions});
  integrate_cut_cells();
  share_nodes(share);
  if (stabilized_) {
    const std::size_t slots = domain_.at_nodes().neighbours.index.size();
    pairs_ = {std::vector<double>(slots, 0.0), std::vector<double>(3 * nodes.size(), 0.0),
              std::vector<double>(9 * nodes.size(), 0.0)};
    for (Index I = 0; I < nodes.size(); ++I)
      pair_row(nodes, domain_.at_nodes(), point_volume_, default_stabilization, law_.lame().mu, I, pairs_);
  }
  if (scene.discretization.meshless.stabilization == NodalStabilization::nsni)
    natural_ = std::make_unique<NaturalStabilization>(nodes, scene.discretization.meshless.basis, domain_.at_nodes(),
                                                      domain_.enrichment(), law_.lame(), cell_moments());
  const int dim = domain_.dimension();
  if (dim == 3) position4_ = padded_positions(nodes.positions);
  body_load_ = Vector::Zero(dof_count());
  for (Index I = 0; I < nodes.size(); ++I) weigh_node(I);
  load_ = body_load_;
  domain_.add_boundary_loads(scene.boundary, load_);
  if (constraints_)
    dirichlet_ = domain_.nodal_constraints(
        scene, [](const BoundaryCondition& bc) { return bc.select.kind == Selection::Kind::point; });
  else
    dirichlet_ = domain_.nodal_constraints(scene, [](const BoundaryCondition&) { return true; });
  correct_test_gradients();
}

void NodalBody::weigh_node(Index I) {
  const int dim = domain_.dimension();
  for (int i = 0; i < dim; ++i) body_load_[dim * I + i] = density_ * domain_.nodes().volume[I] * gravity_[i];
}

void NodalBody::integrate_cut_cells() {
  point_volume_ = domain_.nodes().volume;
  rest_moments_.clear();
  cut_points_.reset();
  cut_schedule_ = {};
  cut_cells_ = 0;
  MeshlessDomain::CutCellPoints points = domain_.cut_cell_points();
  if (points.position.empty()) return;
  for (double& v : points.node_volume) v = std::max(v, 0.0);  // round-off of a whole cell taken away
  point_volume_ = std::move(points.node_volume);
  rest_moments_ = std::move(points.node_moment);
  cut_cells_ = points.cells;
  ShapeTable shapes = domain_.shapes_at(points.position, "a point of a cell at a cut");
  cut_points_ = std::make_unique<PointIntegration>(std::move(shapes), std::move(points.position),
                                                   std::move(points.weight), domain_.nodes().positions, 1);
  own_cut_points_ = even_part(cut_points_->point_count(), share_.rank, share_.count);
}

std::vector<Index> NodalBody::reintegrate_cut_cells() {
  const std::vector<double> before = point_volume_;
  integrate_cut_cells();
  std::vector<Index> changed;
  for (Index I = 0; I < node_count(); ++I)
    if (point_volume_[I] != before[I]) changed.push_back(I);
  return changed;
}

void NodalBody::add_figures(std::map<std::string, double>& extras) const {
  MeshlessBody::add_figures(extras);
  if (!cut_points_) return;
  extras["cut_cells_by_parts"] = static_cast<double>(cut_cells_);
  extras["cut_cell_points"] = static_cast<double>(cut_points_->point_count());
  extras["cut_cell_points_reduced_basis"] = static_cast<double>(cut_points_->shapes().reduced_basis_points());
}

void NodalBody::add_cut_cell_forces(const Vector& u, Vector& f) const {
  if (!cut_points_) return;
  const ShapeTable& table = cut_points_->shapes();
  const Index count = cut_points_->point_count();
  cut_stress_.assign(count, Mat3::Zero());
#pragma omp parallel for schedule(static)
  for (Index p = own_cut_points_.first; p < own_cut_points_.second; ++p)
    cut_stress_[p] = cut_points_->weight(p) * law_.stress(deformation_gradient(table, p, u));
  cut_points_->gather(cut_stress_, cut_force_);
  f += cut_force_;
}

double NodalBody::cut_cell_energy(const Vector& u) const {
  if (!cut_points_) return 0.0;
  double energy = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : energy)
  for (Index p = own_cut_points_.first; p < own_cut_points_.second; ++p)
    energy += cut_points_->weight(p) * law_.energy(deformation_gradient(cut_points_->shapes(), p, u));
  return energy;
}

std::vector<Vec3> NodalBody::cell_moments() const {
  if (!rest_moments_.empty()) return rest_moments_;
  const std::vector<Vec3>* split = domain_.split_second_moments();
  return split ? *split : dual_cell_second_moments(domain_.nodes().cells);
}

void NodalBody::correct_test_gradients() {
  const int dim = domain_.dimension();
  VolumeTerms volume = volume_terms(domain_.at_nodes(), point_volume_, node_count());
  if (cut_points_) {  // the cells at a cut are integrated by their parts' points
    const VolumeTerms parts = volume_terms(cut_points_->shapes(), cut_points_->weights(), node_count());
    for (auto [sum, part] : {std::pair{&volume.gradient_sum, &parts.gradient_sum},
                             std::pair{&volume.magnitude, &parts.magnitude}, std::pair{&volume.value_sum, &parts.value_sum}})
      for (std::size_t k = 0; k < sum->size(); ++k) (*sum)[k] += (*part)[k];
  }
  const std::vector<double>& boundary = domain_.boundary_terms();
  const ConstraintResidual plain = constraint_residual(boundary, volume, dim);
  if (!vci_) return record_constraint(plain, std::nullopt);
  test_offsets_ = consistent_offsets(domain_.at_nodes(), domain_.nodes().volume, boundary, volume);
  const VolumeTerms tested = volume_terms(domain_.at_nodes(), domain_.nodes().volume, node_count(), test_offsets_);
  record_constraint(constraint_residual(boundary, tested, dim), plain);
}

void NodalBody::share_nodes(RankShare share) {
  share_ = share;
  own_nodes_ = even_part(node_count(), share.rank, share.count);
  // Its own nodes and their neighbours: the rows its nodes' terms reach.
  std::vector<char> reached(node_count(), 0);
  for (Index I = own_nodes_.first; I < own_nodes_.second; ++I)
    for (Index J : domain_.at_nodes().neighbours.of(I)) reached[J] = 1;
  if (cut_points_) {
    own_cut_points_ = even_part(cut_points_->point_count(), share.rank, share.count);
    for (Index p = own_cut_points_.first; p < own_cut_points_.second; ++p)
      for (Index J : cut_points_->shapes().neighbours.of(p)) reached[J] = 1;
  }
  // A growing cut's points move: whatever rank gets them, the rows they may reach.
  domain_.visit_cut_cell_reach([&](std::span<const Index> nodes) {
    for (Index J : nodes) reached[J] = 1;
  });
  if (constraints_) {
    constraints_->share(share);
    constraints_->mark_reached(reached);
  }
  touched_nodes_ = touched_node_list(std::move(reached), own_nodes_);
}

void NodalBody::begin_time_step(const Vector& u) {
  if (!constraints_) return;
  const NodeSet& nodes = domain_.nodes();
  constraints_->refresh_alpha(u,
                              WeakBoundaryConditions::VolumePoints{domain_.at_nodes(), nodes.volume, nodes.positions});
}

CutUpdate NodalBody::update_for_cuts(double t) {
  // Every rank brings the whole domain's shape functions up to t (the same
  // on each); the neighbour lists, hence each rank's touched rows, stay.
  CutUpdate update;
  std::vector<Index> rows, resized;
  // A recomputed row's stabilisation pairs join its pass (they read its cut factors).
  const std::function<void(Index)> pairs_of = [&](Index I) {
    pair_row(domain_.nodes(), domain_.at_nodes(), point_volume_, default_stabilization, law_.lame().mu, I, pairs_);
  };
  const std::vector<Index> changed =
      domain_.update_shapes_for_cuts(t, &rows, &resized, stabilized_ ? pairs_of : std::function<void(Index)>{});
  if (changed.empty()) return update;
  update.nodes = static_cast<Index>(changed.size());
  update.changed_nodes = changed;
  update.points = static_cast<Index>(rows.size());
  for (Index I : resized) weigh_node(I);  // the cut moved volume (and mass) across it
  if (domain_.cut_cell_points_grow()) {  // the cells at the cut changed: their points, and the nodes' weights
    const std::vector<Index> reweighed = reintegrate_cut_cells();
    resized.insert(resized.end(), reweighed.begin(), reweighed.end());
  }
  if (stabilized_ && !resized.empty()) {
    // The pairs of a node whose volume changed scale with it: its row again, with the volume now.
    std::sort(resized.begin(), resized.end());
    resized.erase(std::unique(resized.begin(), resized.end()), resized.end());
    const Index count = static_cast<Index>(resized.size());
#pragma omp parallel for schedule(dynamic, 16)
    for (Index r = 0; r < count; ++r) pairs_of(resized[r]);
  }
  if (natural_) {
    natural_->refresh(domain_.nodes(), domain_.basis(), domain_.at_nodes(), rows,
                      domain_.enrichment());
    if (!resized.empty()) natural_->set_moments(cell_moments());
  }
  if (!resized.empty() || domain_.boundary_loads_touch(changed)) {
    load_ = body_load_;
    domain_.add_boundary_loads(boundary_, load_);
  }
  if (constraints_) {
    std::vector<char> moved(node_count(), 0);
    for (Index I : changed) moved[I] = 1;
    const NodeSet& nodes = domain_.nodes();
    constraints_->update_for_cuts(domain_, moved,
                                  WeakBoundaryConditions::VolumePoints{domain_.at_nodes(), nodes.volume, nodes.positions});
  }
  if (vci_) {  // the constraint after a growth costs a boundary update: only VCI needs it
    domain_.update_boundary_terms();
    correct_test_gradients();
  }
  return update;
}

template <int Dim, bool Stabilized>
void NodalBody::force_kernel(const Vector& u, Vector& f) const {
  const NodeSet& nodes = domain_.nodes();
  const ShapeTable& table = domain_.at_nodes();
  const Index N = nodes.size(), dofs = Dim * N;
  const Index* start = table.neighbours.start.data();
  const Index* index = table.neighbours.index.data();
  const double* g = table.gradient.data();
  const double* k = pairs_.stiffness.data();
  const double* offset = test_offsets_.empty() ? nullptr : test_offsets_.data();
  const Vec3* x = nodes.positions.data();
  f.resize(dofs);
  // Sized here, not inside the region: an allocation failure must not be thrown in it.
  thread_forces_.resize(static_cast<std::size_t>(omp_get_max_threads()) * dofs);
#pragma omp parallel
  {
    const int thread = omp_get_thread_num(), threads = omp_get_num_threads();
    double* mine = thread_forces_.data() + static_cast<std::size_t>(thread) * dofs;
    std::fill(mine, mine + dofs, 0.0);
    // One pass over the nodes: F_I from the neighbours, then each neighbour's
    // share of V_I P(F_I) grad phi_K(x_I) and of the pair terms, scattered into
    // this thread's own force vector.
#pragma omp for schedule(static)
    for (Index I = own_nodes_.first; I < own_nodes_.second; ++I) {
      const Index s0 = start[I], s1 = start[I + 1];
      // Plain scalar accumulators: Eigen's fixed matrices here end up on the
      // stack, and the loop then waits on store-to-load forwarding.
      // h = grad u at x_I; d = sum_K u_K (k_IK X_IK)^T for the stabilisation.
      // The levers k_IK X_IK are formed from the positions (cached: a node's
      // neighbours are near it in memory) rather than read from a table.
      double h[Dim][Dim] = {}, d[Dim][Dim] = {};
      const Vec3& xI = x[I];
      for (Index s = s0; s < s1; ++s) {
        const Index K = index[s];
        const double* uK = &u[Dim * K];
        const double* gs = g + Dim * s;
        for (int i = 0; i < Dim; ++i)
          for (int l = 0; l < Dim; ++l) h[i][l] += uK[i] * gs[l];
        if constexpr (Stabilized) {
          double cs[Dim];
          for (int l = 0; l < Dim; ++l) cs[l] = k[s] * (x[K][l] - xI[l]);
          for (int i = 0; i < Dim; ++i)
            for (int l = 0; l < Dim; ++l) d[i][l] += uK[i] * cs[l];
        }
      }
      Mat3 F = Mat3::Identity();
      for (int i = 0; i < Dim; ++i)
        for (int l = 0; l < Dim; ++l) F(i, l) += h[i][l];
      const Mat3 P = law_.stress(F);
      const double* uI = &u[Dim * I];
      // q = V_I P - sum_J k_IJ e_IJ X_IJ^T, the second part through F_I's
      // dependence on the neighbours: sum_J k e X^T = d - u_I s_I^T - h M_I.
      double q[Dim][Dim], vp[Dim][Dim];
      for (int i = 0; i < Dim; ++i)
        for (int l = 0; l < Dim; ++l) {
          q[i][l] = vp[i][l] = point_volume_[I] * P(i, l);
          if constexpr (Stabilized) {
            double hM = 0.0;
            for (int m = 0; m < Dim; ++m) hM += h[i][m] * pairs_.lever_moment[9 * I + 3 * m + l];
            q[i][l] -= d[i][l] - uI[i] * pairs_.lever_sum[3 * I + l] - hM;
          }
        }
      double pushI[Dim] = {};
      for (Index s = s0; s < s1; ++s) {
        double* fK = mine + Dim * index[s];
        const double* gs = g + Dim * s;
        double t[Dim];
        for (int i = 0; i < Dim; ++i) {
          double qg = 0.0;
          for (int l = 0; l < Dim; ++l) qg += q[i][l] * gs[l];
          if (offset)  // VCI tests V P (not the Galerkin pair terms) with its offset too
            for (int l = 0; l < Dim; ++l) qg += vp[i][l] * offset[Dim * s + l];
          t[i] = qg;
        }
        if constexpr (Stabilized) {
          // k_IK e_IK = k_IK (u_K - u_I) - H_I (k_IK X_IK): pulls K, pushes I.
          const Index K = index[s];
          const double* uK = &u[Dim * K];
          double cs[Dim];
          for (int l = 0; l < Dim; ++l) cs[l] = k[s] * (x[K][l] - xI[l]);
          for (int i = 0; i < Dim; ++i) {
            double e = k[s] * (uK[i] - uI[i]);
            for (int l = 0; l < Dim; ++l) e -= h[i][l] * cs[l];
            t[i] += e;
            pushI[i] += e;
          }
        }
        for (int i = 0; i < Dim; ++i) fK[i] += t[i];
      }
      for (int i = 0; i < Dim; ++i) mine[Dim * I + i] -= pushI[i];
    }
#pragma omp for schedule(static)
    for (Index d = 0; d < dofs; ++d) {
      double sum = 0.0;
      for (int t = 0; t < threads; ++t) sum += thread_forces_[static_cast<std::size_t>(t) * dofs + d];
      f[d] = sum;
    }
  }
}

void NodalBody::internal_force_baseline(const Vector& u, Vector& f) const {
  KERF_CHECK(domain_.dimension() == 3, "internal: the baseline pass is the 3D one");
  nodal_force_3d(force_tables(), law_, u, f, scratch_, VectorUnit::baseline);
  if (natural_) natural_->add_forces(domain_.at_nodes(), own_nodes_, u, f);
  add_cut_cell_forces(u, f);
}

std::size_t NodalBody::force_pass_bytes() const {
  const ShapeTable& table = domain_.at_nodes();
  const std::size_t dim = domain_.dimension(), slots = table.neighbours.index.size(), N = node_count();
  const std::size_t threads = static_cast<std::size_t>(omp_get_max_threads());
  std::size_t bytes = slots * (sizeof(Index) + dim * sizeof(double)) + N * (sizeof(Index) + sizeof(double));
  if (stabilized_)
    bytes += slots * sizeof(double) + N * sizeof(double) * (12 + 3);  // k; sums, moments, positions
  if (!test_offsets_.empty()) bytes += slots * dim * sizeof(double);  // VCI's offsets
  if (natural_) bytes += natural_->table_bytes() + N * dim * sizeof(double) * 2 * threads;  // and its own pass
  if (cut_points_) {  // split cells' points: rows, weights, stresses written and gathered, their force vector
    const std::size_t cut_slots = cut_points_->shapes().neighbours.index.size(), P = cut_points_->point_count();
    bytes += cut_slots * (sizeof(Index) + dim * sizeof(double)) +
             P * (sizeof(Index) + sizeof(double) + 2 * 9 * sizeof(double)) + 2 * N * dim * sizeof(double);
  }
  // u read (3D: and copied 4 to a node), each thread's forces zeroed, scattered into and summed, f written
  const std::size_t lanes = dim == 3 ? 4 : dim;
  return bytes + N * sizeof(double) * (2 * dim + (dim == 3 ? lanes : 0) + 2 * lanes * threads);
}

NodalForceTables NodalBody::force_tables() const {
  const ShapeTable& table = domain_.at_nodes();
  NodalForceTables t;
  t.nodes = node_count();
  std::tie(t.pass_begin, t.pass_end) = own_nodes_;
  if (partitioned()) t.touched = touched_nodes_;
  t.start = table.neighbours.start.data();
  t.index = table.neighbours.index.data();
  t.slots = static_cast<Index>(table.neighbours.index.size());
  t.gradient = table.gradient.data();
  t.volume = point_volume_.data();
  t.position4 = aligned_32(position4_);
  if (stabilized_) {
    t.stiffness = pairs_.stiffness.data();
    t.lever_sum = pairs_.lever_sum.data();
    t.lever_moment = pairs_.lever_moment.data();
  }
  if (!test_offsets_.empty()) t.test_offset = test_offsets_.data();
  return t;
}

void NodalBody::internal_force(const Vector& u, Vector& f) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  if (domain_.dimension() == 3)
    nodal_force_3d(force_tables(), law_, u, f, scratch_);
  else
    stabilized_ ? force_kernel<2, true>(u, f) : force_kernel<2, false>(u, f);
  if (natural_) natural_->add_forces(domain_.at_nodes(), own_nodes_, u, f);
  add_cut_cell_forces(u, f);
  if (constraints_) constraints_->terms(u, &f);
}

Vec3 NodalBody::weak_reaction(const Vector& u, const Selection& selection) const {
  return constraints_ ? constraints_->reaction(u, selection) : Vec3::Zero();
}

double NodalBody::energies(const Vector& u, double* stabilization) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  const int dim = domain_.dimension();
  const NodeSet& nodes = domain_.nodes();
  const ShapeTable& table = domain_.at_nodes();
  double material = 0.0, stab = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : material, stab)
  for (Index I = own_nodes_.first; I < own_nodes_.second; ++I) {
    const Mat3 F = deformation_gradient(table, I, u);
    material += point_volume_[I] * law_.energy(F);
    if (!stabilized_) continue;
    auto near = table.neighbours.of(I);
    for (std::size_t j = 0; j < near.size(); ++j) {
      const Index s = table.neighbours.start[I] + static_cast<Index>(j);
      Vec3 e = Vec3::Zero(), X = nodes.positions[near[j]] - nodes.positions[I];
      for (int i = 0; i < dim; ++i) e[i] = u[dim * near[j] + i] - u[dim * I + i];
      e -= (F - Mat3::Identity()) * X;
      stab += 0.5 * pairs_.stiffness[s] * e.squaredNorm();
    }
  }
  if (natural_) stab += natural_->energy(table, own_nodes_, u);
  material += cut_cell_energy(u);
  if (stabilization) *stabilization = stab;
  return material + stab + (constraints_ ? constraints_->terms(u, nullptr) : 0.0);
}

double NodalBody::strain_energy(const Vector& u) const { return energies(u, nullptr); }

double NodalBody::stabilization_energy(const Vector& u) const {
  double stab = 0.0;
  energies(u, &stab);
  return stab;
}

void NodalBody::add_stabilization_block(Index I, std::vector<double>& block) const {
  const int dim = domain_.dimension();
  const NodeSet& nodes = domain_.nodes();
  const ShapeTable& table = domain_.at_nodes();
  auto near = table.neighbours.of(I);
  const Index n = static_cast<Index>(near.size()), s0 = table.neighbours.start[I], size = n * dim;
  const double* g = table.gradients_of(I);
  // e_IJ = sum_a b_J[a] u_a with b_J[a] = [a = J] - [a = I] - grad phi_a(x_I) . X_IJ,
  // S = sum_J k_IJ b_J b_J^T = B^T diag(k) B, one matrix product (rows of B: the b_J).
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd k(n);
  for (Index j = 0; j < n; ++j) {
    k[j] = pairs_.stiffness[s0 + j];
    if (k[j] == 0.0) continue;
    const Vec3 X = nodes.positions[near[j]] - nodes.positions[I];
    for (Index a = 0; a < n; ++a) {
      double gX = 0.0;
      for (int l = 0; l < dim; ++l) gX += g[dim * a + l] * X[l];
      B(j, a) = (a == j ? 1.0 : 0.0) - (near[a] == I ? 1.0 : 0.0) - gX;
    }
  }
  const Eigen::MatrixXd S = B.transpose() * k.asDiagonal() * B;
  for (Index a = 0; a < n; ++a)
    for (Index c = 0; c < n; ++c)
      for (int i = 0; i < dim; ++i) block[(dim * a + i) * size + dim * c + i] += S(a, c);
}

void NodalBody::assemble_tangent(const Vector& u, const BlockSink& sink, std::span<const double> offsets) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  BlockExtra stabilization;
  if (stabilized_) stabilization = [this](Index I, std::vector<double>& block) { add_stabilization_block(I, block); };
  if (natural_)
    stabilization = [this](Index I, std::vector<double>& block) { natural_->add_block(domain_.at_nodes(), I, block); };
  if (schedule_.colours.empty())
    schedule_ = only_points(schedule_points(domain_.at_nodes(), domain_.nodes().positions), own_nodes_);
  assemble_material_blocks(domain_.at_nodes(), schedule_, point_volume_, law_, u, sink, stabilization, offsets);
  if (cut_points_) {
    if (cut_schedule_.colours.empty())
      cut_schedule_ = only_points(cut_points_->schedule(), own_cut_points_);
    assemble_material_blocks(cut_points_->shapes(), cut_schedule_, cut_points_->weights(), law_, u, sink);
  }
  if (constraints_) constraints_->add_tangent(u, sink);
}

void NodalBody::tangent(const Vector& u, const BlockSink& sink, Vector* f) const {
  assemble_tangent(u, sink, test_offsets_);
  if (f) internal_force(u, *f);
}

void NodalBody::galerkin_tangent(const Vector& u, const BlockSink& sink) const { assemble_tangent(u, sink, {}); }

void NodalBody::visit_couplings(const CouplingVisitor& visit) const {
  std::vector<Index> dofs;
  for (Index I = 0; I < node_count(); ++I) {
    neighbour_dofs(domain_.at_nodes(), I, dofs);
    visit(dofs);
  }
  if (domain_.cut_cell_points_grow()) {
    domain_.visit_cut_cell_reach([&](std::span<const Index> nodes) {
      dofs.clear();
      for (Index J : nodes)
        for (int i = 0; i < domain_.dimension(); ++i) dofs.push_back(domain_.dimension() * J + i);
      visit(dofs);
    });
  } else {
    for (Index p = 0; cut_points_ && p < cut_points_->point_count(); ++p) {
      neighbour_dofs(cut_points_->shapes(), p, dofs);
      visit(dofs);
    }
  }
  if (constraints_) constraints_->visit_couplings(visit);
}

Vector NodalBody::lumped_mass() const {
  const int dim = domain_.dimension();
  Vector m = Vector::Zero(dof_count());
  for (Index I = own_nodes_.first; I < own_nodes_.second; ++I)
    for (int i = 0; i < dim; ++i) m[dim * I + i] = density_ * domain_.nodes().volume[I];
  return m;
}

void NodalBody::consistent_mass(const BlockSink& sink) const {
  // Nodal integration has no consistent mass: the lumped one is the method's mass.
  Vector m = lumped_mass();
  for (Index d = 0; d < dof_count(); ++d) sink(std::span<const Index>(&d, 1), std::span<const double>(&m[d], 1));
}

}  // namespace kerf
