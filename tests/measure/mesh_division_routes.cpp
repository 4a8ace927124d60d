// Measures the two routes issue 38 names for dividing a FEM mesh among MPI
// ranks, on the same mesh made on rank 0 before the clock starts:
//   kerf    its own cells' face graph, PT-Scotch through MatPartitioning,
//           divide_mesh (own cells and one ghost layer, every tet10 node and
//           position), each piece sent by a PETSc scatter
//           (mesh_piece_from_first_rank), rank 0 dropping the whole mesh;
//   dmplex  the corner cells handed to DMPlexCreateFromCellListParallelPetsc
//           (uninterpolated, all on rank 0), DMPlexDistribute with overlap 1
//           by PT-Scotch, each rank's original cell numbers through the
//           migration SF, the serial DM dropped. Only the partition and the
//           overlap: the tet10 nodes' numbers and positions would still have
//           to be sent, so its figures are a floor for the route.
// Each rank's seconds, resident memory before and after, and peak (the peak
// reset through /proc/self/clear_refs when the clock starts), to rank 0,
// which prints one line a rank.
// usage: mpirun -np N mesh_division_routes kerf|dmplex SIZE_M [MESH.msh]
//   (without a file: gmsh's tet10 on the 10 x 2 x 2 cm cantilever at SIZE_M)
#include <malloc.h>
#include <petscdmplex.h>
#include <petscsf.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "core/check.h"
#include "geometry/box_mesher.h"
#include "geometry/mesh_from_first_rank.h"
#include "geometry/msh_reader.h"
#include "solvers/petsc_session.h"
#include "solvers/rank_messages.h"

namespace {

using namespace kerf;

/// A /proc/self/status figure in MB (VmRSS, VmHWM).
double status_mb(const std::string& key) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind(key + ":", 0) == 0) return std::atof(line.c_str() + key.size() + 1) / 1024.0;
  return -1.0;
}

/// Corner cells (the first four nodes of each tet) on their own vertex numbering, for DMPlex.
struct CornerMesh {
  std::vector<PetscInt> cells;
  std::vector<PetscReal> coordinates;
};

CornerMesh corners_of(const Mesh& mesh) {
  CornerMesh out;
  std::vector<PetscInt> vertex(mesh.nodes.size(), -1);
  for (Index c = 0; c < mesh.cell_count(); ++c)
    for (int k = 0; k < 4; ++k) {
      const Index n = mesh.cell(c)[k];
      if (vertex[n] < 0) {
        vertex[n] = static_cast<PetscInt>(out.coordinates.size() / 3);
        out.coordinates.insert(out.coordinates.end(), mesh.nodes[n].data(), mesh.nodes[n].data() + 3);
      }
      out.cells.push_back(vertex[n]);
    }
  return out;
}

/// What a route leaves a rank: its cells, own and ghost, and DMPlex's mesh when it made one.
struct Division {
  double own_cells = 0, ghost_cells = 0;
  DM dm = nullptr;
};

/// Each of `divided`'s cells' number in rank 0's `serial` mesh, through the
/// migration SF (what a route must know to send the cells' tet10 nodes);
/// stops when one has none.
std::vector<PetscInt> source_cells(DM serial, DM divided, PetscSF migration) {
  PetscInt start = 0, end = 0, cell_end = 0, old_start = 0, old_end = 0, old_cells = 0;
  check_petsc(DMPlexGetChart(divided, &start, &end), "DMPlexGetChart");
  check_petsc(DMPlexGetHeightStratum(divided, 0, nullptr, &cell_end), "DMPlexGetHeightStratum");
  check_petsc(DMPlexGetChart(serial, &old_start, &old_end), "DMPlexGetChart");
  check_petsc(DMPlexGetHeightStratum(serial, 0, nullptr, &old_cells), "DMPlexGetHeightStratum");
  std::vector<PetscInt> old_number(old_end - old_start), new_number(end - start, -1);
  for (PetscInt p = old_start; p < old_end; ++p) old_number[p - old_start] = p;
  if (!migration) return {old_number.begin(), old_number.begin() + old_cells};  // one rank: nothing moved
  check_petsc(PetscSFBcastBegin(migration, MPIU_INT, old_number.data(), new_number.data(), MPI_REPLACE), "Bcast");
  check_petsc(PetscSFBcastEnd(migration, MPIU_INT, old_number.data(), new_number.data(), MPI_REPLACE), "Bcast");
  new_number.resize(cell_end);
  for (const PetscInt n : new_number)
    KERF_CHECK(n >= 0, "DMPlex's migration gave a cell of this rank no cell of rank 0's mesh");
  return new_number;
}

/// DMPlex's partition and overlap of rank 0's mesh.
Division dmplex_route(Mesh&& whole) {
  PetscInt cells = 0, vertices = 0;
  CornerMesh corners;
  if (!whole.nodes.empty()) {
    corners = corners_of(whole);
    cells = static_cast<PetscInt>(whole.cell_count());
    vertices = static_cast<PetscInt>(corners.coordinates.size() / 3);
  }
  whole = Mesh{};
  DM serial = nullptr, divided = nullptr;
  PetscSF migration = nullptr;
  check_petsc(DMPlexCreateFromCellListParallelPetsc(PETSC_COMM_WORLD, 3, cells, vertices, PETSC_DECIDE, 4,
                                                     PETSC_FALSE, corners.cells.data(), 3,
                                                     corners.coordinates.data(), nullptr, nullptr, &serial),
              "DMPlexCreateFromCellListParallelPetsc");
  corners = CornerMesh{};
  PetscPartitioner partitioner = nullptr;
  check_petsc(DMPlexGetPartitioner(serial, &partitioner), "DMPlexGetPartitioner");
  check_petsc(PetscPartitionerSetType(partitioner, PETSCPARTITIONERPTSCOTCH), "PetscPartitionerSetType");
  check_petsc(DMPlexDistribute(serial, 1, &migration, &divided), "DMPlexDistribute");
  Division division;
  division.dm = divided ? divided : serial;
  const std::vector<PetscInt> source = source_cells(serial, division.dm, migration);
  IS numbering = nullptr;  // owned cells >= 0, ghosts -(g + 1); DMPlex's to keep
  check_petsc(DMPlexGetCellNumbering(division.dm, &numbering), "DMPlexGetCellNumbering");
  const PetscInt* number = nullptr;
  check_petsc(ISGetIndices(numbering, &number), "ISGetIndices");
  for (std::size_t c = 0; c < source.size(); ++c) (number[c] >= 0 ? division.own_cells : division.ghost_cells) += 1;
  check_petsc(ISRestoreIndices(numbering, &number), "ISRestoreIndices");
  if (divided) check_petsc(DMDestroy(&serial), "DMDestroy");
  malloc_trim(0);  // as kerf's route does on rank 0 once the whole mesh is gone
  check_petsc(PetscSFDestroy(&migration), "PetscSFDestroy");
  return division;
}

Division kerf_route(const MpiContext& mpi, Mesh&& whole, MeshPiece& piece) {
  piece = mesh_piece_from_first_rank(mpi, [&] { return std::move(whole); });
  return {static_cast<double>(piece.own_cells), static_cast<double>(piece.mesh.cell_count() - piece.own_cells)};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || (std::string(argv[1]) != "kerf" && std::string(argv[1]) != "dmplex")) {
    std::fprintf(stderr, "usage: mesh_division_routes kerf|dmplex SIZE_M [MESH.msh]\n");
    return 2;
  }
  const std::string route = argv[1];
  ensure_petsc_initialized();
  const RankShare ranks = mpi_ranks();
  const MpiContext mpi = petsc_mpi_context(ranks);
  Mesh whole;
  if (ranks.rank == 0) {
    if (argc > 3) {
      whole = read_msh(argv[3], 3, MshOrder::second);
    } else {
      BoxMeshRequest request;
      request.order = 2;
      request.max = Vec3(0.1, 0.02, 0.02);
      request.size = std::atof(argv[2]);
      whole = mesh_box(request);
    }
  }
  const double total_cells = static_cast<double>(whole.cell_count());
  check_petsc(PetscBarrier(nullptr), "PetscBarrier");
  std::ofstream("/proc/self/clear_refs") << "5";  // the peak from here on
  const double before_mb = status_mb("VmRSS");
  const auto start = std::chrono::steady_clock::now();
  MeshPiece piece;  // kerf's route leaves it, DMPlex's its DM: both held until every figure is read
  Division division = route == "kerf" ? kerf_route(mpi, std::move(whole), piece) : dmplex_route(std::move(whole));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<double> mine{seconds, before_mb, status_mb("VmRSS"), status_mb("VmHWM"), division.own_cells,
                                 division.ghost_cells};
  const auto every = mpi.from_every_rank(mine);
  if (ranks.rank == 0)
    for (int r = 0; r < ranks.count; ++r)
      std::printf("%s rank %d: %.3f s, MB before %.1f after %.1f peak %.1f, cells own %.0f ghost %.0f of %.0f\n",
                  route.c_str(), r, every[r][0], every[r][1], every[r][2], every[r][3], every[r][4], every[r][5],
                  total_cells);
  if (division.dm) check_petsc(DMDestroy(&division.dm), "DMDestroy");
  return 0;
}
