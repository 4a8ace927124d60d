#pragma once
// Explicit central differences (velocity-Verlet form) with the lumped mass:
// no matrix, one internal-force evaluation per step.
#include <memory>

#include "solvers/stepper.h"

namespace kerf {

/// Stiffness-proportional damping beta lowers the stable step:
/// dt_crit = (2 / omega) (sqrt(1 + xi^2) - xi), xi = beta omega / 2.
double damped_critical_step(double undamped_step, double beta);

/// carried_mode: see make_stepper.
std::unique_ptr<Stepper> make_central_difference_stepper(MechanicalSystem& mechanics, const StepperSettings& settings,
                                                         RunReport& report, const Vector& carried_mode = {});

}  // namespace kerf
