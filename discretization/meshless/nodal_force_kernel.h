#pragma once
// The internal-force pass of 3D nodal integration, the explicit step's whole
// cost, written for the vector unit: each node's gather (grad u and the
// stabilisation's lever sums) and scatter (V P grad phi and the pair forces)
// run on 4-wide vectors of doubles (x, y, z, padding) with fused
// multiply-adds, u and the per-thread forces held 4 to a node so every access
// is one aligned load or store. Compiled twice, for AVX2 + FMA and for the
// baseline x86-64, and chosen once at run time, so the binary runs anywhere.
// With VCI each neighbour's force is tested with grad psi_K + xi_K.
// The arithmetic is that of NodalBody (see nodal_body.h), reassociated:
//   e_IK = k_IK (u_K - H x_K - (u_I - H x_I)),  H = grad u at x_I.
#include <span>
#include <vector>

#include "core/types.h"
#include "problem/material.h"

namespace kerf {

/// Views of a 3D nodal body's tables (nothing owned).
struct NodalForceTables {
  Index nodes = 0;
  Index pass_begin = 0, pass_end = 0;    // the nodes whose terms the pass adds (an MPI rank's own)
  std::span<const Index> touched;        // the nodes those terms reach, ascending (empty: every node)
  const Index* start = nullptr;          // neighbour lists (CSR), N + 1
  const Index* index = nullptr;
  Index slots = 0;
  const double* gradient = nullptr;      // 3 per slot
  const double* volume = nullptr;        // per node
  const double* position4 = nullptr;     // 4 per node (x, y, z, 0), 32-byte aligned
  const double* stiffness = nullptr;     // k per slot; null without the stabilisation
  const double* lever_sum = nullptr;     // 3 per node
  const double* lever_moment = nullptr;  // 9 per node, row-major
  const double* test_offset = nullptr;   // VCI's ghat - grad psi, 3 per slot; null without
};

/// Buffers a pass reuses: u padded to 4 a node, each thread's force vector.
struct NodalForceScratch {
  std::vector<double> u4, forces4;
};

/// The first 32-byte aligned entry of `buffer`, which holds 4 spare doubles for it.
const double* aligned_32(const std::vector<double>& buffer);

/// Positions 4 to a node (x, y, z, 0), with the spare doubles aligned_32 needs.
std::vector<double> padded_positions(std::span<const Vec3> positions);

/// Which compiled form of the pass runs: the best this CPU has, or the
/// baseline x86-64 one (tests compare the two).
enum class VectorUnit { best, baseline };

/// f = f_int(u) (3 per node): the pass's nodes' terms, zero at nodes they do
/// not reach. Only the touched nodes' u is read, copied and summed: an MPI
/// rank's work outside the pass is the length of its piece, not of the whole.
void nodal_force_3d(const NodalForceTables& tables, const MaterialLaw& law, const Vector& u, Vector& f,
                    NodalForceScratch& scratch, VectorUnit unit = VectorUnit::best);

}  // namespace kerf
