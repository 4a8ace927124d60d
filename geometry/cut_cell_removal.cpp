#include "geometry/cut_cell_removal.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>

namespace kerf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

Kernel::Point_2 point2(const Vec3& p) { return {p.x(), p.y()}; }
Kernel::Point_3 point3(const Vec3& p) { return {p.x(), p.y(), p.z()}; }

/// Some corner strictly on each side of the piece's line (2D) or plane (3D).
bool separates(const Mesh& mesh, std::span<const Index> cell, const CutPiece& piece) {
  bool positive = false, negative = false;
  for (int k = 0; k <= mesh.dimension; ++k) {
    const Vec3& x = mesh.nodes[cell[k]];
    const CGAL::Orientation side =
        mesh.dimension == 2
            ? CGAL::orientation(point2(piece.corner[0]), point2(piece.corner[1]), point2(x))
            : CGAL::orientation(point3(piece.corner[0]), point3(piece.corner[1]), point3(piece.corner[2]), point3(x));
    positive |= side == CGAL::POSITIVE;
    negative |= side == CGAL::NEGATIVE;
  }
  return positive && negative;
}

bool boxes_overlap(const Mesh& mesh, std::span<const Index> cell, const CutPiece& piece) {
  const int corners = mesh.dimension + 1, piece_corners = mesh.dimension;
  for (int k = 0; k < mesh.dimension; ++k) {
    double lo = mesh.nodes[cell[0]][k], hi = lo, piece_lo = piece.corner[0][k], piece_hi = piece_lo;
    for (int i = 1; i < corners; ++i) {
      lo = std::min(lo, mesh.nodes[cell[i]][k]);
      hi = std::max(hi, mesh.nodes[cell[i]][k]);
    }
    for (int i = 1; i < piece_corners; ++i) {
      piece_lo = std::min(piece_lo, piece.corner[i][k]);
      piece_hi = std::max(piece_hi, piece.corner[i][k]);
    }
    if (hi < piece_lo || piece_hi < lo) return false;
  }
  return true;
}

}  // namespace

bool piece_crosses_cell(const Mesh& mesh, Index c, const CutPiece& piece) {
  const std::span<const Index> cell = mesh.cell(c);
  if (!boxes_overlap(mesh, cell, piece) || !separates(mesh, cell, piece)) return false;
  // The line or plane splits the cell; the piece crosses its interior when it
  // meets the cell in more than a point (2D) or a segment (3D).
  if (mesh.dimension == 2) {
    const auto meet = CGAL::intersection(
        Kernel::Segment_2(point2(piece.corner[0]), point2(piece.corner[1])),
        Kernel::Triangle_2(point2(mesh.nodes[cell[0]]), point2(mesh.nodes[cell[1]]), point2(mesh.nodes[cell[2]])));
    return meet && boost::get<Kernel::Segment_2>(&*meet) != nullptr;
  }
  const auto meet = CGAL::intersection(
      Kernel::Triangle_3(point3(piece.corner[0]), point3(piece.corner[1]), point3(piece.corner[2])),
      Kernel::Tetrahedron_3(point3(mesh.nodes[cell[0]]), point3(mesh.nodes[cell[1]]), point3(mesh.nodes[cell[2]]),
                            point3(mesh.nodes[cell[3]])));
  return meet && (boost::get<Kernel::Triangle_3>(&*meet) != nullptr ||
                  boost::get<std::vector<Kernel::Point_3>>(&*meet) != nullptr);
}

Index remove_crossed_cells(Mesh& mesh, std::span<const CutPiece> pieces) {
  std::vector<Index> kept;
  kept.reserve(mesh.cells.size());
  Index removed = 0;
  for (Index c = 0; c < mesh.cell_count(); ++c) {
    bool crossed = false;
    for (const CutPiece& piece : pieces) crossed = crossed || piece_crosses_cell(mesh, c, piece);
    if (crossed) {
      ++removed;
      continue;
    }
    const std::span<const Index> cell = mesh.cell(c);
    kept.insert(kept.end(), cell.begin(), cell.end());
  }
  if (removed == 0) return 0;
  // Renumber the nodes still in a cell, in their old order.
  std::vector<Index> renumbered(mesh.nodes.size(), -1);
  for (Index n : kept) renumbered[n] = 0;
  std::vector<Vec3> nodes;
  for (std::size_t n = 0; n < mesh.nodes.size(); ++n)
    if (renumbered[n] == 0) {
      renumbered[n] = static_cast<Index>(nodes.size());
      nodes.push_back(mesh.nodes[n]);
    }
  for (Index& n : kept) n = renumbered[n];
  mesh.nodes = std::move(nodes);
  mesh.cells = std::move(kept);
  return removed;
}

}  // namespace kerf
