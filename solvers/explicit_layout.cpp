#include "solvers/explicit_layout.h"

#include <algorithm>

#include "core/check.h"
#include "discretization/body_capabilities.h"
#include "solvers/ghost_exchange.h"

namespace kerf {
namespace {

class WholeLayout final : public ExplicitLayout {
 public:
  explicit WholeLayout(const MechanicalSystem& mechanics) : mechanics_(mechanics) {}
  bool piece() const override { return false; }
  Index size() const override { return mechanics_.dof_count(); }
  void internal_force(const Vector& u, Vector& f) const override { mechanics_.internal_force(u, f); }
  Vector lumped_mass() const override { return mechanics_.lumped_mass(); }
  void external_force(double t, Vector& f) const override { mechanics_.external_force(t, f); }
  std::vector<DirichletDof> constrained(const std::vector<DirichletDof>& whole) const override { return whole; }
  double weighted_square(const Vector& x, const Vector& w) const override { return x.dot(w.cwiseProduct(x)); }
  bool all_finite(const Vector& x) const override { return x.allFinite(); }
  void to_whole(const Vector&, Vector&) const override {}
  void to_whole_at(const Vector&, std::span<const Index>, Vector&) const override {}

 private:
  const MechanicalSystem& mechanics_;
};

/// A partitioned body whole on every rank (meshless, or FEM kept whole) as a
/// piece: its own nodes' dofs, then those of the nodes its cells or points
/// reach. Its force is computed on whole-length buffers, whose entries it
/// reads and writes are the piece's alone (PartitionedAssembly's touched
/// nodes); the step's vectors and what crosses between the ranks are the piece's.
class WholeBodyAsPiece final : public PieceLayout {
 public:
  WholeBodyAsPiece(const DiscreteBody& body, const PartitionedAssembly& part) : body_(body) {
    const int dim = body.dofs_per_node();
    const auto [begin, end] = part.owned_nodes();
    for (Index d = dim * begin; d < dim * end; ++d) dofs_.push_back(d);
    for (Index n : part.touched_nodes())
      if (n < begin || n >= end)
        for (int i = 0; i < dim; ++i) dofs_.push_back(dim * n + i);
    own_ = dim * (end - begin);
    u_ = Vector::Zero(body.dof_count());
  }
  const std::vector<Index>& piece_dofs() const override { return dofs_; }
  Index own_dof_count() const override { return own_; }
  void piece_internal_force(const Vector& u, Vector& f) const override {
    for (std::size_t k = 0; k < dofs_.size(); ++k) u_[dofs_[k]] = u[k];
    body_.internal_force(u_, f_);
    restrict_to_piece(f_, f);
  }
  Vector piece_lumped_mass() const override {
    Vector m;
    restrict_to_piece(body_.lumped_mass(), m);
    return m;
  }
  void piece_external_force(double t, Vector& f) const override {
    body_.external_force(t, f_);
    restrict_to_piece(f_, f);
  }

 private:
  void restrict_to_piece(const Vector& whole, Vector& piece) const {
    piece.resize(static_cast<Index>(dofs_.size()));
    for (std::size_t k = 0; k < dofs_.size(); ++k) piece[k] = whole[dofs_[k]];
  }
  const DiscreteBody& body_;
  std::vector<Index> dofs_;
  Index own_ = 0;
  mutable Vector u_, f_;  // whole-length: the body's own arguments
};

class PieceLayoutVectors final : public ExplicitLayout {
 public:
  PieceLayoutVectors(const MechanicalSystem& mechanics, std::unique_ptr<PieceLayout> adapted, const PieceLayout& piece)
      : mechanics_(mechanics), adapted_(std::move(adapted)), piece_(piece), dofs_(piece.piece_dofs()),
        own_(piece.own_dof_count()),
        exchange_(mechanics.dof_count(), own_,
                  std::span<const Index>(dofs_).subspan(static_cast<std::size_t>(own_))) {}
  bool piece() const override { return true; }
  Index size() const override { return static_cast<Index>(dofs_.size()); }
  void internal_force(const Vector& u, Vector& f) const override {
    piece_.piece_internal_force(u, f);
    exchange_.sum_and_share(f);
  }
  Vector lumped_mass() const override {
    Vector m = piece_.piece_lumped_mass();
    exchange_.sum_and_share(m);
    return m;
  }
  void external_force(double t, Vector& f) const override {
    piece_.piece_external_force(t, f);  // the body's alone: a body with contact spheres is laid out whole
    if (mechanics_.load_scale() != 1.0) f *= mechanics_.load_scale();
  }
  std::vector<DirichletDof> constrained(const std::vector<DirichletDof>& whole) const override;
  double weighted_square(const Vector& x, const Vector& w) const override {
    return exchange_.sum(x.head(own_).dot(w.head(own_).cwiseProduct(x.head(own_))));
  }
  bool all_finite(const Vector& x) const override { return exchange_.sum(x.allFinite() ? 0.0 : 1.0) == 0.0; }
  void to_whole(const Vector& x, Vector& whole) const override { exchange_.gather_all(x, whole); }
  void to_whole_at(const Vector& x, std::span<const Index> dofs, Vector& whole) const override {
    exchange_.gather(x, dofs, whole);
  }

 private:
  const MechanicalSystem& mechanics_;
  std::unique_ptr<PieceLayout> adapted_;  // a whole body seen as a piece, or null
  const PieceLayout& piece_;
  const std::vector<Index>& dofs_;
  Index own_;
  GhostExchange exchange_;
};

std::vector<DirichletDof> PieceLayoutVectors::constrained(const std::vector<DirichletDof>& whole) const {
  // The own dofs are one ascending range, the ghosts' ascending after them.
  std::vector<DirichletDof> out;
  const auto own_end = dofs_.begin() + own_;
  for (const DirichletDof& d : whole) {
    auto at = std::lower_bound(dofs_.begin(), own_end, d.dof);
    if (at == own_end || *at != d.dof) at = std::lower_bound(own_end, dofs_.end(), d.dof);
    if (at != dofs_.end() && *at == d.dof) out.push_back({static_cast<Index>(at - dofs_.begin()), d.value});
  }
  return out;
}

}  // namespace

std::unique_ptr<ExplicitLayout> explicit_layout(const MechanicalSystem& mechanics) {
  if (mechanics.contact()) return std::make_unique<WholeLayout>(mechanics);  // the spheres' dofs are every rank's
  if (const PieceLayout* piece = capability<PieceLayout>(mechanics.body()))
    return std::make_unique<PieceLayoutVectors>(mechanics, nullptr, *piece);
  const PartitionedAssembly* part = capability<PartitionedAssembly>(mechanics.body());
  if (!part || !part->partitioned()) return std::make_unique<WholeLayout>(mechanics);
  auto adapted = std::make_unique<WholeBodyAsPiece>(mechanics.body(), *part);
  const PieceLayout& piece = *adapted;
  return std::make_unique<PieceLayoutVectors>(mechanics, std::move(adapted), piece);
}

}  // namespace kerf
