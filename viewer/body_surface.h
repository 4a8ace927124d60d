#pragma once
// The body as the viewer draws it: volume cells whose outer faces are shown,
// their points moved by the displacement, coloured by von Mises stress. A
// FEM body gives its own cells (split by a cut: the cut opens between them);
// a meshless body gives only nodes, so its cells are the nodes' Delaunay
// tetrahedra, less those a cut crosses (the cut shows as a slot, which
// widens as the body opens it).
#include <vector>

#include <vtkNew.h>
#include <vtkUnstructuredGrid.h>

#include "discretization/body_snapshot.h"
#include "geometry/cut_surface.h"

namespace kerf {

class BodySurface {
 public:
  /// From the body's first snapshot (reference points, cells or bare nodes).
  explicit BodySurface(const BodySnapshot& body);
  /// Points moved by the snapshot's displacement, von Mises from it. A body
  /// whose cells changed (a FEM split) takes its new cells.
  void update(const BodySnapshot& body);
  /// Meshless: the cells an edge of which crosses pieces [first, cut.piece_count()) are no longer drawn.
  void cut_by(const CutSurface& cut, Index first);
  vtkUnstructuredGrid* grid() { return grid_; }
  /// The reference position (m) of a point of the drawn surface, from the
  /// "reference" point array a surface filter passes on.
  static constexpr const char* reference_array = "reference";

 private:
  void take_cells(const BodySnapshot& body);
  void rebuild_meshless_cells();

  bool meshless_ = false;
  std::vector<Vec3> reference_;
  std::vector<Index> tetrahedra_;  // meshless: the Delaunay cells, 4 nodes each
  std::vector<char> dropped_;      // per Delaunay cell: a cut crosses it
  Index snapshot_cells_ = -1;      // FEM: the cell count of the cells taken
  vtkNew<vtkUnstructuredGrid> grid_;
};

}  // namespace kerf
