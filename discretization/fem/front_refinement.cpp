#include "discretization/fem/front_refinement.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "discretization/fem/simplex_shape.h"
#include "geometry/cut_in_cells.h"

namespace kerf {
namespace {

constexpr double inside_tolerance = 1e-10;  // barycentric: on a simplex's boundary to round-off
constexpr double same_point = 1e-8;         // of a cell's size: two crossings found apart are one point

struct VecLess {
  bool operator()(const Vec3& p, const Vec3& q) const {
    return std::lexicographical_compare(p.data(), p.data() + 3, q.data(), q.data() + 3);
  }
};

/// A piece of the front: 3D a segment, 2D a free end (a == b).
struct Segment {
  Vec3 a, b;
};

/// The cut's boundary: 3D the piece edges no other piece shares, 2D the
/// polyline ends no other piece shares (pieces of a cut share corners exactly).
std::vector<Segment> front_of(int dim, std::span<const CutPiece> pieces) {
  std::vector<Segment> out;
  if (dim == 2) {
    std::map<Vec3, int, VecLess> uses;
    for (const CutPiece& p : pieces) ++uses[p.corner[0]], ++uses[p.corner[1]];
    for (const auto& [x, n] : uses)
      if (n == 1) out.push_back({x, x});
    return out;
  }
  const auto less = [](const std::pair<Vec3, Vec3>& p, const std::pair<Vec3, Vec3>& q) {
    const VecLess v;
    return v(p.first, q.first) || (!v(q.first, p.first) && v(p.second, q.second));
  };
  std::map<std::pair<Vec3, Vec3>, int, decltype(less)> uses(less);
  for (const CutPiece& p : pieces)
    for (int k = 0; k < 3; ++k) {
      Vec3 a = p.corner[k], b = p.corner[(k + 1) % 3];
      if (VecLess{}(b, a)) std::swap(a, b);
      ++uses[{a, b}];
    }
  for (const auto& [edge, n] : uses)
    if (n == 1) out.push_back({edge.first, edge.second});
  return out;
}

/// A point of the front, on the input mesh's simplex `at` (its corners,
/// ascending; one corner: the point is that node).
struct FrontPoint {
  std::vector<Index> at;
  std::vector<double> weight;  // barycentric, on `at`
  Vec3 x;                      // straight-sided position (m)
};

/// Barycentric coordinates of x in the straight simplex with these corners.
std::vector<double> barycentric(int dim, std::span<const Vec3> corner, const Vec3& x) {
  Eigen::MatrixXd M(dim, dim);
  for (int k = 0; k < dim; ++k) M.col(k) = (corner[k + 1] - corner[0]).head(dim);
  const Eigen::VectorXd mu = M.partialPivLu().solve((x - corner[0]).head(dim));
  std::vector<double> l(dim + 1);
  l[0] = 1.0 - mu.sum();
  for (int k = 0; k < dim; ++k) l[k + 1] = mu[k];
  return l;
}

/// Points of the front on the input mesh: crossings with faces (3D), ends
/// inside cells. One point per simplex per segment; the same point found
/// from several segments (a corner of the front) is one.
class FrontPoints {
 public:
  explicit FrontPoints(const Mesh& mesh) : mesh_(mesh) {
    const int corners = mesh.dimension + 1;
    for (Index c = 0; c < mesh.cell_count(); ++c) {
      Vec3 lo = mesh.nodes[mesh.cell(c)[0]], hi = lo;
      for (int k = 1; k < corners; ++k) {
        lo = lo.cwiseMin(mesh.nodes[mesh.cell(c)[k]]);
        hi = hi.cwiseMax(mesh.nodes[mesh.cell(c)[k]]);
      }
      boxes_.push_back({lo, hi});
    }
  }

  /// Finds the segment's points; returns them with their parameter along it.
  std::vector<std::pair<double, std::size_t>> add(const Segment& s) {
    std::vector<std::pair<double, std::size_t>> on_segment;
    std::map<std::vector<Index>, std::size_t> here;
    const Vec3 lo = s.a.cwiseMin(s.b), hi = s.a.cwiseMax(s.b);
    const int dim = mesh_.dimension, corners = dim + 1;
    std::set<std::array<Index, 3>> faces_done;
    for (Index c = 0; c < mesh_.cell_count(); ++c) {
      const double size = (boxes_[c][1] - boxes_[c][0]).norm(), margin = 1e-9 * size;
      if (((boxes_[c][0].array() - margin) > hi.array()).any() || ((boxes_[c][1].array() + margin) < lo.array()).any())
        continue;
      const auto cell = mesh_.cell(c);
      std::array<Index, 4> ids{};
      std::array<Vec3, 4> x{};
      for (int k = 0; k < corners; ++k) ids[k] = cell[k], x[k] = mesh_.nodes[cell[k]];
      for (const auto& [t, end] : {std::pair{0.0, s.a}, std::pair{1.0, s.b}}) {
        if (dim == 2 && t == 1.0) break;  // a 2D end is one point
        const auto l = barycentric(dim, std::span(x.data(), corners), end);
        if (*std::min_element(l.begin(), l.end()) >= -inside_tolerance)
          note(std::span(ids.data(), corners), l, t, size, here, on_segment);
      }
      if (dim == 3)
        for (int skip = 0; skip < 4; ++skip) {
          std::array<Index, 3> face{};
          for (int k = 0, j = 0; k < 4; ++k)
            if (k != skip) face[j++] = ids[k];
          std::sort(face.begin(), face.end());
          if (!faces_done.insert(face).second) continue;
          cross_face(s, face, size, here, on_segment);
        }
    }
    return on_segment;
  }

  std::vector<FrontPoint>& points() { return points_; }

 private:
  /// Where the segment crosses the face (corners ascending, so each face is
  /// computed alike from both its cells).
  void cross_face(const Segment& s, const std::array<Index, 3>& face, double size,
                  std::map<std::vector<Index>, std::size_t>& here,
                  std::vector<std::pair<double, std::size_t>>& on_segment) {
    const Vec3 &A = mesh_.nodes[face[0]], &B = mesh_.nodes[face[1]], &C = mesh_.nodes[face[2]];
    const Vec3 n = (B - A).cross(C - A), d = s.b - s.a;
    const double denominator = n.dot(d);
    if (std::abs(denominator) <= 1e-12 * n.norm() * d.norm()) return;  // along the face: no crossing point
    const double t = n.dot(A - s.a) / denominator;
    if (t < -inside_tolerance || t > 1.0 + inside_tolerance) return;
    const Vec3 x = s.a + t * d;
    const double area = n.squaredNorm();
    std::vector<double> mu{n.dot((B - x).cross(C - x)) / area, n.dot((C - x).cross(A - x)) / area, 0.0};
    mu[2] = 1.0 - mu[0] - mu[1];
    if (*std::min_element(mu.begin(), mu.end()) < -inside_tolerance) return;
    note(face, mu, t, size, here, on_segment);
  }

  /// Records a point given by barycentric coordinates on `ids` (those under
  /// round-off dropped: the point lies on that face, edge or corner).
  void note(std::span<const Index> ids, const std::vector<double>& l, double t, double size,
            std::map<std::vector<Index>, std::size_t>& here,
            std::vector<std::pair<double, std::size_t>>& on_segment) {
    std::vector<std::pair<Index, double>> kept;
    double total = 0.0;
    for (std::size_t k = 0; k < ids.size(); ++k)
      if (l[k] > inside_tolerance) kept.push_back({ids[k], l[k]}), total += l[k];
    std::sort(kept.begin(), kept.end());
    FrontPoint p;
    p.x = Vec3::Zero();
    for (const auto& [id, w] : kept) {
      p.at.push_back(id);
      p.weight.push_back(w / total);
      p.x += (w / total) * mesh_.nodes[id];
    }
    if (here.count(p.at)) return;  // this segment's point on that simplex is known
    std::size_t index = points_.size();
    auto [first, last] = by_place_.equal_range(p.at);
    for (auto it = first; it != last; ++it)
      if (p.at.size() == 1 || (points_[it->second].x - p.x).norm() <= same_point * size) index = it->second;
    if (index == points_.size()) {
      by_place_.emplace(p.at, index);
      points_.push_back(std::move(p));
    }
    here[points_[index].at] = index;
    on_segment.push_back({t, index});
  }

  const Mesh& mesh_;
  std::vector<std::array<Vec3, 2>> boxes_;
  std::vector<FrontPoint> points_;
  std::multimap<std::vector<Index>, std::size_t> by_place_;
};

/// One input cell cut into children by the points it holds, in its
/// reference coordinates.
struct Children {
  std::vector<Vec3> xi;      // per vertex
  std::vector<Index> id;     // per vertex: the input node (< N) or N + the point's index
  std::vector<std::array<int, 4>> simplices;

  void insert(int dim, const Vec3& at, Index id_of_point) {
    const int v = static_cast<int>(xi.size());
    xi.push_back(at);
    id.push_back(id_of_point);
    std::vector<std::array<int, 4>> next;
    for (const auto& s : simplices) {
      std::array<Vec3, 4> corner{};
      for (int k = 0; k <= dim; ++k) corner[k] = xi[s[k]];
      const auto l = barycentric(dim, std::span(corner.data(), dim + 1), at);
      if (*std::min_element(l.begin(), l.end()) < -inside_tolerance) {
        next.push_back(s);
        continue;
      }
      for (int k = 0; k <= dim; ++k)
        if (l[k] > inside_tolerance) {
          auto child = s;
          child[k] = v;  // the corner the point replaces: same orientation, as l[k] > 0
          next.push_back(child);
        }
    }
    simplices = std::move(next);
  }
};

std::uint64_t pair_key(Index a, Index b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
}

/// The cells whose corners include all of `ids` (ascending or not).
std::vector<Index> cells_holding(const Mesh& mesh, const NodeCells& around, std::span<const Index> ids) {
  std::vector<Index> out;
  const int corners = mesh.dimension + 1;
  const Index n = ids[0];
  for (Index i = around.start[n]; i < around.start[n + 1]; ++i) {
    const auto cell = mesh.cell(around.cells[i]);
    if (std::all_of(ids.begin(), ids.end(), [&](Index id) {
          return std::find(cell.begin(), cell.begin() + corners, id) != cell.begin() + corners;
        }))
      out.push_back(around.cells[i]);
  }
  return out;
}

/// The input cells each point lies in (every cell holding its simplex).
std::vector<std::vector<std::size_t>> points_per_cell(const Mesh& mesh, const NodeCells& around,
                                                      const std::vector<FrontPoint>& points) {
  std::vector<std::vector<std::size_t>> out(mesh.cell_count());
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (points[p].at.size() == 1) continue;  // a node of the mesh: nothing to insert
    for (Index c : cells_holding(mesh, around, points[p].at)) out[c].push_back(p);
  }
  return out;
}

/// The refined mesh put together: children's corners, their mid-edge nodes,
/// the input's unused mid-edge nodes dropped.
class Assembly {
 public:
  Assembly(const Mesh& input, std::size_t points) : input_(input), N_(input.node_count()) {
    position_.assign(N_ + points, Vec3::Zero());
    for (Index i = 0; i < N_; ++i) position_[i] = input.nodes[i];
  }

  void keep(Index c) {
    const auto cell = input_.cell(c);
    cells_.insert(cells_.end(), cell.begin(), cell.end());
    parent_.push_back(c);
    reference_start_.push_back(static_cast<Index>(reference_.size()));
  }

  void add_children(Index c, const Children& ch) {
    const int dim = input_.dimension, order = input_.order, corners = dim + 1;
    const auto cell = input_.cell(c);
    for (std::size_t v = corners; v < ch.id.size(); ++v) position_[ch.id[v]] = map(c, ch.xi[v]);
    for (const auto& s : ch.simplices) {
      for (int k = 0; k < corners; ++k) {
        cells_.push_back(ch.id[s[k]]);
        reference_.push_back(ch.xi[s[k]]);
      }
      if (order == 2)
        for (const auto& e : mid_edge_corners(dim)) {
          const int i = s[e[0]], j = s[e[1]];
          cells_.push_back(mid_node(c, cell, ch.id[i], ch.id[j], 0.5 * (ch.xi[i] + ch.xi[j])));
          reference_.push_back(0.5 * (ch.xi[i] + ch.xi[j]));
        }
      parent_.push_back(c);
      reference_start_.push_back(static_cast<Index>(reference_.size()));
    }
  }

  /// The input's nodes no cell uses any more dropped (unless no input cell used them either).
  FrontRefinement finish() {
    FrontRefinement r;
    std::vector<char> used(position_.size(), 0), used_before(N_, 0);
    for (Index n : cells_) used[n] = 1;
    for (Index n : input_.cells) used_before[n] = 1;
    std::vector<Index> renumber(position_.size(), -1);
    r.mesh.dimension = input_.dimension;
    r.mesh.order = input_.order;
    for (std::size_t n = 0; n < position_.size(); ++n) {
      const bool input = static_cast<Index>(n) < N_;
      if (!used[n] && (!input || used_before[n])) continue;
      renumber[n] = r.mesh.node_count();
      r.mesh.nodes.push_back(position_[n]);
      r.input_node.push_back(input ? static_cast<Index>(n) : -1);
    }
    r.mesh.cells.reserve(cells_.size());
    for (Index n : cells_) r.mesh.cells.push_back(renumber[n]);
    r.parent = std::move(parent_);
    r.reference_start = std::move(reference_start_);
    r.reference = std::move(reference_);
    return r;
  }

  /// The cells' nodes so far, numbered before finish() (points: N + index).
  const std::vector<Index>& cells() const { return cells_; }

 private:
  /// The parent's map (quadratic when the mesh is) at reference coordinates xi.
  Vec3 map(Index c, const Vec3& xi) const {
    const int npc = input_.nodes_per_cell();
    double N[10];
    simplex_shape_values(input_.dimension, input_.order, xi, N);
    Vec3 x = Vec3::Zero();
    for (int a = 0; a < npc; ++a) x += N[a] * input_.nodes[input_.cell(c)[a]];
    return x;
  }

  /// The mid-edge node between corners a and b of a child of cell c: the
  /// parent's own where the edge is one of its edges, else one shared by
  /// every child on that edge, placed by the parent's map.
  Index mid_node(Index c, std::span<const Index> cell, Index a, Index b, const Vec3& xi) {
    const int dim = input_.dimension, corners = dim + 1;
    if (a < N_ && b < N_) {
      const auto mids = mid_edge_corners(dim);
      for (std::size_t m = 0; m < mids.size(); ++m) {
        const Index p = cell[mids[m][0]], q = cell[mids[m][1]];
        if ((p == a && q == b) || (p == b && q == a)) return cell[corners + m];
      }
    }
    auto [it, added] = mid_.emplace(pair_key(a, b), static_cast<Index>(position_.size()));
    if (added) position_.push_back(map(c, xi));
    return it->second;
  }

  const Mesh& input_;
  Index N_;
  std::vector<Vec3> position_;
  std::vector<Index> cells_, parent_, reference_start_{0};
  std::vector<Vec3> reference_;
  std::unordered_map<std::uint64_t, Index> mid_;
};

}  // namespace

FrontRefinement refine_front(const Mesh& mesh, std::span<const CutPiece> pieces) {
  const int dim = mesh.dimension, corners = dim + 1;
  const Index N = mesh.node_count();
  FrontPoints found(mesh);
  std::vector<std::vector<std::pair<double, std::size_t>>> along;
  for (const Segment& s : front_of(dim, pieces)) along.push_back(found.add(s));
  const std::vector<FrontPoint>& points = found.points();
  const auto id_of = [&](std::size_t p) { return points[p].at.size() == 1 ? points[p].at[0] : N + Index(p); };

  Assembly assembly(mesh, points.size());
  const NodeCells around = node_cells(mesh);
  const auto inside = points_per_cell(mesh, around, points);
  Index subdivided = 0;
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    if (inside[c].empty()) {
      assembly.keep(c);
      continue;
    }
    const auto cell = mesh.cell(c);
    Children ch;
    ch.simplices.push_back({0, 1, 2, 3});
    for (int k = 0; k < corners; ++k) {
      ch.xi.push_back(simplex_node_position(dim, 1, k));
      ch.id.push_back(cell[k]);
    }
    std::vector<std::size_t> order = inside[c];
    std::sort(order.begin(), order.end());  // every cell inserts a shared simplex's points alike
    for (std::size_t p : order) {
      Vec3 xi = Vec3::Zero();
      for (std::size_t i = 0; i < points[p].at.size(); ++i) {
        const int k = static_cast<int>(std::find(cell.begin(), cell.begin() + corners, points[p].at[i]) - cell.begin());
        xi += points[p].weight[i] * simplex_node_position(dim, 1, k);
      }
      ch.insert(dim, xi, id_of(p));
    }
    assembly.add_children(c, ch);
    ++subdivided;
  }

  // Which consecutive points of a segment (in one input cell) are now joined by an edge.
  std::unordered_set<std::uint64_t> edges;
  const auto& cells = assembly.cells();
  const int npc = mesh.nodes_per_cell();
  for (std::size_t c = 0; c < cells.size() / npc; ++c)
    for (int i = 0; i < corners; ++i)
      for (int j = i + 1; j < corners; ++j) edges.insert(pair_key(cells[c * npc + i], cells[c * npc + j]));
  Index segments = 0, unresolved = 0;
  for (auto& list : along) {
    std::sort(list.begin(), list.end());
    for (std::size_t k = 0; k + 1 < list.size(); ++k) {
      const std::size_t p = list[k].second, q = list[k + 1].second;
      if (p == q) continue;
      std::vector<Index> both = points[p].at;
      both.insert(both.end(), points[q].at.begin(), points[q].at.end());
      std::sort(both.begin(), both.end());
      both.erase(std::unique(both.begin(), both.end()), both.end());
      if (static_cast<int>(both.size()) > corners || cells_holding(mesh, around, both).empty()) continue;  // outside the body
      ++segments;
      if (!edges.count(pair_key(id_of(p), id_of(q)))) ++unresolved;
    }
  }

  FrontRefinement r = assembly.finish();
  r.subdivided_cells = subdivided;
  r.front_points = static_cast<Index>(
      std::count_if(points.begin(), points.end(), [](const FrontPoint& p) { return p.at.size() > 1; }));
  r.front_segments = segments;
  r.unresolved_segments = unresolved;
  return r;
}

}  // namespace kerf
