#pragma once
// A safe central-difference step for any body from Gershgorin's theorem:
// omega_max^2 <= max_r sum_c |K_rc| / m_r for the stiffness at rest and the
// lumped mass (each |K_rc| bounded by the sum of the magnitudes of the blocks
// that add into it). Used where no element-by-element bound exists (meshless).
#include "discretization/discrete_body.h"

namespace kerf {

/// 2 / sqrt(Gershgorin bound of omega_max^2) (s).
double gershgorin_critical_step(const DiscreteBody& body);

}  // namespace kerf
