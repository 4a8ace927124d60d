#pragma once
// `fem: split`: each cell a cut separates is replaced by one copy per side
// (the virtual-node, phantom-node, Heaviside-XFEM space: Molino et al. 2004,
// Song et al. 2006). A copy keeps its parent's shape functions and integrates
// only its side's fragment; the nodes it holds on the far side are
// duplicates. ../shared/reference/split_elements.md has the rules; here:
//   - a node within `snap` of its shortest edge from the cut lies on it
//     (side 0); the others take the side of the nearest piece's plane;
//   - a cell is separated when it has corners on both sides and every edge
//     between them crosses a piece of the cut. A cell the cut's front passes
//     through fails that (some edge passes beyond the front) and stays whole,
//     so the material stays joined beyond the front: the jump ends on the
//     nodes of those cells, about one cell behind the front (the papers' lag);
//   - node copies: around each node, the copies of its cells are joined across
//     the faces holding the node where some corner of the face is material
//     (off the cut, on the copy's side) in both; each group is one node. The
//     group where the node is material keeps its id (on the cut: the + side's),
//     the others are new nodes after the originals.
// A cut lying on mesh faces splits no cell: the nodes on it are duplicated.
#include <span>
#include <vector>

#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf {

struct SplitOptions {
  double snap = 0.05;          // of a node's shortest edge: nodes this near the cut lie on it
  double min_fraction = 1e-4;  // a fragment under this share of its cell is dropped
  /// Over-cut: a cell the cut enters but does not span (its front passes
  /// through it) is split too, along the plane of the piece nearest each of
  /// its edges, so the jump reaches past the front instead of lagging behind.
  bool over_cut = false;
};

struct CellSplit {
  /// The copies as cells, in their parents' order; the original nodes first
  /// (same ids, same positions), then the duplicates.
  Mesh mesh;
  std::vector<Index> origin;          // per node: the original node it copies (itself for originals)
  /// per node: a copy off its own side (it only extends a copy's field
  /// across the cut, as XFEM's phantom nodes): boundary conditions skip it.
  std::vector<char> phantom;
  std::vector<Index> parent;          // per cell: its cell in the original mesh
  std::vector<int> side;              // per cell: +1 or -1 for a copy of a separated cell, 0 for a whole one
  std::vector<Index> fragment_start;  // per cell, + 1: its sub-simplices in fragment_points
  /// (dim + 1) reference coordinates (the parent's, corners' affine map) per
  /// sub-simplex of each copy's fragment; a cell with none is whole.
  std::vector<Vec3> fragment_points;

  Index separated_cells = 0;      // original cells the cut separates
  Index duplicated_nodes = 0;     // nodes added
  double dropped_measure = 0.0;   // m^3 (2D: m^2) of fragments under min_fraction, left out
  double smallest_fraction = 1.0; // the smallest fragment kept, as a share of its cell

  bool whole(Index c) const { return fragment_start[c] == fragment_start[c + 1]; }
  std::span<const Vec3> fragment(Index c) const {
    return {fragment_points.data() + fragment_start[c], fragment_points.data() + fragment_start[c + 1]};
  }
};

/// The side of the cut x lies on: the sign of the plane (2D: line) of the
/// piece nearest to it (+1 where its normal points; 0 on it).
int side_of_cut(int dimension, std::span<const CutPiece> pieces, const Vec3& x);

/// Splits `mesh` along the pieces (of one or several cuts, flat, consistently
/// oriented). A mesh no piece separates comes back as it is.
CellSplit split_cells(const Mesh& mesh, std::span<const CutPiece> pieces, const SplitOptions& options = {});

}  // namespace kerf
