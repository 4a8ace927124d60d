#pragma once
// A mesh made once, on rank 0 (gmsh on the box, or a .msh file read), and
// sent to the other ranks: every rank running gmsh on the whole body at once
// would multiply meshing's memory and time by the ranks on a machine.
#include <functional>
#include <vector>

#include "core/mpi_context.h"
#include "geometry/mesh.h"
#include "geometry/mesh_division.h"

namespace kerf {

/// make() on rank 0 alone; every rank returns rank 0's mesh. A collective
/// call under mpirun (MpiContext::from_first_rank); make() itself in a
/// serial run. When make() throws on rank 0, the others wait in the call
/// until the job is stopped (the command line stops every rank).
Mesh mesh_from_first_rank(const MpiContext& mpi, const std::function<Mesh()>& make);

/// make() on rank 0 alone, its cells divided among the ranks by the
/// context's partitioner on their face graph (geometry/mesh_division.h);
/// each rank returns its piece, and rank 0 keeps nothing else of the mesh. A
/// collective call under mpirun; serial: the whole mesh as one piece.
MeshPiece mesh_piece_from_first_rank(const MpiContext& mpi, const std::function<Mesh()>& make);

/// The mesh as the numbers that go between ranks, and back.
std::vector<double> mesh_to_numbers(const Mesh& mesh);
Mesh mesh_from_numbers(const std::vector<double>& numbers);

}  // namespace kerf
