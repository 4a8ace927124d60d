#pragma once
// A run of a scene stepped by its caller, one time step at a time (a load
// increment in a static run): `kerf run` steps it to the end (run_scene), a
// simulator steps it from its own loop and reads the state between steps,
// as SOFA's animate or a haptic loop does. It writes what `kerf run` writes,
// as it goes: summary.json (status "running" until finish(), "error" when a
// call fails), probes.csv and the ParaView series.
//
// Under mpirun every rank opens the same session and makes the same calls
// in the same order: the calls are collective.
//
// A session leaves the process's signals to its host. Within an
// InterruptScope (core/interrupt.h: `kerf run` holds one for the whole run,
// the Python module one for each call) Ctrl-C or SIGTERM stops the call at
// its next check with kerf::Interrupted, the summary saying so.
#include <memory>
#include <span>
#include <nlohmann/json.hpp>

#include "app/run_scene.h"
#include "core/types.h"
#include "discretization/body_snapshot.h"

namespace kerf {

class ContactTerm;

class Session {
 public:
  /// Opens a run of `scene`: refuses what it cannot run or fit (before any
  /// work), writes summary.json, builds the body, its system, stepper and
  /// probes, and writes the output of step 0.
  explicit Session(const Scene& scene, const RunOptions& options = {});
  /// An unfinished session is finished (its summary written), a failed one left as it failed.
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  /// One step of the scene's integrator, then the cuts brought up to the
  /// new time and the output the step is due (the last step's always).
  /// Throws when every step was taken, and after a failure.
  void step();
  /// Feeds cut `cut` (its index in the scene's `cuts`) the next vertices, as a
  /// blade moved by a person gives them: the next polyline vertex (2D), the
  /// next vertex pair of a strip (3D: the blade's two ends; m). They take
  /// the time the session has reached, and the end of the next step brings
  /// the body up to the pieces they complete: the same as a scene giving
  /// these vertices a time within that step. A cut declared with no vertices
  /// (`strip: []`) is fed only this way. Throws, the cut left as it was,
  /// when a new piece is degenerate or folds the cut, or when the new pieces
  /// lie wholly outside the body's box (a blade moved off it).
  void extend_cut(Index cut, std::span<const Vec3> vertices);
  /// A hand on contact sphere `sphere` (its index in the scene's `contact`;
  /// dynamic runs), from the next step on: a displacement-driven sphere's
  /// centre moved to `displacement` (m) from its scene position (a haptic
  /// device's tool), a force-driven one pushed with `force` (N). Refused, the
  /// sphere as it was, where it would leave the surface sampled for it along
  /// its scene path (contact_term.h).
  void move_sphere(Index sphere, const Vec3& displacement);
  void push_sphere(Index sphere, const Vec3& force);
  /// The scene's body force and boundary loads (tractions, pressures) times
  /// `factor` from the next step on (dynamic runs; 1 at the start): an organ
  /// turned over, a retractor's pull let go.
  void scale_loads(double factor);
  /// Every step the scene asks for taken (solve.duration / solve.dt; static: solve.load_steps).
  bool done() const;
  int steps_taken() const;
  int step_count() const;
  /// A call failed (the summary says "error"): the session takes no more steps.
  bool failed() const;
  /// s (static: the load factor, 0 to 1).
  double time() const;
  double time_step() const;

  /// The displacement (m) and velocity (m/s) of every node, dofs_per_node()
  /// entries a node, after the last step (a run stepping its ranks' pieces
  /// gathers them).
  const Vector& displacement();
  const Vector& velocity();
  int dofs_per_node() const;
  Index node_count() const;
  /// The scene's probes now, as summary.json's `probes` holds them.
  nlohmann::ordered_json probes();
  /// The force (N) contact sphere `sphere` (its index in the scene's
  /// `contact`) exerts on the body now: what a haptic device renders. Cheaper
  /// than probes(): one sum over the sphere's contact points.
  Vec3 contact_force(Index sphere);
  /// The body now as ParaView gets it (reference points, cells, displacement
  /// and stress fields): what a viewer draws. A FEM body split by a cut has
  /// new cells and nodes after the step that split it.
  BodySnapshot snapshot();

  /// Ends the run where it stands: the last state written if it was not,
  /// summary.json with status "ok" and the run's figures. A session finishes once.
  RunOutcome finish();

 private:
  /// Throws when the pieces `vertices` add to cut `cut` lie wholly outside the body's box.
  void refuse_a_blade_outside(Index cut, std::span<const Vec3> vertices) const;
  /// The contact term, after checking that the session can take a hand on sphere `sphere` (`what`: the call).
  ContactTerm& sphere_in_hand(Index sphere, const char* what);
  struct Run;
  std::unique_ptr<Run> run_;
};

}  // namespace kerf
