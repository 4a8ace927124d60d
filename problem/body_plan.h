#pragma once
// What a scene's body is built from, decided once from the method's row
// (methods.h) and the scene: the mesh gmsh makes or the file gives (its
// cells' order and size), where a meshless body's nodes come from, and which
// key sets the node count. The body factory builds this plan and the
// resource estimate counts it, so the two cannot disagree on what a scene
// makes.
#include <string>

#include "problem/scene.h"

namespace kerf {

struct MeshPlan {
  bool made = false;  // is there a mesh at all (a meshless body on a lattice may have none)
  int order = 1;      // its cells' order
  double size = 0.0;  // in a box (m): gmsh's target edge length, or the lattice's spacing
  // The box's lattice at `size` split into cells by kerf, no gmsh (meshless.background_cells, fem.box_mesher).
  bool lattice = false;
};

struct BodyPlan {
  const MethodDescriptor* method = nullptr;
  /// FEM: the body's cells. Meshless: the background mesh, where EFG
  /// integrates, where boundary loads and contact are integrated, the nodes
  /// themselves with `nodes: mesh`, the extent of a domain read from a file.
  MeshPlan mesh;
  /// Meshless: the nodes are the mesh's corner nodes (else a lattice in the box).
  bool nodes_on_mesh = false;
  /// Under mpirun, the mesh is divided among the ranks, each holding its
  /// piece (geometry/mesh_division.h), instead of whole on every rank: a FEM
  /// body without what a piece cannot give yet (cells split by a cut, a cut
  /// that grows and so meshes the body anew, nodal stars of averaged
  /// pressure, contact's boundary samples).
  bool divided_among_ranks() const { return whole_on_every_rank.empty(); }
  /// Otherwise, the key that keeps it whole on every rank and what that
  /// means (a run's note under mpirun); empty when divided.
  std::string whole_on_every_rank;
  /// The key whose size sets the node count, and its value (m).
  const char* size_key = "";
  double size = 0.0;
};

BodyPlan body_plan(const Scene& scene);

}  // namespace kerf
