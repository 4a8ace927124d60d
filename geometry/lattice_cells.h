#pragma once
// Cells on a box's node lattice, made without a mesher: the background cells
// of a meshless body whose nodes are that lattice.
#include <array>

#include "core/types.h"
#include "geometry/mesh.h"

namespace kerf {

/// The lattice's intervals along each of the first `dim` axes: round(length
/// / spacing), at least one (as lattice_nodes places its nodes); 0 beyond.
std::array<int, 3> lattice_intervals(int dim, const Vec3& min, const Vec3& max, double spacing);

/// How many cells lattice_cells makes: 5 a cube, 2 a square.
double lattice_cell_count(int dim, const std::array<int, 3>& intervals);

/// How many edges its cells have: the lattice's own, and one diagonal on
/// each square (no cube's diagonal is an edge): the mid-edge nodes of second order.
double lattice_edge_count(int dim, const std::array<int, 3>& intervals);

/// The lattice of the box [min, max] at `spacing`: round(length / spacing) intervals an axis
/// (at least one), as lattice_nodes places its nodes. Each square is split
/// into 2 triangles and each cube into 5 tetrahedra: a central one on the
/// cube's four corners of even parity (i + j + k even, counted over the whole
/// lattice) and one at each other corner. Neighbouring cubes then split their
/// common face along the same diagonal, so the mesh is conforming. Cells
/// positively oriented; nodes numbered with the last axis fastest.
Mesh lattice_cells(int dim, const Vec3& min, const Vec3& max, double spacing);

}  // namespace kerf
