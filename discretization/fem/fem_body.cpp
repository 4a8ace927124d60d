#include "discretization/fem/fem_body.h"

#include <omp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>

#include "core/check.h"
#include "core/parallel_failure.h"
#include "discretization/fem/fragment_quadrature.h"
#include "discretization/fem/simplex_quadrature.h"
#include "discretization/fem/simplex_shape.h"
#include "discretization/fem/symmetric_simplex_quadrature.h"
#include "discretization/prescribed_dofs.h"
#include "geometry/mesh_ordering.h"
#include "geometry/point_location.h"
#include "problem/selection.h"

namespace kerf {
namespace {

/// Calls body.template operator()<Dim, Npc>() for the mesh's cell type.
template <class Body>
void dispatch_cell(int dim, int order, Body&& body) {
  if (dim == 3 && order == 1) body.template operator()<3, 4>();
  else if (dim == 3) body.template operator()<3, 10>();
  else if (order == 1) body.template operator()<2, 3>();
  else body.template operator()<2, 6>();
}


/// Per-element results of one quadrature pass.
template <int Dim, int Npc>
struct ElementWork {
  static constexpr int n = Dim * Npc;
  Eigen::Matrix<double, n, 1> force;
  Eigen::Matrix<double, n, n, Eigen::RowMajor> stiffness;
  std::array<Index, n> dofs;
  double energy = 0.0;
};

}  // namespace

namespace {
Mesh ordered_for_locality(Mesh mesh) {
  order_for_locality(mesh);
  return mesh;
}

SplitOptions split_options(const Scene& scene) {
  SplitOptions options;
  options.snap = scene.discretization.fem.split_snap;
  if (options.snap == 0.0) options.min_fraction = 0.0;  // the cut exactly as given
  options.over_cut = scene.discretization.fem.split_front == SplitFront::over;
  return options;
}

/// fem.split_front: subdivide: the mesh refined along the pieces' front.
std::optional<FrontRefinement> front_refinement(const Scene& scene, const Mesh& mesh,
                                                std::span<const CutPiece> pieces) {
  if (pieces.empty() || scene.discretization.fem.split_front != SplitFront::subdivide) return std::nullopt;
  return refine_front(mesh, pieces);
}
}  // namespace

FemBody::FemBody(const Scene& scene, Mesh mesh, RankShare share, std::span<const CutPiece> split_along)
    : FemBody(Ordered{}, scene, ordered_for_locality(std::move(mesh)), share, split_along) {}

FemBody::FemBody(const Scene& scene, Mesh mesh, FemPiece piece)
    : FemBody(Ordered{}, scene, std::move(mesh), RankShare{}, {}, nullptr, std::move(piece)) {}

namespace {

/// The gradients of a cell's `npc` shape functions at one point (`dN`, in
/// reference coordinates) in physical ones, into `grad`; returns det J (the
/// caller refuses a non-positive one, leaving `grad` unused).
template <int Dim>
Eigen::Matrix<double, Dim, Dim> reference_jacobian(const Mesh& mesh, std::span<const Index> nodes, const double* dN) {
  Eigen::Matrix<double, Dim, Dim> J = Eigen::Matrix<double, Dim, Dim>::Zero();  // dX/dxi
  for (std::size_t a = 0; a < nodes.size(); ++a)
    for (int i = 0; i < Dim; ++i)
      for (int k = 0; k < Dim; ++k) J(i, k) += mesh.nodes[nodes[a]][i] * dN[a * Dim + k];
  return J;
}

/// det J of a cell at one point (`dN`, the reference gradients there).
double jacobian_determinant(const Mesh& mesh, std::span<const Index> nodes, const double* dN) {
  return mesh.dimension == 3 ? reference_jacobian<3>(mesh, nodes, dN).determinant()
                             : reference_jacobian<2>(mesh, nodes, dN).determinant();
}

template <int Dim>
double physical_gradients(const Mesh& mesh, std::span<const Index> nodes, const double* dN, double* grad) {
  const int npc = static_cast<int>(nodes.size());
  const Eigen::Matrix<double, Dim, Dim> J = reference_jacobian<Dim>(mesh, nodes, dN);
  const double det = J.determinant();
  if (!(det > 0.0)) return det;
  const Eigen::Matrix<double, Dim, Dim> Jinv = J.inverse();
  for (int a = 0; a < npc; ++a)
    for (int l = 0; l < Dim; ++l) {
      double sum = 0.0;
      for (int k = 0; k < Dim; ++k) sum += dN[a * Dim + k] * Jinv(k, l);
      grad[a * Dim + l] = sum;
    }
  return det;
}

double physical_gradients(const Mesh& mesh, std::span<const Index> nodes, const double* dN, double* grad) {
  return mesh.dimension == 3 ? physical_gradients<3>(mesh, nodes, dN, grad)
                             : physical_gradients<2>(mesh, nodes, dN, grad);
}

/// Names the cell by its corners' mean: kerf's cell numbers follow its locality order, not the file's.
[[noreturn]] void refuse_inverted(const Mesh& mesh, Index c, std::size_t q, double det) {
  Vec3 centre = Vec3::Zero();
  const int corners = mesh.dimension + 1;
  for (int a = 0; a < corners; ++a) centre += mesh.nodes[mesh.cell(c)[a]] / corners;
  throw Error(detail::concat("mesh cell ", c, " (corners centred at ", centre.x(), ", ", centre.y(), ", ", centre.z(),
                             " m) is inverted or degenerate (det J = ", det, " at quadrature point ", q,
                             "); check the mesh"));
}

/// The shape values and reference gradients at each of `rule`'s points, point after point.
void rule_shapes(int dim, int order, int npc, const QuadratureRule& rule, std::vector<double>& N,
                 std::vector<double>& dN) {
  N.resize(rule.points.size() * npc);
  dN.resize(rule.points.size() * npc * dim);
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    simplex_shape_values(dim, order, rule.points[q], &N[q * npc]);
    simplex_shape_gradients(dim, order, rule.points[q], &dN[q * npc * dim]);
  }
}

}  // namespace

FemBody::FemBody(Ordered, const Scene& scene, Mesh mesh, RankShare share, std::span<const CutPiece> split_along,
                 const FemBody* previous, std::optional<FemPiece> piece)
    : piece_(std::move(piece)),
      front_(front_refinement(scene, mesh, split_along)),
      original_(front_ ? std::move(front_->mesh) : std::move(mesh)),
      split_(split_along.empty() ? std::nullopt
                                 : std::optional<CellSplit>(split_cells(original_, split_along, split_options(scene)))),
      split_pieces_(split_along.begin(), split_along.end()),
      mesh_(split_ ? std::move(split_->mesh) : std::move(original_)),
      facets_(previous && !front_ ? previous->facets_ : boundary_facets(outline())),
      on_boundary_(previous && !front_ ? previous->on_boundary_ : boundary_node_flags(outline(), facets_)),
      locator_(previous && !front_ ? previous->locator_ : CellLocator(outline())),
      law_(scene.material),
      density_(scene.material.density) {
  const int dim = mesh_.dimension;
  if (split_) {
    copies_start_.assign(original_.cell_count() + 1, 0);
    for (Index p : split_->parent) ++copies_start_[p + 1];
    for (Index p = 0; p < original_.cell_count(); ++p) copies_start_[p + 1] += copies_start_[p];
  }
  share_cells(share);
  auto box = bounding_box(mesh_);
  domain_size_ = piece_ ? piece_->domain_size : (box[1] - box[0]).norm();
  npc_ = mesh_.nodes_per_cell();
  mass_rule_ = simplex_quadrature(dim, 2 * mesh_.order);
  rule_shapes(dim, mesh_.order, npc_, mass_rule_, mass_N_, mass_dN_);
  const QuadratureRule rule = simplex_quadrature(dim, element_descriptor(dim, mesh_.order).stiffness_degree);
  integrate_cells(rule, previous && !front_ ? previous : nullptr);
  if (scene.discretization.fem.volumetric == FemVolumetric::averaged_nodal) average_bulk_at_nodes(scene);
  build_loads(scene);
  build_constraints(scene);
}

void FemBody::integrate_cells(const QuadratureRule& rule, const FemBody* previous) {
  if (!split_ && !previous) return integrate_whole_cells(rule);
  const int dim = mesh_.dimension;
  const Index C = kept_cells();
  const std::size_t per_point = static_cast<std::size_t>(npc_) * dim;
  point_start_.assign(1, 0);
  grad_.reserve(static_cast<std::size_t>(C) * rule.points.size() * per_point);
  wdet_.reserve(static_cast<std::size_t>(C) * rule.points.size());
  std::vector<double> dN(per_point);
  for (Index c = 0; c < C; ++c) {
    auto nodes = mesh_.cell(c);
    QuadratureRule own;  // a copy's rule on its fragment; a whole cell uses `rule` itself
    const bool copy = split_ && !split_->whole(c);
    if (!copy && previous && previous->take_whole_cell(split_ ? split_->parent[c] : c, grad_, wdet_)) {
      point_start_.push_back(static_cast<Index>(wdet_.size()));
      continue;
    }
    if (copy) own = cell_rule(c, rule, /*constant_integrand=*/mesh_.order == 1);
    const QuadratureRule& cell = copy ? own : rule;
    for (std::size_t q = 0; q < cell.points.size(); ++q) {
      simplex_shape_gradients(dim, mesh_.order, cell.points[q], dN.data());
      grad_.resize(grad_.size() + per_point);
      const double det = physical_gradients(mesh_, nodes, dN.data(), grad_.data() + grad_.size() - per_point);
      if (!(det > 0.0)) refuse_inverted(mesh_, c, q, det);
      wdet_.push_back(cell.weights[q] * det);
    }
    point_start_.push_back(static_cast<Index>(wdet_.size()));
  }
}

void FemBody::integrate_whole_cells(const QuadratureRule& rule) {
  const int dim = mesh_.dimension;
  const Index C = kept_cells();
  const std::size_t points = rule.points.size(), per_point = static_cast<std::size_t>(npc_) * dim;
  std::vector<double> dN(points * per_point);  // the same reference gradients in every cell
  for (std::size_t q = 0; q < points; ++q)
    simplex_shape_gradients(dim, mesh_.order, rule.points[q], &dN[q * per_point]);
  point_start_.resize(static_cast<std::size_t>(C) + 1);
  for (Index c = 0; c <= C; ++c) point_start_[c] = c * static_cast<Index>(points);
  grad_.resize(static_cast<std::size_t>(C) * points * per_point);
  wdet_.resize(static_cast<std::size_t>(C) * points);
  Index inverted = C;  // the first inverted cell, as the serial loop would meet it
#pragma omp parallel for schedule(static) reduction(min : inverted)
  for (Index c = 0; c < C; ++c)
    for (std::size_t q = 0; q < points; ++q) {
      const std::size_t at = static_cast<std::size_t>(c) * points + q;
      const double det = physical_gradients(mesh_, mesh_.cell(c), &dN[q * per_point], &grad_[at * per_point]);
      if (!(det > 0.0)) {
        inverted = std::min(inverted, c);
        break;
      }
      wdet_[at] = rule.weights[q] * det;
    }
  if (inverted == C) return;
  for (std::size_t q = 0; q < points; ++q) {  // the message's point and determinant
    std::vector<double> unused(per_point);
    const double det = physical_gradients(mesh_, mesh_.cell(inverted), &dN[q * per_point], unused.data());
    if (!(det > 0.0)) refuse_inverted(mesh_, inverted, q, det);
  }
}

bool FemBody::take_whole_cell(Index parent, std::vector<double>& grad, std::vector<double>& wdet) const {
  const auto [first, last] = copies_of(parent);
  if (last - first != 1 || (split_ && !split_->whole(first))) return false;
  const std::size_t per_point = static_cast<std::size_t>(npc_) * mesh_.dimension;
  grad.insert(grad.end(), grad_.begin() + point_start_[first] * per_point, grad_.begin() + point_start_[last] * per_point);
  wdet.insert(wdet.end(), wdet_.begin() + point_start_[first], wdet_.begin() + point_start_[last]);
  return true;
}

QuadratureRule FemBody::cell_rule(Index c, const QuadratureRule& whole, bool constant_integrand) const {
  if (!split_ || split_->whole(c)) return whole;
  const std::span<const Vec3> fragment = split_->fragment(c);
  if (!constant_integrand) return fragment_quadrature(mesh_.dimension, fragment, whole);
  Vec3 centre = Vec3::Zero();
  for (int k = 0; k <= mesh_.dimension; ++k) centre += fragment[k] / (mesh_.dimension + 1);
  return {{centre}, {fragment_measure(mesh_.dimension, fragment)}};
}

std::unique_ptr<DiscreteBody> FemBody::split_along(const Scene& scene, std::span<const CutPiece> pieces) const {
  return std::unique_ptr<DiscreteBody>(new FemBody(Ordered{}, scene, outline(), share_, pieces, this));
}

Vector FemBody::carried_to(const DiscreteBody& next_body, const Vector& field) const {
  const auto* next = dynamic_cast<const FemBody*>(&next_body);
  const FrontRefinement* refined = next ? next->front() : nullptr;
  KERF_CHECK(next && (refined ? refined->parent.size() == static_cast<std::size_t>(next->outline().cell_count())
                              : next->outline().cell_count() == outline().cell_count() &&
                                    next->outline().node_count() == outline().node_count()),
             "internal: a split body's state carried to a body on another mesh");
  const int dim = mesh_.dimension;
  std::vector<double> N(npc_);
  Vector out = Vector::Zero(next->dof_count());
  for (Index c = 0; c < next->mesh_.cell_count(); ++c) {
    const Index cell = next->split_ ? next->split_->parent[c] : c;  // in next's outline
    const Index parent = refined ? refined->parent[cell] : cell;     // in this body's outline
    const bool child = refined && refined->child(cell);
    // This body's copy of the parent holding the new copy (cuts only grow: it
    // lies in one old fragment); a point inside it tells.
    auto [from, last] = copies_of(parent);
    if (last - from > 1) {
      const Vec3 inside = point_in_parent(*next, c, child ? refined->child_reference(cell) : std::span<const Vec3>{});
      for (Index old = from; old < last; ++old)
        if (fragment_holds(dim, split_->fragment(old), inside)) {
          from = old;
          break;
        }
    }
    const auto to_nodes = next->mesh_.cell(c), from_nodes = mesh_.cell(from);
    for (int a = 0; a < npc_; ++a) {
      if (!child) {
        for (int i = 0; i < dim; ++i) out[dim * to_nodes[a] + i] = field[dim * from_nodes[a] + i];
        continue;
      }
      // A child of a front cell: the parent's field where its node lies.
      simplex_shape_values(dim, mesh_.order, refined->child_reference(cell)[a], N.data());
      for (int i = 0; i < dim; ++i) {
        double value = 0.0;
        for (int b = 0; b < npc_; ++b) value += N[b] * field[dim * from_nodes[b] + i];
        out[dim * to_nodes[a] + i] = value;
      }
    }
  }
  return out;
}

Vec3 FemBody::point_in_parent(const FemBody& next, Index c, std::span<const Vec3> child_reference) const {
  const int dim = mesh_.dimension;
  Vec3 inside = Vec3::Constant(1.0 / (dim + 1));  // the cell's centroid, unless it is a copy
  if (dim == 2) inside.z() = 0.0;
  if (next.split_ && !next.split_->whole(c)) {
    const auto fragment = next.split_->fragment(c);
    inside.setZero();
    for (int k = 0; k <= dim; ++k) inside += fragment[k] / (dim + 1);
  }
  if (child_reference.empty()) return inside;
  Vec3 in_parent = child_reference[0];  // the child's corners' affine map into its parent
  for (int k = 0; k < dim; ++k) in_parent += inside[k] * (child_reference[k + 1] - child_reference[0]);
  return in_parent;
}

std::pair<Index, Index> FemBody::copies_of(Index p) const {
  if (!split_) return {p, p + 1};
  return {copies_start_[p], copies_start_[p + 1]};
}

Index FemBody::copy_node(Index c, Index parent, Index node) const {
  const auto nodes = outline().cell(parent);
  const auto local = std::find(nodes.begin(), nodes.end(), node) - nodes.begin();
  return mesh_.cell(c)[local];
}

void FemBody::average_bulk_at_nodes(const Scene& scene) {
  KERF_CHECK(mesh_.order == 1, scene.locate("discretization.fem.volumetric").describe(),
             ": value 'averaged_nodal' averages the bulk term of linear cells, but the mesh ",
             scene.mesh_file.empty() ? std::string() : "file " + scene.mesh_file + " ",
             "holds quadratic ones; expected a linear mesh, or volumetric: element");
  bulk_average_.emplace(mesh_, wdet_);  // one point per linear cell: its weight is its volume
  if (!share_.distributed()) return;
  // This rank's nodes' stars reach beyond its cells: their rows are touched too.
  std::vector<char> reached(mesh_.node_count(), 0);
  for (Index n : touched_nodes_) reached[n] = 1;
  for (Index a = owned_nodes_.first; a < owned_nodes_.second; ++a)
    for (Index n : bulk_average_->star(a)) reached[n] = 1;
  touched_nodes_ = touched_node_list(std::move(reached), owned_nodes_);
}

void FemBody::share_cells(RankShare share) {
  share_ = share;
  std::tie(cell_begin_, cell_end_) = even_part(mesh_.cell_count(), share.rank, share.count);
  owned_nodes_ = even_part(mesh_.node_count(), share.rank, share.count);
  if (piece_) {
    std::tie(cell_begin_, cell_end_) = std::pair<Index, Index>(0, piece_->own_cells);
    owned_nodes_ = {0, piece_->own_nodes};
  }
  schedule_ = schedule_cells_worth_threads(mesh_, cell_begin_, cell_end_);
  // Its own nodes (their rows take the whole lumped mass) and its cells'.
  std::vector<char> reached(mesh_.node_count(), 0);
  for (Index c = cell_begin_; c < cell_end_; ++c)
    for (Index n : mesh_.cell(c)) reached[n] = 1;
  touched_nodes_ = touched_node_list(std::move(reached), owned_nodes_);
}

template <int Dim, int Npc>
void FemBody::bulk_averages(const Vector& u, BulkAverages& out) const {
  const Index cells = mesh_.cell_count();
  out.gradient.resize(cells);
  out.own.resize(cells);
#pragma omp parallel for schedule(static)
  for (Index c = 0; c < cells; ++c) {
    auto nodes = mesh_.cell(c);
    // One point per linear cell (copies too): its gradients.
    Eigen::Map<const Eigen::Matrix<double, Npc, Dim, Eigen::RowMajor>> G(
        &grad_[static_cast<std::size_t>(point_start_[c]) * Npc * Dim]);
    Mat3 F = Mat3::Identity();
    for (int a = 0; a < Npc; ++a)
      for (int i = 0; i < Dim; ++i) F.row(i).template head<Dim>() += u[Dim * nodes[a] + i] * G.row(a);
    const MaterialLaw::BulkMeasure b = law_.bulk_measure(F);
    out.own[c] = b.value;
    out.gradient[c] = b.gradient;
  }
  out.node.resize(mesh_.node_count());
  bulk_average_->to_nodes(out.own, out.node);
  out.cell_mean.resize(cells);
  bulk_average_->to_cells(mesh_, out.node, out.cell_mean);
}

template <int Dim, int Npc>
void FemBody::element_loop(const Vector& u, const BulkAverages* averages, const ElementSink* sink, Vector* f,
                           double* energy) const {
  using Work = ElementWork<Dim, Npc>;
  if (f) f->setZero(dof_count());
  double total_energy = 0.0;
  ParallelFailure failure;  // a material law or the sink may throw
  // Phase by phase: the ranges of one phase share no node, so their forces and
  // blocks are written without atomics.
#pragma omp parallel reduction(+ : total_energy) if (schedule_.threads > 1)
  {
    Work work;
    Mat3 P;
    Mat9 dPdF;
    for (const auto& phase : schedule_.phases) {
#pragma omp for schedule(static, 1)
      for (std::size_t range = 0; range < phase.size(); ++range)
        failure.run([&] {
          for (Index slot = phase[range].first; slot < phase[range].second; ++slot) {
            const Index c = schedule_.cells[slot];
            auto nodes = mesh_.cell(c);
            Eigen::Matrix<double, Dim, Npc> U;
            for (int a = 0; a < Npc; ++a)
              for (int i = 0; i < Dim; ++i) {
                work.dofs[Dim * a + i] = Dim * nodes[a] + i;
                U(i, a) = u[Dim * nodes[a] + i];
              }
            work.force.setZero();
            if (sink) work.stiffness.setZero();
            for (std::size_t point = point_start_[c]; point < static_cast<std::size_t>(point_start_[c + 1]); ++point) {
              Eigen::Map<const Eigen::Matrix<double, Npc, Dim, Eigen::RowMajor>> G(&grad_[point * Npc * Dim]);
              const double w = wdet_[point];
              Mat3 F = Mat3::Identity();
              F.template topLeftCorner<Dim, Dim>() += U * G;
              if (averages) {  // the nodes hold the bulk term: the cell feels its nodes' mean
                const MaterialLaw::BulkMeasure own{averages->own[c], averages->gradient[c]};
                const double mean = averages->cell_mean[c];
                if (sink)
                  law_.averaged_bulk_stress_and_tangent(F, own, mean, P, dPdF);
                else
                  P = law_.averaged_bulk_stress(F, own, mean);
                if (energy) total_energy += w * law_.energy_without_bulk(F);
              } else {
                if (sink)
                  law_.stress_and_tangent(F, P, dPdF);
                else
                  P = law_.stress(F);
                if (energy) total_energy += w * law_.energy(F);
              }
              Eigen::Matrix<double, Dim, Npc> fq = P.template topLeftCorner<Dim, Dim>() * G.transpose();
              for (int a = 0; a < Npc; ++a)
                for (int i = 0; i < Dim; ++i) work.force[Dim * a + i] += w * fq(i, a);
              if (!sink) continue;
              for (int b = 0; b < Npc; ++b)
                for (int k = 0; k < Dim; ++k) {
                  // T(i, j) = sum_l dP(i,j)/dF(k,l) G(b,l)
                  Eigen::Matrix<double, Dim, Dim> T = Eigen::Matrix<double, Dim, Dim>::Zero();
                  for (int l = 0; l < Dim; ++l)
                    for (int j = 0; j < Dim; ++j)
                      for (int i = 0; i < Dim; ++i) T(i, j) += dPdF(i + 3 * j, k + 3 * l) * G(b, l);
                  Eigen::Matrix<double, Dim, Npc> column = T * G.transpose();
                  for (int a = 0; a < Npc; ++a)
                    for (int i = 0; i < Dim; ++i) work.stiffness(Dim * a + i, Dim * b + k) += w * column(i, a);
                }
            }
            if (f)
              for (int r = 0; r < Work::n; ++r) (*f)[work.dofs[r]] += work.force[r];
            if (sink) (*sink)(c, work.dofs, std::span<const double>(work.stiffness.data(), Work::n * Work::n));
          }
        });
    }
  }
  failure.rethrow_if_failed();
  if (energy) *energy = total_energy;
}

void FemBody::loop(const Vector& u, const ElementSink* sink, Vector* f, double* energy,
                   const NodalBulkAverage::StarSink* stars, bool standard) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  dispatch_cell(mesh_.dimension, mesh_.order, [&]<int Dim, int Npc>() {
    if (!bulk_average_ || standard) return element_loop<Dim, Npc>(u, nullptr, sink, f, energy);
    KERF_CHECK(!sink || stars, "internal: an averaged-nodal-pressure tangent without its stars' blocks");
    BulkAverages& averages = bulk_state_;
    bulk_averages<Dim, Npc>(u, averages);
    element_loop<Dim, Npc>(u, &averages, sink, f, energy);
    const double k = law_.bulk_coefficient();
    const auto [begin, end] = owned_nodes_;
    if (energy) *energy += bulk_average_->nodal_energy(averages.node, k, begin, end);
    if (stars) bulk_average_->star_tangents(averages.gradient, grad_, k, begin, end, *stars);
  });
}

void FemBody::internal_force(const Vector& u, Vector& f) const { loop(u, nullptr, &f, nullptr); }

void FemBody::tangent(const Vector& u, const BlockSink& sink, Vector* f) const {
  ElementSink forward = [&](Index, std::span<const Index> dofs, std::span<const double> values) {
    sink(dofs, values);
  };
  NodalBulkAverage::StarSink star = [&](Index, std::span<const Index> dofs, std::span<const double> values) {
    sink(dofs, values);
  };
  loop(u, &forward, f, nullptr, &star);
}

namespace {

/// True when every node's dpn rows hold the same columns, in whole blocks of
/// a node's dpn consecutive dofs (build_pattern's matrices): then a block's
/// first entry in its node's first row places the whole block.
bool whole_node_blocks(const CsrView& m, int dpn) {
  if (m.rows % dpn != 0) return false;
  const Index nodes = m.rows / dpn;
  Index broken = 0;
#pragma omp parallel for schedule(static) reduction(+ : broken)
  for (Index node = 0; node < nodes; ++node) {
    const Index row = dpn * node, length = m.outer[row + 1] - m.outer[row];
    bool whole = length % dpn == 0;
    for (int i = 1; i < dpn && whole; ++i) whole = m.outer[row + i + 1] - m.outer[row + i] == length;
    for (Index q = 0; q < length && whole; q += dpn) {
      const Index first = m.inner[m.outer[row] + q];
      whole = first % dpn == 0;
      for (int i = 0; i < dpn && whole; ++i)
        for (int k = 0; k < dpn && whole; ++k) whole = m.inner[m.outer[row + i] + q + k] == first + k;
    }
    broken += whole ? 0 : 1;
  }
  return broken == 0;
}

/// Where each of cell `nodes`' node-pair blocks starts in its rows of `m`
/// (npc^2 offsets into `out`), or false when the pattern lacks one. With
/// `whole_blocks` (whole_node_blocks) a block is checked by its first entry.
bool cell_block_offsets(std::span<const Index> nodes, int dpn, const CsrView& m, bool whole_blocks, Index* out) {
  const int npc = static_cast<int>(nodes.size());
  for (int a = 0; a < npc; ++a) {
    const Index row = dpn * nodes[a];
    if (row + dpn > m.rows) return false;
    const Index* begin = m.inner + m.outer[row];
    const Index* end = m.inner + m.outer[row + 1];
    for (int b = 0; b < npc; ++b) {
      const Index offset = static_cast<Index>(std::lower_bound(begin, end, dpn * nodes[b]) - begin);
      if (whole_blocks) {
        if (begin + offset == end || begin[offset] != dpn * nodes[b]) return false;
        out[a * npc + b] = offset;
        continue;
      }
      // The same offset serves the node's other rows: their patterns must agree.
      for (int i = 0; i < dpn; ++i)
        for (int k = 0; k < dpn; ++k) {
          const Index p = m.outer[row + i] + offset + k;
          if (p >= m.outer[row + i + 1] || m.inner[p] != dpn * nodes[b] + k) return false;
        }
      out[a * npc + b] = offset;
    }
  }
  return true;
}

}  // namespace

const std::vector<Index>& FemBody::pair_offsets(const CsrView& m) const {
  if (m.rows == offsets_pattern_.rows && m.outer == offsets_pattern_.outer && m.inner == offsets_pattern_.inner &&
      !pair_offsets_.empty())
    return pair_offsets_;
  // This rank's cells alone (all in a serial run), indexed from cell_begin_;
  // each cell fills its own entries, so the cells run in parallel.
  pair_offsets_.resize(static_cast<std::size_t>(cell_end_ - cell_begin_) * npc_ * npc_);
  Index lacking = -1;  // a cell whose blocks the pattern lacks (no exception may leave the loop)
  const bool whole_blocks = whole_node_blocks(m, mesh_.dimension);
#pragma omp parallel for schedule(static)
  for (Index c = cell_begin_; c < cell_end_; ++c) {
    std::array<Index, 10> global;  // a piece's cell in the matrix's numbering
    std::span<const Index> nodes = mesh_.cell(c);
    if (piece_) {
      for (int a = 0; a < npc_; ++a) global[a] = piece_->global_node[nodes[a]];
      nodes = std::span<const Index>(global.data(), npc_);
    }
    if (!cell_block_offsets(nodes, mesh_.dimension, m, whole_blocks,
                            &pair_offsets_[static_cast<std::size_t>(c - cell_begin_) * npc_ * npc_])) {
#pragma omp critical(kerf_pair_offsets)
      lacking = c;
    }
  }
  KERF_CHECK(lacking < 0, "internal: the matrix's pattern lacks a block of cell ", lacking);
  offsets_pattern_ = m;
  return pair_offsets_;
}

const std::vector<Index>& FemBody::star_offsets(const CsrView& m) const {
  if (m.rows == star_offsets_pattern_.rows && m.outer == star_offsets_pattern_.outer &&
      m.inner == star_offsets_pattern_.inner && !star_offset_start_.empty())
    return star_offsets_;
  const auto [begin, end] = owned_nodes_;
  star_offset_start_.assign(end - begin + 1, 0);
  for (Index a = begin; a < end; ++a) {
    const Index k = static_cast<Index>(bulk_average_->star(a).size());
    star_offset_start_[a - begin + 1] = star_offset_start_[a - begin] + k * k;
  }
  star_offsets_.resize(star_offset_start_.back());
  Index lacking = -1;
  const bool whole_blocks = whole_node_blocks(m, mesh_.dimension);
#pragma omp parallel for schedule(static)
  for (Index a = begin; a < end; ++a)
    if (!cell_block_offsets(bulk_average_->star(a), mesh_.dimension, m, whole_blocks,
                            &star_offsets_[star_offset_start_[a - begin]])) {
#pragma omp critical(kerf_star_offsets)
      lacking = a;
    }
  KERF_CHECK(lacking < 0, "internal: the matrix's pattern lacks a block of node ", lacking, "'s star");
  star_offsets_pattern_ = m;
  return star_offsets_;
}

namespace {

/// Adds the dense block over `dofs` (whole nodes, dpn each) into m, node pair
/// (a, b)'s columns starting at `offsets[a * nodes + b]` in a's rows.
void add_block(const CsrView& m, const Index* offsets, int dpn, std::span<const Index> dofs,
               std::span<const double> block) {
  const int n = static_cast<int>(dofs.size()), nodes = n / dpn;
  for (int a = 0; a < nodes; ++a)
    for (int i = 0; i < dpn; ++i) {
      double* row = m.values + m.outer[dofs[dpn * a + i]];
      const double* from = &block[static_cast<std::size_t>(dpn * a + i) * n];
      for (int b = 0; b < nodes; ++b)
        for (int k = 0; k < dpn; ++k) row[offsets[a * nodes + b] + k] += from[dpn * b + k];
    }
}

/// add_block for a cell of `Nodes` nodes of `Dpn` dofs: the compiler unrolls
/// the node pairs' rows (the scatter was a third of the corotational tet4
/// kernels' time with the sizes known only at run time).
template <int Dpn, int Nodes>
void add_cell_block(const CsrView& m, const Index* offsets, const Index* dofs, const double* block) {
  constexpr int n = Dpn * Nodes;
  for (int a = 0; a < Nodes; ++a)
    for (int i = 0; i < Dpn; ++i) {
      double* row = m.values + m.outer[dofs[Dpn * a + i]];
      const double* from = block + (Dpn * a + i) * n;
      for (int b = 0; b < Nodes; ++b) {
        double* to = row + offsets[a * Nodes + b];
        for (int k = 0; k < Dpn; ++k) to[k] += from[Dpn * b + k];
      }
    }
}

using CellBlockAdder = void (*)(const CsrView&, const Index*, const Index*, const double*);

/// The unrolled adder for kerf's cells (core/element_types.h), or null.
CellBlockAdder cell_block_adder(int dpn, int npc) {
  if (dpn == 3 && npc == 4) return add_cell_block<3, 4>;
  if (dpn == 3 && npc == 10) return add_cell_block<3, 10>;
  if (dpn == 2 && npc == 3) return add_cell_block<2, 3>;
  if (dpn == 2 && npc == 6) return add_cell_block<2, 6>;
  return nullptr;
}

}  // namespace

void FemBody::add_tangent_into(const Vector& u, const CsrView& m, Vector* f) const {
  const std::vector<Index>& offsets = pair_offsets(m);
  const int dpn = mesh_.dimension, npc = npc_;
  const CellBlockAdder unrolled = cell_block_adder(dpn, npc);
  // Cells of one phase share no node, hence no row: no two threads add to one value.
  ElementSink write = [&](Index c, std::span<const Index> dofs, std::span<const double> block) {
    const Index* at = &offsets[static_cast<std::size_t>(c - cell_begin_) * npc * npc];
    if (!piece_ && unrolled) return unrolled(m, at, dofs.data(), block.data());
    if (!piece_) return add_block(m, at, dpn, dofs, block);
    std::array<Index, 30> global;  // the dofs in the matrix's numbering
    for (std::size_t k = 0; k < dofs.size(); ++k) global[k] = dpn * piece_->global_node[dofs[k] / dpn] + dofs[k] % dpn;
    add_block(m, at, dpn, std::span<const Index>(global.data(), dofs.size()), block);
  };
  if (!bulk_average_) return loop(u, &write, f, nullptr);
  const std::vector<Index>& at_star = star_offsets(m);
  NodalBulkAverage::StarSink write_star = [&](Index a, std::span<const Index> dofs, std::span<const double> block) {
    add_block(m, &at_star[star_offset_start_[a - owned_nodes_.first]], dpn, dofs, block);
  };
  loop(u, &write, f, nullptr, &write_star);
}

double FemBody::strain_energy(const Vector& u) const {
  double e = 0.0;
  loop(u, nullptr, nullptr, &e);
  return e;
}

double FemBody::mean_neighbors() const {
  std::vector<Index> start, adjacent;
  node_adjacency(mesh_, start, adjacent);
  return node_count() ? static_cast<double>(adjacent.size()) / node_count() : 0.0;
}

void FemBody::visit_couplings(const CouplingVisitor& visit) const {
  const int dim = mesh_.dimension;
  std::vector<Index> dofs(npc_ * dim);
  // Every cell, a piece's ghosts too: a row a rank owns is then whole, as
  // PETSc's preallocation of the summed matrix needs.
  for (Index c = 0; c < mesh_.cell_count(); ++c) {
    auto nodes = mesh_.cell(c);
    for (int a = 0; a < npc_; ++a)
      for (int i = 0; i < dim; ++i) dofs[dim * a + i] = dim * nodes[a] + i;
    visit(dofs);
  }
  if (!bulk_average_) return;
  for (Index a = 0; a < mesh_.node_count(); ++a) {
    auto star = bulk_average_->star(a);
    dofs.resize(star.size() * dim);
    for (std::size_t n = 0; n < star.size(); ++n)
      for (int i = 0; i < dim; ++i) dofs[dim * n + i] = dim * star[n] + i;
    visit(dofs);
  }
}

Eigen::MatrixXd FemBody::element_scalar_mass(Index c, bool whole) const {
  const int dim = mesh_.dimension;
  QuadratureRule own;  // a copy's mass rule on its fragment; a whole cell uses mass_rule_ and its shapes
  std::vector<double> own_N, own_dN;
  const bool copy = !whole && split_ && !split_->whole(c);
  if (copy) {
    own = cell_rule(c, mass_rule_);
    rule_shapes(dim, mesh_.order, npc_, own, own_N, own_dN);
  }
  const QuadratureRule& rule = copy ? own : mass_rule_;
  const double* N = copy ? own_N.data() : mass_N_.data();
  const double* dN = copy ? own_dN.data() : mass_dN_.data();
  auto nodes = mesh_.cell(c);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(npc_, npc_);
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const double det = jacobian_determinant(mesh_, nodes, dN + q * npc_ * dim);
    const Eigen::Map<const Eigen::VectorXd> n(N + q * npc_, npc_);
    M.noalias() += (density_ * rule.weights[q] * det) * n * n.transpose();
  }
  return M;
}

Vector FemBody::lumped_mass() const {
  // HRZ lumping: the consistent diagonal scaled to the element mass (positive
  // for quadratic elements, where row sums give negative corner masses).
  const int dim = mesh_.dimension;
  Vector m = Vector::Zero(dof_count());
  for (Index c = cell_begin_; c < cell_end_; ++c) {
    const Eigen::VectorXd lumped = lumped_cell_mass(c);
    auto nodes = mesh_.cell(c);
    for (int a = 0; a < npc_; ++a)
      for (int i = 0; i < dim; ++i) m[dim * nodes[a] + i] += lumped[a];
  }
  return m;
}

Eigen::VectorXd FemBody::lumped_cell_mass(Index c) const {
  const Eigen::MatrixXd M = element_scalar_mass(c);
  if (!split_ || split_->whole(c)) return M.diagonal() * (M.sum() / M.diagonal().sum());
  const Eigen::MatrixXd parent = element_scalar_mass(c, /*whole=*/true);
  return parent.diagonal() * (M.sum() / parent.diagonal().sum());
}

void FemBody::consistent_mass(const BlockSink& sink) const {
  const int dim = mesh_.dimension, n = npc_ * dim;
  std::vector<Index> dofs(n);
  std::vector<double> block(n * n);
  for (Index c = cell_begin_; c < cell_end_; ++c) {
    Eigen::MatrixXd M = element_scalar_mass(c);
    auto nodes = mesh_.cell(c);
    std::fill(block.begin(), block.end(), 0.0);
    for (int a = 0; a < npc_; ++a)
      for (int i = 0; i < dim; ++i) {
        dofs[dim * a + i] = dim * nodes[a] + i;
        for (int b = 0; b < npc_; ++b) block[(dim * a + i) * n + dim * b + i] = M(a, b);
      }
    sink(dofs, block);
  }
}

void FemBody::external_force(double, Vector& f) const { f = load_; }

void FemBody::add_gravity(const Vec3& gravity) {
  // rho g times the integral of N_a over each cell (the row sums of its
  // scalar mass, the N_b summing to 1), with the rule's shape values found
  // once and the cells' integrals in parallel: every rank integrates every
  // cell (the load is whole on each), so this is set-up no rank divides.
  // N_a det J has degree order + dim (order - 1) (curved cells' J is of degree
  // order - 1): the symmetric rule of that degree is exact, as the mass rule
  // is, with 14 points a tet10 against 64 (the 2.5 mm cantilever: 86 -> 24 ms CPU).
  const int dim = mesh_.dimension, order = mesh_.order;
  const QuadratureRule rule = symmetric_simplex_rule(dim, order + dim * (order - 1));
  const std::size_t nq = rule.points.size(), npc = static_cast<std::size_t>(npc_);
  std::vector<double> N(nq * npc), dN(nq * npc * dim);
  for (std::size_t q = 0; q < nq; ++q) {
    simplex_shape_values(dim, order, rule.points[q], &N[q * npc]);
    simplex_shape_gradients(dim, order, rule.points[q], &dN[q * npc * dim]);
  }
  const Index cells = mesh_.cell_count();
  std::vector<double> integral(static_cast<std::size_t>(cells) * npc, 0.0);
#pragma omp parallel for schedule(static)
  for (Index c = 0; c < cells; ++c) {
    const auto nodes = mesh_.cell(c);
    double* w = &integral[static_cast<std::size_t>(c) * npc];
    if (split_ && !split_->whole(c)) {  // a copy: over its fragment alone
      const Eigen::VectorXd row_sums = element_scalar_mass(c).rowwise().sum();
      for (std::size_t a = 0; a < npc; ++a) w[a] = row_sums[a];
      continue;
    }
    for (std::size_t q = 0; q < nq; ++q) {
      Mat3 J = Mat3::Identity();
      for (int i = 0; i < dim; ++i)
        for (int k = 0; k < dim; ++k) {
          double sum = 0.0;
          for (std::size_t a = 0; a < npc; ++a) sum += mesh_.nodes[nodes[a]][i] * dN[(q * npc + a) * dim + k];
          J(i, k) = sum;
        }
      const double scale = density_ * rule.weights[q] * J.determinant();  // 2D: the z row and column are 1
      for (std::size_t a = 0; a < npc; ++a) w[a] += scale * N[q * npc + a];
    }
  }
  for (Index c = 0; c < cells; ++c) {
    const auto nodes = mesh_.cell(c);
    for (std::size_t a = 0; a < npc; ++a)
      for (int i = 0; i < dim; ++i)
        load_[dim * nodes[a] + i] += integral[static_cast<std::size_t>(c) * npc + a] * gravity[i];
  }
}

void FemBody::build_loads(const Scene& scene) {
  const int dim = mesh_.dimension, order = mesh_.order;
  load_ = Vector::Zero(dof_count());
  if (scene.gravity.squaredNorm() > 0.0) add_gravity(scene.gravity);
  // Tractions and pressures on the boundary facets whose nodes all lie in the selection.
  const int fdim = dim - 1, nf = facets_.nodes_per_facet;
  QuadratureRule rule = simplex_quadrature(fdim, order + 1);
  std::vector<double> N(nf), dN(nf * std::max(fdim, 1));
  loaded_faces_.assign(scene.boundary.size(), 0);
  for (const BoundaryCondition& bc : scene.boundary) {
    if (bc.is_dirichlet()) continue;
    std::vector<char> selected(mesh_.nodes.size(), 0);
    for (Index n : select_nodes(bc.select)) selected[n] = 1;
    Index loaded = 0;
    std::vector<Index> fn(nf);
    for (Index fi = 0; fi < facets_.count(); ++fi) {
      const auto facet = facets_.facet(fi);
      if (!std::all_of(facet.begin(), facet.end(), [&](Index n) { return selected[n]; })) continue;
      ++loaded;
      if (facets_.cell[fi] < kept_cells()) ++loaded_faces_[&bc - scene.boundary.data()];
      // Its cell's copy's nodes (fem: split; a cell the cut separates has two).
      const auto [first, last] = copies_of(facets_.cell[fi]);
      KERF_CHECK(last - first == 1 && (!split_ || split_->whole(first)), bc.select.where.describe(),
                 ": a traction or pressure on a boundary face that the cut (fem: split) separates is not built "
                 "yet; expected the load's faces away from the cut, or the cut's fem: remesh");
      for (int a = 0; a < nf; ++a) fn[a] = split_ ? copy_node(first, facets_.cell[fi], facet[a]) : facet[a];
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        simplex_shape_values(fdim, order, rule.points[q], N.data());
        simplex_shape_gradients(fdim, order, rule.points[q], dN.data());
        Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();
        for (int a = 0; a < nf; ++a) {
          t1 += mesh_.nodes[fn[a]] * dN[a * fdim];
          if (fdim == 2) t2 += mesh_.nodes[fn[a]] * dN[a * fdim + 1];
        }
        Vec3 area_normal = fdim == 2 ? Vec3(t1.cross(t2)) : Vec3(t1.y(), -t1.x(), 0.0);  // outward, |.| = dA/dxi
        Vec3 traction = Vec3::Zero();
        if (bc.traction) traction += *bc.traction * area_normal.norm();
        if (bc.pressure) traction -= *bc.pressure * area_normal;
        for (int a = 0; a < nf; ++a)
          for (int i = 0; i < dim; ++i) load_[dim * fn[a] + i] += rule.weights[q] * N[a] * traction[i];
      }
    }
    KERF_CHECK(piece_ || loaded > 0, bc.select.where.describe(),
               ": the selection holds boundary points but no whole boundary face, so the load has "
               "nowhere to act; expected a plane or box covering at least one face");
  }
}

void FemBody::build_constraints(const Scene& scene) {
  dirichlet_ = prescribed_dofs(
      scene, mesh_.dimension, [this](const Selection& s) { return select_nodes(s); }, mesh_.nodes,
      [](const BoundaryCondition&) { return true; });
}

SurfaceSamples FemBody::surface_samples(const Box& region, int points_per_direction) const {
  // Scene validation refuses contact with fem: split before any work.
  KERF_CHECK(!split_, "internal: contact on a body split by a cut (fem: split) is not built");
  const int dim = mesh_.dimension, fdim = dim - 1, nf = facets_.nodes_per_facet, corners = dim;
  const QuadratureRule rule = collapsed_gauss(fdim, points_per_direction);
  std::vector<double> N(nf), dN(nf * fdim);
  SurfaceSamples out;
  for (Index fi = 0; fi < facets_.count(); ++fi) {
    auto fn = facets_.facet(fi);
    if (std::none_of(fn.begin(), fn.begin() + corners, [&](Index n) { return region.contains(mesh_.nodes[n], 0.0); }))
      continue;
    const Vec3 a = mesh_.nodes[fn[0]], b = mesh_.nodes[fn[1]], c = fdim == 2 ? mesh_.nodes[fn[2]] : b;
    out.facets.push_back({a, b, c});
    const double size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      simplex_shape_values(fdim, mesh_.order, rule.points[q], N.data());
      simplex_shape_gradients(fdim, mesh_.order, rule.points[q], dN.data());
      SurfacePoint p;
      Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();
      for (int k = 0; k < nf; ++k) {
        p.position += N[k] * mesh_.nodes[fn[k]];
        t1 += mesh_.nodes[fn[k]] * dN[k * fdim];
        if (fdim == 2) t2 += mesh_.nodes[fn[k]] * dN[k * fdim + 1];
        p.interpolation.nodes.push_back(fn[k]);
        p.interpolation.weights.push_back(N[k]);
      }
      p.weight = rule.weights[q] * (fdim == 2 ? t1.cross(t2).norm() : t1.norm());
      p.size = size;
      out.points.push_back(std::move(p));
    }
  }
  return out;
}

double FemBody::critical_time_step() const {
  // Element eigenvalue bound: omega_max <= max over elements of omega_e with the
  // element's own lumped mass, so 2 / max(omega_e) is a safe step.
  // A partitioned body's bound is over its own cells: the caller takes the smallest over the ranks.
  // Each cell keeps its own bulk term here: averaged at the nodes, the bulk
  // energy is no larger (sum_a V_a m_a^2 <= sum_e V_e m_e^2, m_a being a
  // weighted mean of the m_e), so the standard cells' bound stays safe.
  const int dim = mesh_.dimension, n = npc_ * dim;
  std::vector<double> omega2(mesh_.cell_count(), 0.0);
  ElementSink element_frequency = [&](Index c, std::span<const Index>, std::span<const double> values) {
    const Eigen::VectorXd lumped = lumped_cell_mass(c);
    Eigen::VectorXd s(n);
    for (int a = 0; a < npc_; ++a)
      for (int i = 0; i < dim; ++i) s[dim * a + i] = 1.0 / std::sqrt(lumped[a]);
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> K(values.data(), n, n);
    Eigen::MatrixXd A = s.asDiagonal() * K * s.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (A + A.transpose()), Eigen::EigenvaluesOnly);
    omega2[c] = eig.eigenvalues().maxCoeff();
  };
  loop(Vector::Zero(dof_count()), &element_frequency, nullptr, nullptr, nullptr, /*standard=*/true);
  return 2.0 / std::sqrt(*std::max_element(omega2.begin(), omega2.end()));
}

std::vector<Index> FemBody::select_nodes(const Selection& selection) const {
  if (piece_) return piece_->select(selection);
  std::vector<Index> chosen = select_points(selection, outline().nodes, on_boundary_, domain_size_);
  if (!split_) return chosen;
  // The copies of a chosen node on its own side (a phantom only extends a copy's field).
  std::vector<char> taken(outline().node_count(), 0);
  for (Index n : chosen) taken[n] = 1;
  for (Index k = outline().node_count(); k < mesh_.node_count(); ++k)
    if (taken[split_->origin[k]] && !split_->phantom[k]) chosen.push_back(k);
  return chosen;
}

std::optional<PointInterpolation> FemBody::interpolation_at(const Vec3& x) const {
  auto where = locator_.locate(outline(), x, 1e-6 * domain_size_);
  if (!where) return std::nullopt;
  // The copy on the point's side of the cut as given (snapping may have moved
  // the fragments' boundary a little past it); on the cut, the + side's.
  auto [cell, last] = copies_of(where->cell);
  if (last - cell > 1) {
    const int side = side_of_cut(mesh_.dimension, split_pieces_, x);
    for (Index c = cell; c < last; ++c)
      if (split_->side[c] == (side < 0 ? -1 : 1)) {
        cell = c;
        break;
      }
  }
  PointInterpolation p;
  p.weights.resize(npc_);
  simplex_shape_values(mesh_.dimension, mesh_.order, where->local, p.weights.data());
  auto nodes = mesh_.cell(cell);
  p.nodes.assign(nodes.begin(), nodes.end());
  return p;
}

void FemBody::snapshot(const Vector& u, BodySnapshot& out) const {
  const int dim = mesh_.dimension;
  const ElementDescriptor& element = element_descriptor(dim, mesh_.order);
  const Index C = kept_cells();
  out = BodySnapshot{};
  out.piece = piece_.has_value();
  out.points = mesh_.nodes;
  out.connectivity.reserve(mesh_.cells.size());
  OutputField displacement{"displacement", 3, std::vector<double>(3 * mesh_.nodes.size(), 0.0)};
  for (Index n = 0; n < mesh_.node_count(); ++n)
    for (int i = 0; i < dim; ++i) displacement.values[3 * n + i] = u[dim * n + i];
  const std::vector<Mat3> sigma = cell_stresses(u);
  OutputField stress{"stress", 9, {}}, mises{"von_mises", 1, {}};
  std::vector<double> N(npc_);
  for (Index c = 0; c < C; ++c) {
    auto n = mesh_.cell(c);
    const auto cell_values = [&] {
      for (int k = 0; k < 9; ++k) stress.values.push_back(sigma[c](k / 3, k % 3));
      mises.values.push_back(von_mises(sigma[c]));
    };
    if (!split_ || split_->whole(c)) {
      for (int local : element.vtk_nodes) out.connectivity.push_back(n[local]);
      out.offsets.push_back(static_cast<Index>(out.connectivity.size()));
      out.cell_types.push_back(static_cast<std::uint8_t>(element.vtk_type));
      cell_values();
      continue;
    }
    // A copy: its fragment's sub-simplices as linear cells, on points of their own
    // carrying the copy's field (the copies of one cell overlap as whole cells).
    const std::span<const Vec3> fragment = split_->fragment(c);
    for (std::size_t k = 0; k < fragment.size(); ++k) {
      simplex_shape_values(dim, mesh_.order, fragment[k], N.data());
      Vec3 x = Vec3::Zero(), w = Vec3::Zero();
      for (int a = 0; a < npc_; ++a) {
        x += N[a] * mesh_.nodes[n[a]];
        for (int i = 0; i < dim; ++i) w[i] += N[a] * u[dim * n[a] + i];
      }
      out.connectivity.push_back(static_cast<Index>(out.points.size()));
      out.points.push_back(x);
      for (int i = 0; i < 3; ++i) displacement.values.push_back(w[i]);
      if ((k + 1) % (dim + 1)) continue;
      out.offsets.push_back(static_cast<Index>(out.connectivity.size()));
      out.cell_types.push_back(static_cast<std::uint8_t>(element_descriptor(dim, 1).vtk_type));
      cell_values();
    }
  }
  out.point_fields.push_back(std::move(displacement));
  out.cell_fields.push_back(std::move(stress));
  out.cell_fields.push_back(std::move(mises));
}

std::vector<Mat3> FemBody::cell_stresses(const Vector& u) const {
  const int dim = mesh_.dimension;
  BulkAverages& averages = bulk_state_;  // with the bulk term at the nodes, a cell's stress takes their mean
  if (bulk_average_)
    dispatch_cell(dim, mesh_.order, [&]<int Dim, int Npc>() { bulk_averages<Dim, Npc>(u, averages); });
  std::vector<Mat3> out(kept_cells(), Mat3::Zero());
  for (Index c = 0; c < kept_cells(); ++c) {
    auto nodes = mesh_.cell(c);
    const Index first = point_start_[c], points = point_start_[c + 1] - first;
    for (Index q = first; q < first + points; ++q) {
      const double* g = &grad_[static_cast<std::size_t>(q) * npc_ * dim];
      Mat3 F = Mat3::Identity();
      for (int a = 0; a < npc_; ++a)
        for (int i = 0; i < dim; ++i)
          for (int l = 0; l < dim; ++l) F(i, l) += u[dim * nodes[a] + i] * g[a * dim + l];
      const Mat3 P = bulk_average_ ? law_.averaged_bulk_stress(F, {averages.own[c], averages.gradient[c]},
                                                               averages.cell_mean[c])
                                   : law_.stress(F);
      out[c] += P * F.transpose() / (F.determinant() * points);
    }
  }
  return out;
}

}  // namespace kerf
