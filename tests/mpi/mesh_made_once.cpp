// Under mpirun: the mesh is made (gmsh) on rank 0 alone, and every rank
// receives rank 0's mesh exactly (its numbers sent back again by rank 0 and
// compared one by one).
// usage: mpirun -np N mesh_made_once   (N >= 2)
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/rank_share.h"
#include "geometry/box_mesher.h"
#include "geometry/mesh_from_first_rank.h"
#include "solvers/petsc_session.h"
#include "solvers/rank_messages.h"

namespace {

[[noreturn]] void fail(int rank, const std::string& message) {
  std::fprintf(stderr, "FAILED on rank %d: %s\n", rank, message.c_str());
  std::exit(1);
}

}  // namespace

int main() {
  using namespace kerf;
  const RankShare ranks = mpi_ranks();
  if (!ranks.distributed()) fail(0, "run me under mpirun with 2 ranks or more");
  const MpiContext mpi{ranks, &send_from_first_rank};
  int made = 0;
  const Mesh mesh = mesh_from_first_rank(mpi, [&] {
    ++made;
    BoxMeshRequest request;
    request.order = 2;
    request.max = Vec3(0.03, 0.01, 0.01);
    request.size = 0.004;
    return mesh_box(request);
  });
  if (made != (ranks.rank == 0 ? 1 : 0)) fail(ranks.rank, "meshed " + std::to_string(made) + " times");
  if (mesh.cell_count() == 0 || mesh.order != 2) fail(ranks.rank, "received no tet10 cells");
  const std::vector<double> mine = mesh_to_numbers(mesh);
  if (mpi.from_first_rank(mine) != mine) fail(ranks.rank, "its mesh is not rank 0's");
  std::printf("rank %d: %d nodes, %d cells, rank 0's\n", ranks.rank, mesh.node_count(), mesh.cell_count());
  return 0;
}
