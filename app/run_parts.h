#pragma once
// What a run holds while it steps: the body, its mechanical system (the body
// with its solver-side terms), the stepper on that system, and the probes
// resolved against it. Each refers to the one before: they are made, and
// replaced when a cut grows, in this order.
#include <memory>

#include "app/probe_set.h"
#include "discretization/discrete_body.h"
#include "solvers/mechanical_system.h"
#include "solvers/stepper.h"

namespace kerf {

struct RunParts {
  std::unique_ptr<DiscreteBody> body;
  std::unique_ptr<MechanicalSystem> mechanics;
  std::unique_ptr<Stepper> stepper;
  std::unique_ptr<ProbeSet> probes;
};

}  // namespace kerf
