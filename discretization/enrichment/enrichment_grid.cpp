#include "discretization/enrichment/enrichment_grid.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/parallel_failure.h"

namespace kerf {

EnrichmentGrid::EnrichmentGrid(const CutSurface& cut, Index pieces, double spacing, double padding)
    : EnrichmentGrid(cut, pieces, spacing, padding, nullptr) {}

EnrichmentGrid::EnrichmentGrid(const CutSurface& cut, Index pieces, double spacing, double padding,
                               const EnrichmentGrid& before)
    : EnrichmentGrid(cut, pieces, spacing, padding, &before) {}

EnrichmentGrid::EnrichmentGrid(const CutSurface& cut, Index pieces, double spacing, double padding,
                               const EnrichmentGrid* before)
    : cut_(&cut),
      pieces_(pieces),
      spacing_(spacing),
      frame_(common_frame(cut, 0, pieces)),
      regions_(cut, 0, pieces, frame_),
      dim_(cut.dimension),
      anchor_(cut.vertices.front()) {
  size_lattice(padding);
  const bool same_points = before && same_lattice(*before);
  const bool grows = same_points && dim_ == 3 && before->cut_ == cut_ && before->pieces_ < pieces_;
  const CutRegionIndex added(cut, grows ? before->pieces_ : pieces_, pieces_, frame_);  // the new pieces
  if (before) changed_.assign(columns_.size(), 0);
  ParallelFailure failure;
#pragma omp parallel for schedule(static)
  for (Index c = 0; c < static_cast<Index>(columns_.size()); ++c)
    failure.run([&] {
      const Vec3 x = column_point(c);
      const Index old = same_points ? column_in(*before, c) : -1;
      if (!grows || old < 0) {
        columns_[c] = column_at(x);
        if (before) changed_[c] = !same(columns_[c], old >= 0 ? before->columns_[old] : before->column_at(x), x);
        return;
      }
      columns_[c] = before->columns_[old];
      if (columns_[c].d_plus == 0.0) return;  // over an earlier piece: it wins
      // A column no nearer the new pieces' boxes than its d+ keeps its region (a blade advancing a little
      // each step changes the columns around its tip only).
      if (added.distance_bound(x) > columns_[c].d_plus * (1.0 + 1e-12)) return;
      const CutRegion region = added.region(x);
      if (region.d_plus >= columns_[c].d_plus) return;
      columns_[c] = column_of(region, x);
      changed_[c] = !same(columns_[c], before->columns_[old], x);
    });
  failure.rethrow_if_failed();
  if (before) dilate_changes();
}

void EnrichmentGrid::dilate_changes() {
  // One column of dilation: a change narrower than the spacing still shows.
  std::vector<char> dilated(changed_);
  const Index n0 = count_[0], n1 = dim_ == 3 ? count_[1] : 1;
  changed_box_ = {n0, -1, n1, -1};
  for (Index c = 0; c < static_cast<Index>(changed_.size()); ++c) {
    if (!changed_[c]) continue;
    const Index i = c % n0, j = c / n0;
    for (Index dj = -1; dj <= 1; ++dj)
      for (Index di = -1; di <= 1; ++di) {
        const Index ii = i + di, jj = j + dj;
        if (ii < 0 || ii >= n0 || jj < 0 || jj >= n1) continue;
        dilated[ii + n0 * jj] = 1;
        changed_box_ = {std::min(changed_box_[0], ii), std::max(changed_box_[1], ii), std::min(changed_box_[2], jj),
                        std::max(changed_box_[3], jj)};
      }
  }
  changed_ = std::move(dilated);
}

void EnrichmentGrid::size_lattice(double padding) {
  const CutSurface& cut = *cut_;
  KERF_CHECK(pieces_ > 0 && pieces_ <= cut.piece_count() && spacing_ > 0.0,
             "an Enrichment Grid needs pieces and a spacing");
  axes_ = dim_ == 2 ? std::array<Vec3, 3>{frame_.axis[0], frame_.normal, Vec3::UnitZ()}
                    : std::array<Vec3, 3>{frame_.axis[0], frame_.axis[1], frame_.normal};
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
  for (Index k = 0; k < pieces_; ++k)
    for (int c = 0; c < dim_; ++c) {
      const Vec3 q = coordinates(cut.pieces[k].corner[c]);
      low = low.cwiseMin(q), high = high.cwiseMax(q);
    }
  double points = 1.0;  // counted in double: a too fine spacing overflows an Index
  std::array<double, 3> per_axis{1.0, 1.0, 1.0};
  for (int a = 0; a < dim_; ++a) {
    // Whole cells from the anchor: a cut that grows without turning keeps its lattice points.
    low_[a] = std::floor((low[a] - padding) / spacing_) * spacing_;
    per_axis[a] = std::ceil((high[a] + padding - low_[a]) / spacing_) + 1.0;
    points *= per_axis[a];
  }
  KERF_CHECK(points <= max_points, cut.where, ": key 'grid.spacing': value ", spacing_,
             " m gives an Enrichment Grid of ", points, " points around the cut (padding ", padding,
             " m, twice the largest support radius); expected at most ", max_points, ": a larger spacing");
  for (int a = 0; a < dim_; ++a) count_[a] = static_cast<Index>(per_axis[a]);
  columns_.resize(dim_ == 2 ? count_[0] : count_[0] * count_[1]);
}

Index EnrichmentGrid::column_in(const EnrichmentGrid& other, Index column) const {
  Index at = 0, stride = 1;
  const Index index[2] = {column % count_[0], column / count_[0]};
  for (int a = 0; a < dim_ - 1; ++a) {
    // Both lows are whole multiples of the spacing from the same anchor.
    const Index i = index[a] + static_cast<Index>(std::lround((low_[a] - other.low_[a]) / spacing_));
    if (i < 0 || i >= other.count_[a]) return -1;
    at += i * stride;
    stride *= other.count_[a];
  }
  return at;
}

std::vector<double> EnrichmentGrid::lattice_phi() const {
  const Index columns = static_cast<Index>(columns_.size()), along = count_[dim_ - 1];
  std::vector<double> phi(static_cast<std::size_t>(columns) * along);
  ParallelFailure failure;
#pragma omp parallel for schedule(static)
  for (Index c = 0; c < columns; ++c)
    failure.run([&] {
      const Vec3 base = column_point(c);
      for (Index k = 0; k < along; ++k)
        phi[c + columns * k] = phi_in(columns_[c], base + (low_[dim_ - 1] + k * spacing_) * axes_[dim_ - 1]).value;
    });
  failure.rethrow_if_failed();
  return phi;
}

Vec3 EnrichmentGrid::coordinates(const Vec3& x) const {
  const Vec3 d = x - anchor_;
  return Vec3(axes_[0].dot(d), axes_[1].dot(d), dim_ == 3 ? axes_[2].dot(d) : 0.0);
}

Vec3 EnrichmentGrid::column_point(Index column) const {
  const Index i = column % count_[0], j = column / count_[0];
  Vec3 x = anchor_ + (low_[0] + i * spacing_) * axes_[0];
  if (dim_ == 3) x += (low_[1] + j * spacing_) * axes_[1];
  return x;
}

bool EnrichmentGrid::same_lattice(const EnrichmentGrid& other) const {
  for (int a = 0; a < dim_; ++a)
    if ((axes_[a] - other.axes_[a]).norm() > 1e-12) return false;
  return anchor_ == other.anchor_ && spacing_ == other.spacing_;
}

Vec3 EnrichmentGrid::lattice_origin() const {
  Vec3 x = anchor_;
  for (int a = 0; a < dim_; ++a) x += low_[a] * axes_[a];
  return x;
}

EnrichmentGrid::Column EnrichmentGrid::column_at(const Vec3& x) const {
  return column_of(regions_.region(x), x);
}

EnrichmentGrid::Column EnrichmentGrid::column_of(const CutRegion& r, const Vec3& x) {
  return {r.piece, r.d_plus, r.d_plus_gradient, r.s_gradient, r.s_gradient.dot(x) - r.s};
}

PhiValue EnrichmentGrid::phi_in(const Column& c, const Vec3& x) const {
  CutRegion r;
  r.piece = c.piece;
  r.d_plus = c.d_plus;
  r.d_plus_gradient = c.d_plus_gradient;
  r.s = c.s_normal.dot(x) - c.s_offset;
  r.s_gradient = c.s_normal;
  return phi_of(r);
}

PhiValue EnrichmentGrid::exact(const Vec3& x) const { return phi_of(regions_.region(x)); }

PhiValue EnrichmentGrid::interpolated(const Vec3& x) const {
  // d+ is continuous in the plane: interpolated between the columns around x;
  // the region is the nearest column's, and s is exact from its piece, so the
  // jump across the faces stays sharp.
  const Vec3 q = coordinates(x);
  const int in_plane = dim_ - 1;
  std::array<Index, 2> cell{0, 0}, nearest{0, 0};
  std::array<double, 2> f{0.0, 0.0};
  for (int a = 0; a < in_plane; ++a) {
    const double r = (q[a] - low_[a]) / spacing_;
    if (!(r >= 0.0 && r <= count_[a] - 1)) return exact(x);
    cell[a] = std::min(static_cast<Index>(r), count_[a] - 2);
    f[a] = r - cell[a];
    nearest[a] = cell[a] + (f[a] >= 0.5 ? 1 : 0);
  }
  Column c = columns_[nearest[0] + count_[0] * nearest[1]];
  c.d_plus = 0.0;
  c.d_plus_gradient = Vec3::Zero();
  const int corners = 1 << in_plane;
  for (int corner = 0; corner < corners; ++corner) {
    double weight = 1.0;
    Index column = 0, stride = 1;
    for (int a = 0; a < in_plane; ++a) {
      const int bit = (corner >> a) & 1;
      weight *= bit ? f[a] : 1.0 - f[a];
      column += (cell[a] + bit) * stride;
      stride *= count_[a];
    }
    c.d_plus += weight * columns_[column].d_plus;
    c.d_plus_gradient += weight * columns_[column].d_plus_gradient;
  }
  return phi_in(c, x);
}

bool EnrichmentGrid::same(const Column& a, const Column& b, const Vec3& base) const {
  const double tolerance = 1e-12 * std::max(cut_->extent, spacing_);
  const bool same_plane =
      (a.s_normal - b.s_normal).norm() < 1e-12 && std::abs(a.s_offset - b.s_offset) < tolerance;
  if (same_plane) {
    if (std::abs(a.d_plus - b.d_plus) > tolerance) return false;
    return a.d_plus == 0.0 || (a.d_plus_gradient - b.d_plus_gradient).norm() < 1e-12;
  }
  // Over the cut (d+ = 0) phi is the sign of s: two planes give the same phi
  // on the column except between their crossings of it; same if the lattice
  // holds no point there.
  if (a.d_plus != 0.0 || b.d_plus != 0.0) return false;
  const Vec3& along = axes_[dim_ - 1];
  auto crossing = [&](const Column& c) { return (c.s_offset - c.s_normal.dot(base)) / c.s_normal.dot(along); };
  const double z0 = std::min(crossing(a), crossing(b)), z1 = std::max(crossing(a), crossing(b));
  const double bottom = low_[dim_ - 1], top = bottom + (count_[dim_ - 1] - 1) * spacing_;
  return z1 < bottom - spacing_ || z0 > top + spacing_;
}

bool EnrichmentGrid::reaches_changed_column(const Vec3& x, double radius) const {
  if (changed_box_[1] < changed_box_[0]) return false;  // nothing changed
  const Vec3 q = coordinates(x);
  // The columns the ball's projection spans, clipped to the changed ones' box.
  auto range = [&](int a, Index low, Index high) {
    const double r = (q[a] - low_[a]) / spacing_, span = radius / spacing_;
    return std::pair<Index, Index>{std::max<Index>(low, static_cast<Index>(std::ceil(r - span))),
                                   std::min<Index>(high, static_cast<Index>(std::floor(r + span)))};
  };
  const auto [i0, i1] = range(0, changed_box_[0], changed_box_[1]);
  const auto [j0, j1] = dim_ == 3 ? range(1, changed_box_[2], changed_box_[3]) : std::pair<Index, Index>{0, 0};
  for (Index j = j0; j <= j1; ++j)
    for (Index i = i0; i <= i1; ++i) {
      if (!changed_[i + count_[0] * j]) continue;
      // The column is a line along the normal: the ball reaches it when its projection is within the radius.
      const double du = low_[0] + i * spacing_ - q[0];
      const double dv = dim_ == 3 ? low_[1] + j * spacing_ - q[1] : 0.0;
      if (du * du + dv * dv < radius * radius) return true;
    }
  return false;
}

}  // namespace kerf
