#pragma once
// What a run will need, from the scene alone, before any meshing: the
// counts (mesh cells and nodes, the body's nodes and dofs, quadrature points,
// MLS neighbours, the stiffness matrix's and its factor's nonzeros, the
// Enrichment Grids' points), the output per step and the peak memory. A run
// that cannot fit in the machine's memory is refused with the key that sets
// its size, the estimate and the limit (--force runs it anyway).
//
// The constants are fitted to measured runs (tests/regression/
// test_resource_estimate.cpp holds the estimate to the measured counts and
// peak memory); they are meant to be right within a factor of about two, which
// is what telling a run that fits from one a thousand times too large needs.
#include <nlohmann/json.hpp>
#include <string>

#include "core/rank_share.h"
#include "problem/scene.h"

namespace kerf {

struct ResourceEstimate {
  double mesh_cells = 0.0, mesh_nodes = 0.0;  // the mesh: FEM's, or a meshless body's background
  bool gmsh_meshes = false;                   // gmsh makes it, or a file holds it (not a lattice's own cells)
  double nodes = 0.0, dofs = 0.0;             // the body's
  double points = 0.0;                        // quadrature points (a nodal body's are its nodes)
  double neighbors = 0.0;                     // nodes each meshless point sees
  double nonzeros = 0.0;                      // the stiffness matrix's, when an implicit run assembles it
  double factor_nonzeros = 0.0;               // its Cholesky factor's, with a direct solver
  double grid_points = 0.0;                   // the Enrichment Grids'
  double output_mb_per_step = 0.0, output_mb = 0.0;  // the ParaView series
  double memory_mb = 0.0;                     // peak resident memory of the whole run on one process
  int ranks = 1;                              // the MPI ranks it was estimated for
  double memory_mb_per_rank = 0.0;            // the largest rank's peak among them (memory_mb on one)
  std::string size_key;                       // the key whose value sets the resolution
  double size = 0.0;                          // and that value
};

/// For a run on `ranks` MPI ranks (the per-rank memory then follows how they share it).
ResourceEstimate estimate_resources(const Scene& scene, int ranks = 1);

/// The estimate as `kerf check` prints it, a line per figure.
std::string describe(const ResourceEstimate& estimate);

/// The estimate in summary.json ("estimate"), beside the measured counts and memory.
nlohmann::ordered_json estimate_to_json(const ResourceEstimate& estimate);

/// MemAvailable of /proc/meminfo (MB): what a run may take without swapping.
double available_memory_mb();

/// What one process of the run may take: this machine's available memory
/// over the ranks it runs under mpirun, or the environment's
/// KERF_MEMORY_LIMIT_MB (a cap on each process) when smaller.
double memory_limit_mb(const RankShare& ranks);

/// Throws naming output.vtk when the series would not fit on the disk holding `directory`.
void refuse_output_that_cannot_fit(const Scene& scene, const ResourceEstimate& estimate, const std::string& directory);

/// Throws naming the scene's file, the key and value that set the size, the
/// estimated memory of the largest rank, the limit a process, and --force.
void refuse_what_cannot_fit(const Scene& scene, const ResourceEstimate& estimate, double limit_mb);

}  // namespace kerf
