#pragma once
// fem.split_front: subdivide. The cells a cut's front passes through are
// subdivided so that the front runs along edges of the mesh, and the split
// that follows ends the jump on the front itself rather than a cell behind it
// (split_elements.md 2.6, "subdivide front elements").
//
// The front is the cut's boundary inside the body (3D: the edges of the
// pieces that no other piece shares; 2D: the polyline's free ends). Every
// point where it crosses a face or an edge of the mesh, or ends inside a cell,
// is inserted by splitting the simplices that hold it: a simplex becomes one
// child per corner the point does not lie against, that corner replaced by the
// point (inside a tet: 4 children; on a face: 3 in each of its two cells; on
// an edge: 2 in each cell around it). Every simplex holding a point is split
// the same way from all its cells, so the mesh stays conforming. Points are
// not moved: one moved onto a nearby edge or corner would leave the cut's
// plane, and the cells around it, the cut inside them, would stay whole (a
// weld behind the front, measured: the cut block's sag 19% short at 3 mm
// against 6%). A front passing near an edge or a node leaves thin children.
//
// Once a cell holds both ends of a front segment, the later insertion makes
// the segment an edge; a cut that is flat in the cell then spans every child
// it meets. The children are quadratic when the mesh is: new nodes sit where
// the parent's map puts them, so the children carry the parent's field
// exactly, and a state is carried by the parent's shape functions.
#include <span>
#include <vector>

#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf {

struct FrontRefinement {
  /// The input's nodes first, in their order (a quadratic mesh's mid-edge
  /// nodes on a split edge dropped), then the added ones.
  Mesh mesh;
  std::vector<Index> input_node;       // per node: the input's node it is, or -1 for one added
  std::vector<Index> parent;           // per cell: the input's cell it lies in
  std::vector<Index> reference_start;  // per cell + 1: its nodes' coordinates in `reference`
  /// The parent's reference coordinates of each node of a child; a cell with
  /// an empty range is its parent itself.
  std::vector<Vec3> reference;

  Index subdivided_cells = 0;     // input cells split into children
  Index front_points = 0;         // points inserted (corners; mid-edge nodes not counted)
  Index front_segments = 0;       // front segments inside the body, between consecutive points
  Index unresolved_segments = 0;  // of those, not made an edge (the jump lags there)

  bool child(Index c) const { return reference_start[c] != reference_start[c + 1]; }
  std::span<const Vec3> child_reference(Index c) const {
    return {reference.data() + reference_start[c], reference.data() + reference_start[c + 1]};
  }
};

/// The front of `pieces` (one or several cuts) made edges of `mesh`. A mesh
/// the front misses comes back as it is.
FrontRefinement refine_front(const Mesh& mesh, std::span<const CutPiece> pieces);

}  // namespace kerf
