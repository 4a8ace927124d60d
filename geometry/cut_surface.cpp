#include "geometry/cut_surface.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <sstream>

#include "core/check.h"
#include "geometry/cut_projection.h"

namespace kerf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = Kernel::Point_2;
using Point3 = Kernel::Point_3;

/// A piece whose normal is within this cosine of perpendicular to the common
/// normal is a fold: its side of the cut cannot be read off the common frame.
constexpr double fold_cosine = 0.05;  // about 87 degrees

Point2 point2(const Vec3& p) { return {p.x(), p.y()}; }
Point3 point3(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

std::string vector_text(const Vec3& v, int dim) {
  std::ostringstream s;
  s << "[" << v[0] << ", " << v[1];
  if (dim == 3) s << ", " << v[2];
  s << "]";
  return s.str();
}

CutPiece make_piece(int dim, const std::vector<Vec3>& v, Index k) {
  CutPiece p;
  if (dim == 2) {
    p.corner = {v[k], v[k + 1], Vec3::Zero()};
    const Vec3 d = v[k + 1] - v[k];
    p.size = d.norm();
    p.normal = Vec3(-d.y(), d.x(), 0.0) / p.size;
    p.centre = 0.5 * (v[k] + v[k + 1]);
    return p;
  }
  // Strip triangles alternate their winding: flip every other one.
  p.corner = k % 2 == 0 ? std::array<Vec3, 3>{v[k], v[k + 1], v[k + 2]} : std::array<Vec3, 3>{v[k + 1], v[k], v[k + 2]};
  const Vec3 n = (p.corner[1] - p.corner[0]).cross(p.corner[2] - p.corner[0]);
  p.size = 0.5 * n.norm();
  p.normal = n.normalized();
  p.centre = (p.corner[0] + p.corner[1] + p.corner[2]) / 3.0;
  return p;
}

}  // namespace

Index CutSurface::pieces_at(double t) const {
  return static_cast<Index>(std::upper_bound(appears.begin(), appears.end(), t) - appears.begin());
}

namespace {

/// The pieces `vertices` (appended to the cut's) add, each checked for a zero size.
void append_pieces(CutSurface& cut, std::span<const Vec3> vertices, std::span<const double> times) {
  const int dim = cut.dimension;
  const Index corners = dim == 2 ? 2 : 3;
  for (const Vec3& v : vertices) cut.vertices.push_back(dim == 2 ? Vec3(v.x(), v.y(), 0.0) : v);
  cut.times.insert(cut.times.end(), times.begin(), times.end());
  const std::vector<Vec3>& all = cut.vertices;
  const Index n = static_cast<Index>(all.size());
  cut.extent = 0.0;
  for (Index k = 0; k < std::min(n, corners); ++k) cut.extent = std::max(cut.extent, (all[k] - all.front()).norm());
  const double extent = cut.extent;
  for (Index k = cut.piece_count(); k + corners <= n; ++k) {
    CutPiece p = make_piece(dim, all, k);
    if (dim == 2)
      KERF_CHECK(p.size > 1e-12 * extent, cut.where, ": the polyline's segment from vertex ", k, " ",
                 vector_text(all[k], dim), " to vertex ", k + 1, " ", vector_text(all[k + 1], dim),
                 " has zero length; expected distinct consecutive vertices");
    else
      KERF_CHECK(p.size > 1e-12 * extent * extent, cut.where, ": the strip's triangle of vertices ", k, ", ", k + 1,
                 ", ", k + 2, " ", vector_text(all[k], 3), " ", vector_text(all[k + 1], 3), " ",
                 vector_text(all[k + 2], 3), " is collapsed (area ", p.size,
                 " m^2); expected three vertices not on one line");
    cut.pieces.push_back(p);
    cut.appears.push_back(cut.times[k + corners - 1]);
  }
}

/// Every stage of a growing cut from `first_count` pieces on must be readable in its own common frame.
void refuse_folds(const CutSurface& cut, Index first_count) {
  const int dim = cut.dimension;
  const Index corners = dim == 2 ? 2 : 3;
  for (Index count = std::max<Index>(first_count, 1); count <= cut.piece_count(); ++count) {
    if (count < cut.piece_count() && cut.appears[count] == cut.appears[count - 1]) continue;
    const CutFrame frame = common_frame(cut, 0, count);
    for (Index k = 0; k < count; ++k) {
      const double cosine = cut.pieces[k].normal.dot(frame.normal);
      if (cosine > fold_cosine) continue;
      const double degrees = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
      std::ostringstream why;
      why << cut.where << ": the " << (dim == 2 ? "polyline" : "strip") << " folds over its common "
          << (dim == 2 ? "line" : "plane") << ": " << (dim == 2 ? "segment " : "triangle ") << k << " (vertices " << k
          << " to " << k + corners - 1 << ") turns " << degrees << " degrees from the mean "
          << (dim == 2 ? "direction" : "normal") << " of the first " << count
          << " pieces; expected under 87 degrees (split it into separate cuts)";
      throw Error(why.str());
    }
  }
}

}  // namespace

CutSurface cut_surface(int dim, std::vector<Vec3> vertices, std::vector<double> times, std::string where) {
  CutSurface cut;
  cut.dimension = dim;
  cut.where = std::move(where);
  KERF_CHECK(times.size() == vertices.size(), cut.where, ": expected one time per vertex (", vertices.size(),
             "), found ", times.size());
  append_pieces(cut, vertices, times);
  refuse_folds(cut, 1);
  return cut;
}

void extend_cut_surface(CutSurface& cut, std::span<const Vec3> vertices, double time) {
  KERF_CHECK(cut.times.empty() || time >= cut.times.back(), cut.where, ": a vertex at t = ", time,
             " s comes before the cut's last vertex (t = ", cut.times.back(),
             " s); expected times that never decrease");
  const std::size_t vertex_count = cut.vertices.size();
  const Index piece_count = cut.piece_count();
  const double extent = cut.extent;
  try {
    append_pieces(cut, vertices, std::vector<double>(vertices.size(), time));
    refuse_folds(cut, piece_count + 1);  // the earlier stages are as they were checked
  } catch (...) {
    cut.vertices.resize(vertex_count), cut.times.resize(vertex_count);
    cut.pieces.resize(piece_count), cut.appears.resize(piece_count);
    cut.extent = extent;
    throw;
  }
}

CutFrame common_frame(const CutSurface& cut, Index first, Index last) {
  KERF_DCHECK(first < last && last <= cut.piece_count());
  CutFrame f;
  double total = 0.0;
  for (Index k = first; k < last; ++k) {
    f.origin += cut.pieces[k].size * cut.pieces[k].centre;
    total += cut.pieces[k].size;
  }
  f.origin /= total;
  if (cut.dimension == 2) {
    // Eq. 20: the size-weighted mean angle, each angle taken within pi of the first.
    auto angle = [&](Index k) { return std::atan2(-cut.pieces[k].normal.x(), cut.pieces[k].normal.y()); };
    const double reference = angle(first);
    double mean = 0.0;
    for (Index k = first; k < last; ++k)
      mean += cut.pieces[k].size * std::remainder(angle(k) - reference, 2.0 * std::numbers::pi);
    const double theta = reference + mean / total;
    f.axis[0] = Vec3(std::cos(theta), std::sin(theta), 0.0);
    f.normal = Vec3(-std::sin(theta), std::cos(theta), 0.0);
    f.axis[1] = Vec3::UnitZ();
    return f;
  }
  for (Index k = first; k < last; ++k) f.normal += cut.pieces[k].size * cut.pieces[k].normal;
  f.normal.normalize();
  // In-plane axes: the sweep direction of the first piece, then normal x axis.
  Vec3 e = cut.pieces[first].corner[2] - cut.pieces[first].corner[0];
  e -= e.dot(f.normal) * f.normal;
  if (e.norm() < 1e-12 * std::sqrt(total)) e = f.normal.unitOrthogonal();
  f.axis[0] = e.normalized();
  f.axis[1] = f.normal.cross(f.axis[0]);
  return f;
}

CutRegion cut_region(const CutSurface& cut, Index first, Index last, const CutFrame& frame, const Vec3& x) {
  CutRegion r;
  if (cut.dimension == 2) {
    // Eq. 21-24: t along the common direction, regions between vertices' t.
    const double t = frame.axis[0].dot(x - frame.origin);
    auto t_of = [&](Index vertex) { return frame.axis[0].dot(cut.vertices[vertex] - frame.origin); };
    const double t0 = t_of(first), tn = t_of(last);
    Index piece = first;
    while (piece + 1 < last && t >= t_of(piece + 1)) ++piece;
    r.piece = piece;
    if (t < t0) r.d_plus = t0 - t, r.d_plus_gradient = -frame.axis[0];
    if (t > tn) r.d_plus = t - tn, r.d_plus_gradient = frame.axis[0];
    if (r.d_plus > 0.0) {
      // Beyond an end, s is measured along the common normal from that end
      // vertex, not from the end segment's own line: a zigzag's last segment
      // turns with every new piece, and its line would move the nodes ahead
      // of the tip from side to side (each flip mirrors a node's weight).
      const Vec3& end = cut.vertices[t < t0 ? first : last];
      r.s = frame.normal.dot(x - end);
      r.s_gradient = frame.normal;
      return r;
    }
  } else {
    // The common plane's coordinates; the projected triangles keep their winding.
    const Eigen::Vector2d q = in_frame_plane(frame, x);
    ProjectedNearest best;
    for (Index k = first; k < last; ++k)
      if (visit_projected(k, projected_piece(cut.pieces[k], frame), q, best)) break;
    return region_from(cut, frame, x, q, best);
  }
  const CutPiece& p = cut.pieces[r.piece];
  r.s = p.normal.dot(x - p.corner[0]);
  r.s_gradient = p.normal;
  return r;
}

bool segment_crosses_cut(const CutSurface& cut, Index first, Index last, const Vec3& a, const Vec3& b) {
  if (a == b) return false;
  bool crosses = false;
  for (Index k = first; k < last && !crosses; ++k) {
    const auto& c = cut.pieces[k].corner;
    crosses = cut.dimension == 2
                  ? CGAL::do_intersect(Kernel::Segment_2(point2(a), point2(b)),
                                       Kernel::Segment_2(point2(c[0]), point2(c[1])))
                  : CGAL::do_intersect(Kernel::Segment_3(point3(a), point3(b)),
                                       Kernel::Triangle_3(point3(c[0]), point3(c[1]), point3(c[2])));
  }
  if (!crosses) return false;
  const double touch = 1e-12 * cut.extent;
  return distance_to_cut(cut, first, last, a) > touch && distance_to_cut(cut, first, last, b) > touch;
}

Vec3 off_the_cut(const CutSurface& cut, Index pieces, const Vec3& x) {
  const double touch = 1e-12 * cut.extent;
  for (Index k = 0; k < pieces; ++k)
    if (distance_to_cut(cut, k, k + 1, x) <= touch) return x + 1e-9 * cut.extent * cut.pieces[k].normal;
  return x;
}

double distance_to_cut(const CutSurface& cut, Index first, Index last, const Vec3& x) {
  double best = std::numeric_limits<double>::infinity();
  for (Index k = first; k < last; ++k) {
    const auto& c = cut.pieces[k].corner;
    const double d2 =
        cut.dimension == 2
            ? CGAL::squared_distance(point2(x), Kernel::Segment_2(point2(c[0]), point2(c[1])))
            : CGAL::squared_distance(point3(x), Kernel::Triangle_3(point3(c[0]), point3(c[1]), point3(c[2])));
    best = std::min(best, d2);
  }
  return std::sqrt(best);
}

}  // namespace kerf
