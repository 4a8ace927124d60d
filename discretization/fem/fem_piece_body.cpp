#include "discretization/fem/fem_piece_body.h"

#include <algorithm>
#include <limits>

#include "core/check.h"
#include "geometry/boundary_facets.h"

namespace kerf {
namespace {

/// The other nodes each of the first `own` nodes shares a cell with, summed
/// (every cell around an own node is in the piece).
double own_neighbour_count(const Mesh& mesh, Index own) {
  std::vector<std::vector<Index>> around(own);
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (Index a : mesh.cell(c))
      if (a < own)
        for (Index b : mesh.cell(c))
          if (b != a) around[a].push_back(b);
  double total = 0.0;
  for (std::vector<Index>& list : around) {
    std::sort(list.begin(), list.end());
    total += static_cast<double>(std::unique(list.begin(), list.end()) - list.begin());
  }
  return total;
}

/// How far inside the simplex of `corners` x lies: its smallest barycentric
/// coordinate (negative outside).
double depth_inside(std::span<const Vec3> corners, const Vec3& x, int dim) {
  Eigen::Matrix3d edges = Eigen::Matrix3d::Identity();
  for (int k = 0; k < dim; ++k) edges.col(k).head(dim) = (corners[k + 1] - corners[0]).head(dim);
  const Vec3 y = edges.partialPivLu().solve(Vec3(x - corners[0]));
  double depth = 1.0 - y.head(dim).sum();
  for (int k = 0; k < dim; ++k) depth = std::min(depth, y[k]);
  return depth;
}

}  // namespace

FemPieceBody::FemPieceBody(const Scene& scene, MeshPiece piece, const MpiContext& mpi)
    : mpi_(mpi),
      dim_(piece.mesh.dimension),
      own_nodes_(piece.own_nodes),
      first_node_(piece.first_node),
      total_nodes_(piece.total_nodes),
      total_cells_(piece.total_cells),
      domain_size_(piece.domain_size),
      global_node_(std::move(piece.global_node)),
      piece_positions_(piece.mesh.nodes),
      on_boundary_(boundary_node_flags(piece.mesh, boundary_facets(piece.mesh))) {
  share_positions_and_neighbours(piece.mesh);
  FemPiece own_part{piece.own_cells, own_nodes_, domain_size_,
                    [this](const Selection& s) { return piece_selection(s); }, global_node_};
  body_ = std::make_unique<FemBody>(scene, std::move(piece.mesh), std::move(own_part));
  for (Index n : body_->touched_nodes()) touched_.push_back(global_node_[n]);
  std::sort(touched_.begin(), touched_.end());
  share_loads_and_constraints(scene);
  for (Index d = 0; d < dim_ * static_cast<Index>(global_node_.size()); ++d) piece_dofs_.push_back(global_dof(d));
  piece_load_ = local(load_);
}

void FemPieceBody::share_positions_and_neighbours(const Mesh& mesh) {
  // Every node's position: each rank's own nodes, end to end.
  std::vector<double> own;
  for (Index n = 0; n < own_nodes_; ++n)
    own.insert(own.end(), mesh.nodes[n].data(), mesh.nodes[n].data() + 3);
  for (const std::vector<double>& part : mpi_.from_every_rank(std::move(own)))
    for (std::size_t k = 0; k + 2 < part.size(); k += 3) positions_.emplace_back(part[k], part[k + 1], part[k + 2]);
  KERF_CHECK(static_cast<Index>(positions_.size()) == total_nodes_, "internal: the ranks own ", positions_.size(),
             " nodes of ", total_nodes_);
  double neighbours = 0.0;  // whole numbers: the sum is exact
  for (const std::vector<double>& part : mpi_.from_every_rank({own_neighbour_count(mesh, own_nodes_)}))
    neighbours += part[0];
  mean_neighbors_ = total_nodes_ ? neighbours / static_cast<double>(total_nodes_) : 0.0;
}

void FemPieceBody::share_loads_and_constraints(const Scene& scene) {
  Vector piece_load;
  body_->external_force(0.0, piece_load);
  load_ = joined_own_rows(piece_load);
  // A load that acts on no face of any rank's cells is refused, as a serial run refuses it.
  std::vector<double> faces(body_->loaded_faces().begin(), body_->loaded_faces().end());
  std::vector<double> total(faces.size(), 0.0);
  for (const std::vector<double>& part : mpi_.from_every_rank(faces))
    for (std::size_t k = 0; k < total.size(); ++k) total[k] += part[k];
  for (std::size_t k = 0; k < scene.boundary.size(); ++k) {
    const BoundaryCondition& bc = scene.boundary[k];
    KERF_CHECK(bc.is_dirichlet() || total[k] > 0, bc.select.where.describe(),
               ": the selection holds boundary points but no whole boundary face, so the load has "
               "nowhere to act; expected a plane or box covering at least one face");
  }
  // The constraints of own nodes, every rank's end to end (ascending dofs).
  std::vector<double> own;
  for (const DirichletDof& d : body_->dirichlet(0.0))
    if (d.dof < dim_ * own_nodes_) {
      own.push_back(static_cast<double>(global_dof(d.dof)));
      own.push_back(d.value);
    }
  for (const std::vector<double>& part : mpi_.from_every_rank(std::move(own)))
    for (std::size_t k = 0; k + 1 < part.size(); k += 2)
      dirichlet_.push_back({static_cast<Index>(part[k]), part[k + 1]});
}

Vector FemPieceBody::joined_own_rows(const Vector& piece_values) const {
  std::vector<double> own(piece_values.data(), piece_values.data() + dim_ * own_nodes_);
  Vector whole(dof_count());
  Index at = 0;
  for (const std::vector<double>& part : mpi_.from_every_rank(std::move(own)))
    for (double v : part) whole[at++] = v;
  KERF_CHECK(at == dof_count(), "internal: the ranks' own rows are ", at, " of ", dof_count());
  return whole;
}

std::vector<Index> FemPieceBody::whole_selection(const Selection& selection) const {
  const std::span<const Vec3> own(piece_positions_.data(), own_nodes_);
  std::vector<double> mine;  // global numbers (a point: its distance first)
  if (selection.kind == Selection::Kind::point) {
    double best = std::numeric_limits<double>::infinity();
    Index nearest = -1;
    for (Index n = 0; n < own_nodes_; ++n) {
      const double d = (own[n] - selection.point).squaredNorm();
      if (d < best) best = d, nearest = n;
    }
    if (nearest >= 0) mine = {best, static_cast<double>(first_node_ + nearest)};
  } else {
    try {
      for (Index n : select_points(selection, own, on_boundary_, domain_size_))
        mine.push_back(static_cast<double>(first_node_ + n));
    } catch (const Error&) {  // none here; maybe on another rank
    }
  }
  std::vector<Index> chosen;
  double best = std::numeric_limits<double>::infinity();
  for (const std::vector<double>& part : mpi_.from_every_rank(std::move(mine))) {
    if (selection.kind != Selection::Kind::point) {
      chosen.insert(chosen.end(), part.begin(), part.end());
    } else if (!part.empty() && part[0] < best) {  // ties: the lowest rank's, hence the lowest number
      best = part[0];
      chosen = {static_cast<Index>(part[1])};
    }
  }
  // Nothing anywhere: the serial message (select_points on no points throws it).
  if (chosen.empty()) select_points(selection, {}, {}, domain_size_);
  return chosen;
}

std::vector<Index> FemPieceBody::piece_selection(const Selection& selection) const {
  std::vector<Index> out;
  for (Index g : whole_selection(selection))
    if (Index n = local_node(g); n >= 0) out.push_back(n);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Index> FemPieceBody::select_nodes(const Selection& selection) const { return whole_selection(selection); }

Index FemPieceBody::local_node(Index g) const {
  if (g >= first_node_ && g < first_node_ + own_nodes_) return g - first_node_;
  // The ghosts follow the own nodes, in ascending global numbers.
  const auto ghosts = global_node_.begin() + own_nodes_;
  const auto at = std::lower_bound(ghosts, global_node_.end(), g);
  return at != global_node_.end() && *at == g ? static_cast<Index>(at - global_node_.begin()) : -1;
}

std::optional<PointInterpolation> FemPieceBody::interpolation_at(const Vec3& x) const {
  std::vector<double> mine;  // how deep inside its cell, node count, global nodes, weights
  if (auto p = body_->interpolation_at(x)) {
    std::vector<Vec3> corners;
    for (int k = 0; k <= dim_; ++k) corners.push_back(piece_positions_[p->nodes[k]]);
    mine.push_back(depth_inside(corners, x, dim_));
    mine.push_back(static_cast<double>(p->nodes.size()));
    for (Index n : p->nodes) mine.push_back(static_cast<double>(global_node_[n]));
    mine.insert(mine.end(), p->weights.begin(), p->weights.end());
  }
  // A point within the locator's tolerance of a cell on its rank but inside
  // another rank's cell (just off a cut's face) takes the cell it is inside,
  // as the serial locator does; among cells it is inside, the first rank's.
  std::optional<PointInterpolation> best;
  double deepest = -std::numeric_limits<double>::infinity();
  for (const std::vector<double>& part : mpi_.from_every_rank(std::move(mine))) {
    if (part.empty() || part[0] <= deepest || (deepest >= 0.0 && part[0] >= 0.0)) continue;
    deepest = part[0];
    const std::size_t count = static_cast<std::size_t>(part[1]);
    best = PointInterpolation{};
    for (std::size_t k = 0; k < count; ++k) best->nodes.push_back(static_cast<Index>(part[2 + k]));
    best->weights.assign(part.begin() + 2 + count, part.begin() + 2 + 2 * count);
  }
  return best;
}

const Vector& FemPieceBody::local(const Vector& u) const {
  KERF_CHECK(u.size() == dof_count(), "displacement vector has ", u.size(), " entries; expected ", dof_count());
  local_u_.resize(dim_ * static_cast<Index>(global_node_.size()));
  for (Index n = 0; n < static_cast<Index>(global_node_.size()); ++n)
    for (int i = 0; i < dim_; ++i) local_u_[dim_ * n + i] = u[dim_ * global_node_[n] + i];
  return local_u_;
}

void FemPieceBody::to_whole(const Vector& piece_values, Vector& whole) const {
  whole.setZero(dof_count());
  for (Index n = 0; n < static_cast<Index>(global_node_.size()); ++n)
    for (int i = 0; i < dim_; ++i) whole[dim_ * global_node_[n] + i] = piece_values[dim_ * n + i];
}

Vector FemPieceBody::lumped_mass() const {
  Vector whole;
  to_whole(body_->lumped_mass(), whole);
  return whole;
}

BlockSink FemPieceBody::to_global(const BlockSink& sink) const {
  return [this, &sink](std::span<const Index> dofs, std::span<const double> values) {
    thread_local std::vector<Index> global;
    global.resize(dofs.size());
    for (std::size_t k = 0; k < dofs.size(); ++k) global[k] = global_dof(dofs[k]);
    sink(global, values);
  };
}

void FemPieceBody::visit_couplings(const CouplingVisitor& visit) const {
  std::vector<Index> global;
  body_->visit_couplings([&](std::span<const Index> dofs) {
    global.resize(dofs.size());
    for (std::size_t k = 0; k < dofs.size(); ++k) global[k] = global_dof(dofs[k]);
    visit(global);
  });
}

void FemPieceBody::internal_force(const Vector& u, Vector& f) const {
  body_->internal_force(local(u), piece_force_);
  to_whole(piece_force_, f);
}

void FemPieceBody::tangent(const Vector& u, const BlockSink& sink, Vector* f) const {
  body_->tangent(local(u), to_global(sink), f ? &piece_force_ : nullptr);
  if (f) to_whole(piece_force_, *f);
}

void FemPieceBody::add_tangent_into(const Vector& u, const CsrView& matrix, Vector* f) const {
  body_->add_tangent_into(local(u), matrix, f ? &piece_force_ : nullptr);
  if (f) to_whole(piece_force_, *f);
}

}  // namespace kerf
