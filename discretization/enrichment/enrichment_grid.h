#pragma once
// The Enrichment Grid (paper section 6) as a data structure: a lattice aligned
// with the cut's common frame (2D: t along the common line, then the normal;
// 3D: two in-plane axes, then the normal), anchored at the cut's first vertex
// (so a cut that grows without turning keeps its lattice points), reaching
// `padding` beyond the cut,
// storing phi and its gradient at every lattice point. Region and d+ depend on
// a point's projection onto the common line/plane only, so they are computed
// once per column (the lattice points sharing a projection) and s per point.
// It serves phi exactly (the analytic definition, O(pieces) per query) or
// interpolated (O(1)): d+ and its gradient interpolated between the columns
// around the point, the region of the nearest column, s exact from that
// region's piece, so the jump across the faces stays sharp and only the
// smooth part around the tips (and the region boundaries at kinks, within
// half a spacing) is approximated. It gives phi at every lattice point (for
// ParaView, computed on request) and tells which columns changed when the cut
// grew: the nodes whose support reaches none of them keep their enriched weight.
#include <array>
#include <limits>
#include <vector>

#include "discretization/enrichment/cut_phi.h"
#include "geometry/cut_region_index.h"
#include "geometry/cut_surface.h"

namespace kerf {

class EnrichmentGrid {
 public:
  /// Pieces [0, pieces) of `cut` (pieces > 0); lattice spacing and padding in m.
  /// Refuses (naming the cut) a lattice of more than `max_points` points.
  EnrichmentGrid(const CutSurface& cut, Index pieces, double spacing, double padding);
  /// The same, grown from `before` (the same cut with fewer pieces): in 3D, on
  /// the same lattice, a column before kept its region unless a new piece
  /// holds its projection or lies nearer, so only the new pieces are visited
  /// there (the region of pieces [0, n) is that of [0, k) and [k, n) combined,
  /// earlier pieces winning ties as in cut_region).
  EnrichmentGrid(const CutSurface& cut, Index pieces, double spacing, double padding, const EnrichmentGrid& before);
  EnrichmentGrid(const EnrichmentGrid&) = delete;  // its region index views its frame
  EnrichmentGrid& operator=(const EnrichmentGrid&) = delete;

  static constexpr Index max_points = 20'000'000;

  Index pieces() const { return pieces_; }
  const CutFrame& frame() const { return frame_; }
  double spacing() const { return spacing_; }

  /// phi from the analytic definition (the grid's regions and d+, eq. 23/25).
  PhiValue exact(const Vec3& x) const;
  /// phi from d+ interpolated between columns (see above); exact outside the lattice.
  PhiValue interpolated(const Vec3& x) const;

  /// Built from `before` (the second constructor), so that it knows which of
  /// its columns' phi differs from before's?
  bool knows_changes() const { return !changed_.empty(); }
  /// Does the ball (x, radius) reach a column whose phi differs from `before`'s,
  /// on it or on a neighbouring column (changes between columns thinner than a
  /// lattice spacing are caught by that one-column dilation)? False when the
  /// grid does not know its changes.
  bool reaches_changed_column(const Vec3& x, double radius) const;
  /// The flags reaches_changed_column reads, per column (axis 0 fastest); empty unless knows_changes().
  const std::vector<char>& changed_columns() const { return changed_; }
  /// Same lattice points as `other` (same axes, anchor, spacing; the extent may differ)?
  bool same_lattice(const EnrichmentGrid& other) const;

  /// The lattice for output: origin, axes (unit, world frame), points per axis
  /// (1 on unused axes), phi per point with axis 0 fastest (computed here).
  Vec3 lattice_origin() const;
  const std::array<Vec3, 3>& lattice_axes() const { return axes_; }
  const std::array<Index, 3>& lattice_count() const { return count_; }
  std::vector<double> lattice_phi() const;

 private:
  /// Both public constructors: grown from *before when given.
  EnrichmentGrid(const CutSurface& cut, Index pieces, double spacing, double padding, const EnrichmentGrid* before);
  struct Column {
    Index piece = 0;
    double d_plus = 0.0;
    Vec3 d_plus_gradient = Vec3::Zero();
    // The plane s is measured from: s(x) = s_normal . x - s_offset (the
    // piece's plane, or beyond a 2D cut's ends the common normal's through the end).
    Vec3 s_normal = Vec3::Zero();
    double s_offset = 0.0;
  };
  /// The lattice coordinates of x (lattice axes, origin at the anchor).
  Vec3 coordinates(const Vec3& x) const;
  /// The world point of a column on the common line/plane.
  Vec3 column_point(Index column) const;
  Column column_at(const Vec3& x) const;
  static Column column_of(const CutRegion& r, const Vec3& x);
  /// The index in `other` (the same lattice) of this grid's column, or -1 outside it.
  Index column_in(const EnrichmentGrid& other, Index column) const;
  /// The lattice extent around pieces [0, pieces) (low_, count_); throws when too fine.
  void size_lattice(double padding);
  PhiValue phi_in(const Column& c, const Vec3& x) const;
  /// Same phi all along the column through `base` from both?
  bool same(const Column& a, const Column& b, const Vec3& base) const;
  /// changed_ dilated by one column; changed_box_ the range the flagged columns span.
  void dilate_changes();

  const CutSurface* cut_;
  Index pieces_;
  double spacing_;
  CutFrame frame_;
  CutRegionIndex regions_;      // of pieces [0, pieces_) in frame_
  int dim_;
  Vec3 anchor_;                 // the cut's first vertex: lattice coordinates start here
  std::array<Vec3, 3> axes_;    // lattice axes; the last used one is the normal
  Vec3 low_ = Vec3::Zero();     // lattice corner in lattice coordinates
  std::array<Index, 3> count_{1, 1, 1};
  std::vector<Column> columns_; // axis 0 fastest (3D: then axis 1)
  // Built from `before`: per column, does phi differ from before's (dilated by
  // one column), found while the columns are built; and the flagged columns'
  // index ranges {i0, i1, j0, j1} (empty, i1 < i0, when none).
  std::vector<char> changed_;
  std::array<Index, 4> changed_box_{0, -1, 0, -1};
};

}  // namespace kerf
