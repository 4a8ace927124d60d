#include "geometry/cell_split.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <unordered_map>

#include <Eigen/Dense>

#include "core/check.h"
#include "geometry/cell_fragments.h"
#include "geometry/cut_in_cells.h"
#include "geometry/facet_distance.h"

namespace kerf {
namespace {

constexpr double on_piece_tolerance = 1e-9;  // of a piece's size, in its barycentric coordinates

/// Where the segment p -> q crosses the piece: t in (0, 1), or -1 when it does not.
double crossing_on_piece(int dim, const CutPiece& piece, const Vec3& p, const Vec3& q) {
  const double dp = piece.normal.dot(p - piece.corner[0]), dq = piece.normal.dot(q - piece.corner[0]);
  if (!((dp > 0 && dq < 0) || (dp < 0 && dq > 0))) return -1.0;
  const double t = dp / (dp - dq);
  const Vec3 x = p + t * (q - p);
  const auto& c = piece.corner;
  if (dim == 2) {
    const Vec3 e = c[1] - c[0];
    const double s = (x - c[0]).dot(e) / e.squaredNorm();
    return s >= -on_piece_tolerance && s <= 1 + on_piece_tolerance ? t : -1.0;
  }
  const double twice_area = piece.normal.dot((c[1] - c[0]).cross(c[2] - c[0]));
  for (int k = 0; k < 3; ++k)
    if (piece.normal.dot((c[(k + 1) % 3] - x).cross(c[(k + 2) % 3] - x)) < -on_piece_tolerance * twice_area)
      return -1.0;
  return t;
}

/// The piece nearest x (and its distance): 2D pieces are segments.
std::size_t nearest_piece(int dim, std::span<const CutPiece> pieces, const Vec3& x, double* distance = nullptr) {
  double nearest = std::numeric_limits<double>::infinity();
  std::size_t which = 0;
  for (std::size_t f = 0; f < pieces.size(); ++f) {
    const CutPiece& p = pieces[f];
    const std::array<Vec3, 3> facet = dim == 2 ? std::array<Vec3, 3>{p.corner[0], p.corner[1], p.corner[1]} : p.corner;
    const double d = distance_to_facets(x, std::span(&facet, 1));
    if (d < nearest) nearest = d, which = f;
  }
  if (distance) *distance = nearest;
  return which;
}

std::uint64_t edge_key(Index a, Index b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
}

/// One copy of a cell: the whole cell (side 0) or its fragment on side +1 or -1.
struct Copy {
  Index cell = 0;
  int side = 0;
  std::vector<Vec3> fragment;  // sub-simplices, physical coordinates; empty: whole
};

/// Which side of the cut each node lies on, and where cell edges cross it.
class CutSides {
 public:
  CutSides(const Mesh& mesh, std::span<const CutPiece> pieces, const NodeCells& around, double snap)
      : mesh_(mesh), pieces_(pieces), side_(mesh.node_count(), 1) {
    find_candidates();
    classify_corners(around, snap);
  }
  const std::vector<Index>& candidates() const { return candidates_; }
  int side(Index node) const { return side_[node]; }
  void set_side(Index node, int s) { side_[node] = s; }
  /// Where the edge between nodes a and b (of opposite sides) crosses the cut,
  /// as a point; nullopt when it passes beside it (beyond a front). With
  /// `extended`, an edge beside the cut crosses the plane of the piece nearest
  /// its middle, where that plane separates its ends (the over-cut front).
  std::optional<Vec3> crossing(Index a, Index b, bool extended = false) {
    const EdgeCrossing& e = edge_crossing(a, b);
    const double t = e.on_cut >= 0.0 ? e.on_cut : extended ? e.on_plane : -1.0;
    if (t < 0.0) return std::nullopt;
    const Index p = std::min(a, b), q = std::max(a, b);
    return mesh_.nodes[p] + t * (mesh_.nodes[q] - mesh_.nodes[p]);
  }
  /// The crossing's parameter from a to b (nullopt: none).
  std::optional<double> crossing_parameter(Index a, Index b, bool extended = false) {
    if (!crossing(a, b, extended)) return std::nullopt;
    const EdgeCrossing& e = edge_crossing(a, b);
    const double t = e.on_cut >= 0.0 ? e.on_cut : e.on_plane;
    return a < b ? t : 1.0 - t;
  }

 private:
  /// Cells whose box meets some piece's box, grown by the cell's longest edge.
  void find_candidates() {
    const int corners = mesh_.dimension + 1, piece_corners = mesh_.dimension;
    std::vector<std::array<Vec3, 2>> boxes;
    for (const CutPiece& piece : pieces_) {
      std::array<Vec3, 2> box{piece.corner[0], piece.corner[0]};
      for (int k = 1; k < piece_corners; ++k) {
        box[0] = box[0].cwiseMin(piece.corner[k]);
        box[1] = box[1].cwiseMax(piece.corner[k]);
      }
      boxes.push_back(box);
    }
    for (Index c = 0; c < mesh_.cell_count(); ++c) {
      const auto cell = mesh_.cell(c);
      Vec3 lo = mesh_.nodes[cell[0]], hi = lo;
      for (int k = 1; k < corners; ++k) {
        lo = lo.cwiseMin(mesh_.nodes[cell[k]]);
        hi = hi.cwiseMax(mesh_.nodes[cell[k]]);
      }
      const double reach = (hi - lo).norm();
      for (const auto& box : boxes)
        if ((lo.array() - reach <= box[1].array()).all() && (box[0].array() <= hi.array() + reach).all()) {
          candidates_.push_back(c);
          break;
        }
    }
  }

  /// The corners of candidate cells: on the cut (0) within snap x their
  /// shortest edge, else the side of the nearest piece's plane.
  void classify_corners(const NodeCells& around, double snap) {
    const int corners = mesh_.dimension + 1;
    std::vector<char> done(mesh_.node_count(), 0);
    for (Index c : candidates_)
      for (int k = 0; k < corners; ++k) {
        const Index n = mesh_.cell(c)[k];
        if (done[n]) continue;
        done[n] = 1;
        const Vec3& x = mesh_.nodes[n];
        double nearest = 0.0;
        const std::size_t which = nearest_piece(mesh_.dimension, pieces_, x, &nearest);
        // A node on the cut to round-off lies on it whatever the snap: no side is its own.
        if (nearest <= std::max(snap, 1e-10) * shortest_edge(around, n)) {
          side_[n] = 0;
          continue;
        }
        side_[n] = pieces_[which].normal.dot(x - pieces_[which].corner[0]) > 0 ? 1 : -1;
      }
  }

  double shortest_edge(const NodeCells& around, Index n) const {
    double h = std::numeric_limits<double>::infinity();
    for (Index k = around.start[n]; k < around.start[n + 1]; ++k)
      for (int a = 0; a <= mesh_.dimension; ++a) {
        const Index m = mesh_.cell(around.cells[k])[a];
        if (m != n) h = std::min(h, (mesh_.nodes[m] - mesh_.nodes[n]).norm());
      }
    return h;
  }

  const Mesh& mesh_;
  std::span<const CutPiece> pieces_;
  std::vector<int> side_;
  std::vector<Index> candidates_;
  /// Parameters from the edge's lower node; -1: none.
  struct EdgeCrossing {
    double on_cut = -1.0, on_plane = -1.0;
  };
  const EdgeCrossing& edge_crossing(Index a, Index b) {
    auto found = crossings_.find(edge_key(a, b));
    if (found != crossings_.end()) return found->second;
    const Index p = std::min(a, b), q = std::max(a, b);
    const Vec3 &xp = mesh_.nodes[p], &xq = mesh_.nodes[q];
    EdgeCrossing e;
    for (const CutPiece& piece : pieces_)
      if ((e.on_cut = crossing_on_piece(mesh_.dimension, piece, xp, xq)) >= 0.0) break;
    const CutPiece& nearest = pieces_[nearest_piece(mesh_.dimension, pieces_, 0.5 * (xp + xq))];
    const double dp = nearest.normal.dot(xp - nearest.corner[0]), dq = nearest.normal.dot(xq - nearest.corner[0]);
    if ((dp > 0 && dq < 0) || (dp < 0 && dq > 0)) e.on_plane = dp / (dp - dq);
    return crossings_.emplace(edge_key(a, b), e).first->second;
  }
  std::unordered_map<std::uint64_t, EdgeCrossing> crossings_;
};

/// Union-find over the copies' node slots (copy * nodes per cell + local node).
class Slots {
 public:
  explicit Slots(std::size_t count) : parent_(count) { std::iota(parent_.begin(), parent_.end(), 0); }
  std::size_t find(std::size_t s) {
    while (parent_[s] != s) s = parent_[s] = parent_[parent_[s]];
    return s;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

class Splitter {
 public:
  Splitter(const Mesh& mesh, std::span<const CutPiece> pieces, const SplitOptions& options)
      : mesh_(mesh), options_(options), npc_(mesh.nodes_per_cell()), around_(node_cells(mesh)),
        sides_(mesh, pieces, around_, options.snap) {}

  CellSplit run() {
    make_copies();
    side_mid_edge_nodes();
    Slots slots(copies_.size() * npc_);
    std::vector<Index> involved = involved_nodes();
    for (Index n : involved) join_around(n, slots);
    return assemble(involved, slots);
  }

 private:
  void make_copies();
  std::optional<bool> separation(Index c, const std::array<int, 4>& side);
  void side_mid_edge_nodes();
  std::vector<Index> involved_nodes() const;
  /// The cells holding node n (a mid-edge node: those holding its edge).
  std::vector<Index> cells_of(Index n) const;
  bool material(const Copy& copy, int local) const {
    const int s = sides_.side(mesh_.cell(copy.cell)[local]);
    return copy.side == 0 ? s != 0 : s == copy.side;
  }
  void join_around(Index n, Slots& slots);
  std::unordered_map<std::size_t, Index> number_groups(const std::vector<Index>& involved, Slots& slots);
  CellSplit assemble(const std::vector<Index>& involved, Slots& slots);
  int local_index(Index cell, Index node) const {
    const auto nodes = mesh_.cell(cell);
    return static_cast<int>(std::find(nodes.begin(), nodes.end(), node) - nodes.begin());
  }

  const Mesh& mesh_;
  SplitOptions options_;
  int npc_;
  NodeCells around_;
  CutSides sides_;
  std::vector<Copy> copies_;
  std::vector<Index> copy_start_;            // per cell + 1, into copies_
  std::vector<std::array<Index, 2>> edge_of_;  // per node: the corners of its edge (mid-edge nodes), else -1
  std::vector<char> candidate_, separated_;
  CellSplit out_;
};

/// How cell c meets the cut: not separated (nullopt), separated (false), or
/// split beyond the front (true: over-cut, along its pieces' planes).
std::optional<bool> Splitter::separation(Index c, const std::array<int, 4>& side) {
  const int corners = mesh_.dimension + 1;
  const auto cell = mesh_.cell(c);
  bool plus = false, minus = false;
  for (int k = 0; k < corners; ++k) plus |= side[k] > 0, minus |= side[k] < 0;
  if (!candidate_[c] || !plus || !minus) return std::nullopt;
  // Separated: every edge between the sides crosses the cut. Over-cut, a
  // front cell the cut enters is also split along its nearest piece's plane.
  bool entered = false, spanned = true, extended = true;
  for (int a = 0; a < corners; ++a)
    for (int b = a + 1; b < corners; ++b) {
      if (side[a] * side[b] >= 0) continue;
      const bool crosses = sides_.crossing(cell[a], cell[b]).has_value();
      entered |= crosses;
      spanned &= crosses;
      extended &= crosses || sides_.crossing(cell[a], cell[b], true).has_value();
    }
  if (spanned) return false;
  if (options_.over_cut && entered && extended) return true;
  return std::nullopt;
}

void Splitter::make_copies() {
  const int dim = mesh_.dimension, corners = dim + 1;
  separated_.assign(mesh_.cell_count(), 0);
  candidate_.assign(mesh_.cell_count(), 0);
  for (Index c : sides_.candidates()) candidate_[c] = 1;
  copy_start_.assign(1, 0);
  for (Index c = 0; c < mesh_.cell_count(); ++c) {
    const auto cell = mesh_.cell(c);
    std::array<int, 4> side{};
    std::array<Vec3, 4> x{};
    for (int k = 0; k < corners; ++k) side[k] = sides_.side(cell[k]), x[k] = mesh_.nodes[cell[k]];
    const std::optional<bool> beyond_front = separation(c, side);
    if (!beyond_front) {
      copies_.push_back({c, 0, {}});
      copy_start_.push_back(static_cast<Index>(copies_.size()));
      continue;
    }
    separated_[c] = 1;
    ++out_.separated_cells;
    const CellFragments parts = cell_fragments(
        dim, x, side, [&](int a, int b) { return *sides_.crossing(cell[a], cell[b], *beyond_front); });
    const double measure = cell_measure(mesh_, c);
    for (int s = 0; s < 2; ++s) {
      double fraction = 0.0;
      for (std::size_t k = 0; k < parts.simplices[s].size(); k += corners)
        fraction += simplex_measure(dim, &parts.simplices[s][k]) / measure;
      if (fraction <= options_.min_fraction) {  // (an empty fragment is never a copy)
        out_.dropped_measure += fraction * measure;
        continue;
      }
      out_.smallest_fraction = std::min(out_.smallest_fraction, fraction);
      copies_.push_back({c, s == 0 ? 1 : -1, parts.simplices[s]});
    }
    copy_start_.push_back(static_cast<Index>(copies_.size()));
  }
}

/// A mid-edge node takes the side of its edge's part it lies in: on an edge
/// the cut crosses, the nearer end's (on the cut at the middle); else the side
/// of an end off the cut (0 when both ends lie on it).
void Splitter::side_mid_edge_nodes() {
  edge_of_.assign(mesh_.node_count(), {-1, -1});
  if (mesh_.order == 1) return;
  const auto edges = mid_edge_corners(mesh_.dimension);
  const int corners = mesh_.dimension + 1;
  for (Index c = 0; c < mesh_.cell_count(); ++c) {
    const auto cell = mesh_.cell(c);
    for (std::size_t k = 0; k < edges.size(); ++k) {
      const Index m = cell[corners + k], a = cell[edges[k][0]], b = cell[edges[k][1]];
      if (edge_of_[m][0] >= 0) continue;
      edge_of_[m] = {a, b};
      const int sa = sides_.side(a), sb = sides_.side(b);
      int s = sa != 0 ? sa : sb;
      if (sa * sb < 0)
        if (const auto t = sides_.crossing_parameter(a, b, options_.over_cut)) s = *t > 0.5 ? sa : *t < 0.5 ? sb : 0;
      sides_.set_side(m, s);
    }
  }
}

std::vector<Index> Splitter::involved_nodes() const {
  std::vector<char> involved(mesh_.node_count(), 0);
  for (Index c = 0; c < mesh_.cell_count(); ++c)
    for (Index n : mesh_.cell(c))
      if (separated_[c] || sides_.side(n) == 0) involved[n] = 1;
  std::vector<Index> out;
  for (Index n = 0; n < mesh_.node_count(); ++n)
    if (involved[n]) out.push_back(n);
  return out;
}

std::vector<Index> Splitter::cells_of(Index n) const {
  const bool mid = edge_of_[n][0] >= 0;
  const Index corner = mid ? edge_of_[n][0] : n;
  std::vector<Index> out;
  for (Index k = around_.start[corner]; k < around_.start[corner + 1]; ++k) {
    const Index c = around_.cells[k];
    if (!mid || local_index(c, edge_of_[n][1]) < npc_) out.push_back(c);
  }
  return out;
}

/// Joins n's slots across the faces around it that hold n and some corner
/// material in both copies.
void Splitter::join_around(Index n, Slots& slots) {
  const int dim = mesh_.dimension, corners = dim + 1;
  const std::vector<Index> cells = cells_of(n);
  const bool mid = edge_of_[n][0] >= 0;
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (std::size_t j = i + 1; j < cells.size(); ++j) {
      const auto a = mesh_.cell(cells[i]), b = mesh_.cell(cells[j]);
      std::array<Index, 3> shared{};
      int count = 0;
      for (int k = 0; k < corners; ++k)
        if (std::find(b.begin(), b.begin() + corners, a[k]) != b.begin() + corners && count < 3) shared[count++] = a[k];
      if (count != dim) continue;  // no common face
      const auto holds = [&](Index m) { return std::find(shared.begin(), shared.begin() + count, m) != shared.begin() + count; };
      if (mid ? !(holds(edge_of_[n][0]) && holds(edge_of_[n][1])) : !holds(n)) continue;
      const int la = local_index(cells[i], n), lb = local_index(cells[j], n);
      for (Index p = copy_start_[cells[i]]; p < copy_start_[cells[i] + 1]; ++p)
        for (Index q = copy_start_[cells[j]]; q < copy_start_[cells[j] + 1]; ++q)
          for (int k = 0; k < count; ++k)
            if (material(copies_[p], local_index(cells[i], shared[k])) &&
                material(copies_[q], local_index(cells[j], shared[k]))) {
              slots.join(static_cast<std::size_t>(p) * npc_ + la, static_cast<std::size_t>(q) * npc_ + lb);
              break;
            }
    }
}

/// Each involved node's groups of slots: the one where it is material (on
/// the cut: the + side's, then the - side's) keeps its id, the others are
/// new nodes, appended to out_'s. Returns each group's root's node.
std::unordered_map<std::size_t, Index> Splitter::number_groups(const std::vector<Index>& involved, Slots& slots) {
  const int corners = mesh_.dimension + 1;
  CellSplit& out = out_;
  std::unordered_map<std::size_t, Index> node_of_group;
  for (Index n : involved) {
    // key: the smallest of its cells' sorted corners, so that groups of one
    // rank are numbered alike whatever order the cells come in.
    struct Group { std::size_t root; int rank; std::array<Index, 4> key; };
    std::vector<Group> groups;
    for (Index c : cells_of(n))
      for (Index p = copy_start_[c]; p < copy_start_[c + 1]; ++p) {
        const int local = local_index(c, n);
        const std::size_t root = slots.find(static_cast<std::size_t>(p) * npc_ + local);
        // rank: 4 where n itself is material, else 2 for a + corner material, 1 for a - one
        int rank = material(copies_[p], local) ? 4 : 0;
        for (int k = 0; k < corners; ++k)
          if (material(copies_[p], k)) rank |= sides_.side(mesh_.cell(c)[k]) > 0 ? 2 : 1;
        std::array<Index, 4> key{-1, -1, -1, -1};  // 2D: the last stays -1
        for (int k = 0; k < corners; ++k) key[k] = mesh_.cell(c)[k];
        std::sort(key.begin(), key.end());
        auto g = std::find_if(groups.begin(), groups.end(), [&](const Group& x) { return x.root == root; });
        if (g == groups.end()) {
          groups.push_back({root, rank, key});
        } else {
          g->rank |= rank;
          g->key = std::min(g->key, key);
        }
      }
    std::sort(groups.begin(), groups.end(),
              [](const Group& a, const Group& b) { return a.rank != b.rank ? a.rank > b.rank : a.key < b.key; });
    for (std::size_t k = 0; k < groups.size(); ++k) {
      Index id = n;
      if (k > 0) {
        id = static_cast<Index>(out.mesh.nodes.size());
        out.mesh.nodes.push_back(mesh_.nodes[n]);
        out.origin.push_back(n);
        out.phantom.push_back(!(groups[k].rank & 4) && sides_.side(n) != 0);
        ++out.duplicated_nodes;
      }
      node_of_group[groups[k].root] = id;
    }
  }
  return node_of_group;
}

CellSplit Splitter::assemble(const std::vector<Index>& involved, Slots& slots) {
  const int dim = mesh_.dimension;
  CellSplit& out = out_;
  out.mesh.dimension = dim;
  out.mesh.order = mesh_.order;
  out.mesh.nodes = mesh_.nodes;
  out.origin.resize(mesh_.node_count());
  std::iota(out.origin.begin(), out.origin.end(), 0);
  out.phantom.assign(mesh_.node_count(), 0);
  const std::unordered_map<std::size_t, Index> node_of_group = number_groups(involved, slots);
  std::vector<char> is_involved(mesh_.node_count(), 0);
  for (Index n : involved) is_involved[n] = 1;
  out.fragment_start.assign(1, 0);
  for (Index c = 0; c < mesh_.cell_count(); ++c) {
    const auto cell = mesh_.cell(c);
    std::vector<std::vector<Index>> tuples;
    for (Index p = copy_start_[c]; p < copy_start_[c + 1]; ++p) {
      std::vector<Index> tuple(cell.begin(), cell.end());
      for (int a = 0; a < npc_; ++a)
        if (is_involved[cell[a]]) tuple[a] = node_of_group.at(slots.find(static_cast<std::size_t>(p) * npc_ + a));
      tuples.push_back(std::move(tuple));
    }
    // Two copies on the same nodes are the whole cell (their fragments tile it).
    const bool merged = tuples.size() == 2 && tuples[0] == tuples[1];
    for (std::size_t k = 0; k < (merged ? 1 : tuples.size()); ++k) {
      out.mesh.cells.insert(out.mesh.cells.end(), tuples[k].begin(), tuples[k].end());
      out.parent.push_back(c);
      out.side.push_back(merged ? 0 : copies_[copy_start_[c] + k].side);
      const Copy& copy = copies_[copy_start_[c] + k];
      if (!merged && !copy.fragment.empty()) {
        // Reference coordinates by the corners' affine map.
        Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
        for (int i = 0; i < dim; ++i)
          for (int k2 = 0; k2 < dim; ++k2) J(i, k2) = mesh_.nodes[cell[k2 + 1]][i] - mesh_.nodes[cell[0]][i];
        const Eigen::Matrix3d inverse = J.inverse();
        for (const Vec3& x : copy.fragment) out.fragment_points.push_back(inverse * (x - mesh_.nodes[cell[0]]));
      }
      out.fragment_start.push_back(static_cast<Index>(out.fragment_points.size()));
    }
  }
  return std::move(out);
}

}  // namespace

int side_of_cut(int dimension, std::span<const CutPiece> pieces, const Vec3& x) {
  if (pieces.empty()) return 0;
  const CutPiece& p = pieces[nearest_piece(dimension, pieces, x)];
  const double s = p.normal.dot(x - p.corner[0]);
  return s > 0 ? 1 : s < 0 ? -1 : 0;
}

CellSplit split_cells(const Mesh& mesh, std::span<const CutPiece> pieces, const SplitOptions& options) {
  return Splitter(mesh, pieces, options).run();
}

}  // namespace kerf
