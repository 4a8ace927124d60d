#pragma once
// Meshless nodes: a lattice filling a box (finer inside `refine` boxes) or the
// vertices of a mesh, each with its support radius (a multiple of the local
// spacing), its nodal volume (integration weight of nodal integration), a
// flag for nodes on the domain's boundary (for selections), and the simplices
// on the nodes whose barycentric dual cells are the nodal volumes.
#include <span>
#include <vector>

#include "geometry/mesh.h"
#include "problem/scene.h"

namespace kerf {

struct NodeSet {
  int dimension = 3;
  std::vector<Vec3> positions;   // m
  std::vector<double> spacing;   // local node spacing (m)
  std::vector<double> support;   // support radius d_I (m)
  std::vector<double> volume;    // m^3 (2D: m^2 per metre of thickness)
  std::vector<char> on_boundary;
  Mesh cells;  // linear simplices on the nodes (same numbering); volume = dual_cell_volumes(cells)
  Index size() const { return static_cast<Index>(positions.size()); }
};

/// A lattice over the box at `spacing` (adjusted per axis so that nodes lie on
/// every face); inside each refine box, that box's own finer lattice replaces
/// it. Cells: the Delaunay triangulation of the nodes, so the volumes add up
/// to the box's volume.
NodeSet lattice_nodes(int dimension, const Box& box, double spacing, std::span<const RefineRegion> refine,
                      double support_factor);

/// The vertices (corner nodes) of a mesh, so FEM and meshless run on the same
/// nodes; spacing is the mean length of the edges at a node, volumes are the
/// cells' shares (adding up to the mesh's volume).
NodeSet mesh_nodes(const Mesh& mesh, double support_factor);

}  // namespace kerf
