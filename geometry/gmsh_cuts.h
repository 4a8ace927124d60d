#pragma once
// Cuts a conforming FEM mesh is built around (`fem: remesh`): the pieces are
// fragmented into the gmsh model before meshing, so the mesh has edges (2D)
// or faces (3D) along them, and opened after meshing by gmsh's Crack plugin,
// which duplicates the nodes on them so the two faces move apart. Where a
// cut's edge lies on the domain's boundary (an edge crack) it is opened too;
// inside the body (the tips, the blade's front) the faces stay joined.
#include <vector>

#include "geometry/cut_surface.h"

namespace kerf {

/// Physical group tags of the model's crack (dimension - 1) and of its edges on
/// the domain's boundary (dimension - 2); 0 when there is none.
struct CutGroups {
  int crack = 0;
  int open = 0;
};

/// Fragments the body (entity `body` of `dimension` in the current OpenCASCADE
/// model, the box [min, max]) with the pieces, drops the parts of the pieces
/// outside the box, synchronizes, and returns the groups for open_cuts.
CutGroups embed_cuts(int dimension, int body, const std::vector<CutPiece>& pieces, const Vec3& min, const Vec3& max);

/// After meshing: duplicates the nodes on the crack (gmsh's Crack plugin).
void open_cuts(int dimension, const CutGroups& groups);

}  // namespace kerf
