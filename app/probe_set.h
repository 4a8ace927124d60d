#pragma once
// The scene's probes resolved against a discretized body: what each one reads
// from the solver state, as CSV columns and as the summary's final values.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "solvers/mechanical_system.h"
#include "solvers/stepper.h"

namespace kerf {

/// Energies at one instant (J; 2D: J per metre of thickness).
struct EnergyState {
  double kinetic = 0.0;
  double strain = 0.0;
  double external_work = 0.0;  // work of the external loads since t = 0
  double total() const { return kinetic + strain - external_work; }
};

class ProbeSet {
 public:
  /// Throws, naming the probe's scene line, when a point lies outside the body.
  ProbeSet(const Scene& scene, const MechanicalSystem& mechanics);

  std::vector<std::string> columns() const;  // without the leading "time"
  bool needs_reaction() const;
  bool needs_energy() const;
  /// The dofs of u the probes read, ascending, when they read displacements
  /// alone; nullopt when they need the whole state (a reaction, an energy, a
  /// contact reading).
  const std::optional<std::vector<Index>>& displacement_dofs_read() const { return displacement_dofs_; }
  /// `reaction` may be empty when no probe needs it.
  std::vector<double> values(const SolverState& state, const Vector& reaction, const EnergyState& energy) const;
  nlohmann::ordered_json final_values(const SolverState& state, const Vector& reaction, const EnergyState& energy) const;

 private:
  struct Resolved {
    Probe probe;
    PointInterpolation interpolation;  // displacement
    std::vector<Index> nodes;          // reaction
  };
  std::vector<double> probe_values(const Resolved& r, const SolverState& state, const Vector& reaction,
                                   const EnergyState& energy) const;
  const MechanicalSystem& mechanics_;
  const WeakConstraints* weak_;  // the body's, or null
  /// displacement_dofs_read's list, made once.
  std::optional<std::vector<Index>> displacement_dofs() const;
  std::vector<Resolved> probes_;
  int dim_;
  std::optional<std::vector<Index>> displacement_dofs_;
};

}  // namespace kerf
