#pragma once
// Static, implicit Euler and Newmark (average acceleration) steppers: each
// solves r(u) = 0 for the new displacement with Newton on an ImplicitSystem.
#include <memory>

#include "solvers/stepper.h"

namespace kerf {

std::unique_ptr<Stepper> make_static_stepper(MechanicalSystem& mechanics, const SolveOptions& solve,
                                             RunReport& report);
std::unique_ptr<Stepper> make_implicit_euler_stepper(MechanicalSystem& mechanics, const StepperSettings& settings,
                                                     RunReport& report);
std::unique_ptr<Stepper> make_newmark_stepper(MechanicalSystem& mechanics, const StepperSettings& settings,
                                              RunReport& report);

}  // namespace kerf
