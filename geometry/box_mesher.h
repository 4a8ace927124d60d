#pragma once
// Meshes an axis-aligned box with gmsh: tetrahedra in 3D, triangles in 2D
// (the x-y rectangle), linear or quadratic, with finer size in refine boxes,
// conforming to cuts whose nodes are duplicated.
#include <vector>

#include "geometry/cut_surface.h"
#include "geometry/mesh.h"

namespace kerf {

struct SizeBox {
  Vec3 min, max;
  double size;  // target edge length inside the box (m)
};

struct BoxMeshRequest {
  int dimension = 3;
  int order = 1;
  Vec3 min = Vec3::Zero(), max = Vec3::Ones();
  double size = 0.1;             // target edge length (m)
  std::vector<SizeBox> refine;   // finer regions
  std::vector<CutPiece> cuts;    // the mesh conforms to them and opens along them (gmsh_cuts.h)
};

Mesh mesh_box(const BoxMeshRequest& request);

}  // namespace kerf
