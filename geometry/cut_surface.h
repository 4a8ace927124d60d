#pragma once
// A cut as a list of flat pieces: the segments of a 2D polyline, or the
// triangles of a 3D triangle strip (a blade's two ends, position after
// position), each appearing when the last of its vertices does. And the
// geometry the enrichment functions need from it: the common frame of a run
// of pieces (the paper's eq. 19-20; in 3D the common plane), which piece's
// region a point falls in, the in-frame distance d+ from the cut's projection,
// the signed normal distance s, and whether a straight line crosses the cut.
// Exact predicates (sides, inside a projected triangle, crossings) are CGAL's.
#include <array>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"

namespace kerf {

/// One piece, oriented consistently along the cut: 2D segment a -> b with
/// normal (-t_y, t_x); 3D triangle (a, b, c) with normal (b - a) x (c - a) / |.|.
struct CutPiece {
  std::array<Vec3, 3> corner;  // m; corner[2] unused in 2D
  Vec3 normal = Vec3::Zero();  // unit
  Vec3 centre = Vec3::Zero();  // m
  double size = 0.0;           // length (2D, m) or area (3D, m^2)
};

struct CutSurface {
  int dimension = 3;
  std::vector<Vec3> vertices;  // m
  std::vector<double> times;   // s, one per vertex, never decreasing
  std::vector<CutPiece> pieces;
  std::vector<double> appears;  // s, one per piece
  std::string where;            // the scene location, for messages
  // m: the first piece's size (its corners' largest distance from the first
  // vertex), the scale of the cut's tolerances: fixed once the first piece
  // exists, so a cut fed vertex by vertex has those of the same cut given whole.
  double extent = 0.0;

  Index piece_count() const { return static_cast<Index>(pieces.size()); }
  /// Pieces present at time t: they appear in order, so a prefix.
  Index pieces_at(double t) const;
};

/// Builds and checks a cut: refuses zero-length segments, collapsed
/// triangles, and a cut that folds over its common line or plane (at any
/// stage of its growth), naming `where` and the offending vertex or piece.
/// Fewer vertices than a piece has corners make no piece yet (a cut fed at run time).
CutSurface cut_surface(int dimension, std::vector<Vec3> vertices, std::vector<double> times, std::string where);
/// The same cut grown by `vertices` at `time` (no earlier than its last
/// vertex's), as a blade fed at run time gives them: only the stages the new
/// pieces make are checked, so a growth costs O(pieces), not O(pieces^2).
/// Throws, the cut left as it was, as cut_surface would.
void extend_cut_surface(CutSurface& cut, std::span<const Vec3> vertices, double time);

/// The common frame of pieces [first, last): origin at the size-weighted
/// centre, `normal` the size-weighted mean normal (2D: at the size-weighted
/// mean angle, eq. 20), `axis[0]` the in-frame direction t (2D), `axis[0..1]`
/// an in-plane basis (3D).
struct CutFrame {
  Vec3 origin = Vec3::Zero();
  std::array<Vec3, 2> axis{Vec3::Zero(), Vec3::Zero()};
  Vec3 normal = Vec3::Zero();
};
CutFrame common_frame(const CutSurface& cut, Index first, Index last);

/// Where x lies relative to pieces [first, last) seen in `frame`: the piece
/// whose projection holds x's projection (else the nearest projected piece),
/// d+ = distance of x's projection to the projected pieces (0 over them; 2D:
/// the modified d1+ of eq. 23, measured from the two ends only), and
/// s = normal . (x - corner) of that piece; in 2D beyond the ends (d+ > 0),
/// s = common normal . (x - end vertex), so that nodes ahead of a zigzag's
/// tip keep their side as it grows. Gradients in 1/1 (m/m).
struct CutRegion {
  Index piece = 0;
  double d_plus = 0.0;
  Vec3 d_plus_gradient = Vec3::Zero();
  double s = 0.0;
  Vec3 s_gradient = Vec3::Zero();
};
CutRegion cut_region(const CutSurface& cut, Index first, Index last, const CutFrame& frame, const Vec3& x);

/// Does the segment a-b meet one of pieces [first, last)? A segment with an
/// end on the cut (a node or point lying on it) only touches it: false.
bool segment_crosses_cut(const CutSurface& cut, Index first, Index last, const Vec3& a, const Vec3& b);

/// x itself, or, when x lies on one of pieces [0, pieces) (within 1e-12 of
/// the cut's extent), x moved 1e-9 extents to the side that piece's normal
/// points to: the +1 side, where the Enrichment Grid puts points on the cut.
/// Visibility and diffraction look from there, so a node on the cut sees one side.
Vec3 off_the_cut(const CutSurface& cut, Index pieces, const Vec3& x);

/// Distance (m) from x to the nearest of pieces [first, last).
double distance_to_cut(const CutSurface& cut, Index first, Index last, const Vec3& x);

}  // namespace kerf
