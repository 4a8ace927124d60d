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
  Vector restricted(const Vector& whole) const override { return whole; }
  std::vector<DirichletDof> constrained(const std::vector<DirichletDof>& whole) const override { return whole; }
  double weighted_square(const Vector& x, const Vector& w) const override { return x.dot(w.cwiseProduct(x)); }
  bool all_finite(const Vector& x) const override { return x.allFinite(); }
  void to_whole(const Vector& x, std::span<const Index>, bool, Vector& whole) const override { whole = x; }

 private:
  const MechanicalSystem& mechanics_;
};

class PieceLayoutVectors final : public ExplicitLayout {
 public:
  PieceLayoutVectors(const MechanicalSystem& mechanics, const PieceLayout& piece)
      : piece_(piece), dofs_(piece.piece_dofs()), own_(piece.own_dof_count()),
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
  void external_force(double t, Vector& f) const override { piece_.piece_external_force(t, f); }
  Vector restricted(const Vector& whole) const override {
    Vector x(size());
    for (Index k = 0; k < size(); ++k) x[k] = whole[dofs_[k]];
    return x;
  }
  std::vector<DirichletDof> constrained(const std::vector<DirichletDof>& whole) const override;
  double weighted_square(const Vector& x, const Vector& w) const override {
    return exchange_.sum(x.head(own_).dot(w.head(own_).cwiseProduct(x.head(own_))));
  }
  bool all_finite(const Vector& x) const override { return exchange_.sum(x.allFinite() ? 0.0 : 1.0) == 0.0; }
  void to_whole(const Vector& x, std::span<const Index> dofs, bool all, Vector& whole) const override {
    if (all)
      exchange_.gather_all(x, whole);
    else
      exchange_.gather(x, dofs, whole);
  }

 private:
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
  const PieceLayout* piece = capability<PieceLayout>(mechanics.body());
  if (piece && !mechanics.contact()) return std::make_unique<PieceLayoutVectors>(mechanics, *piece);
  return std::make_unique<WholeLayout>(mechanics);
}

}  // namespace kerf
