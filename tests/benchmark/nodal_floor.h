#pragma once
// The floor under nodal integration's explicit step: the least work one
// internal-force pass must do on kerf's own tables, written bare (no
// framework, no material object: Hooke's law inline) and in the vector form
// kerf's kernel uses (4-wide vectors of doubles, u and forces 4 to a node,
// AVX2 + FMA): for each node I, F_I from a gather of its neighbours'
// displacements and gradients, the stress, and a scatter of V_I P grad phi_K
// into each thread's own force vector, summed at the end. With the
// stabilisation, also the pair term k_IJ e_IJ with e_IJ = u_J - u_I -
// (F_I - 1) X_IJ, the lever X_IJ taken from the positions (one k a pair read),
// and its reaction through F_I.
#include <span>
#include <vector>

#include "core/types.h"

namespace kerf::bench {

struct NodalFloorData {
  std::span<const Index> start, index;  // neighbour lists (CSR)
  std::span<const double> gradient;     // 3 per slot
  std::span<const double> stiffness;    // k_IJ per slot (stabilised floor only)
  const double* position4 = nullptr;    // 4 per node, 32-byte aligned
  std::span<const double> volume;
  double lambda = 0.0, mu = 0.0;
};

/// Whether this CPU runs the floor (AVX2 and FMA).
bool nodal_floor_supported();

/// f = f_int(u) (3D; u4 and f4 4 to a node, 32-byte aligned), `scratch` holding
/// one force vector per thread (4 to a node, aligned).
void nodal_floor_force(const NodalFloorData& data, bool stabilized, const double* u4, double* f4,
                       std::vector<double>& scratch);

}  // namespace kerf::bench
