// Stability study: where each method's explicit steps stop being stable,
// what long undamped runs do to the energy, what nodal integration does
// without its stabilisation, what a long zigzag cut does to the MLS weights
// under the Enrichment Grid and under the multiplicative rule, and which
// elements lock when the tissue is nearly incompressible. Every part ends as
// numbers in stability.json and stability.csv.
//
//   kerf study stability [--quick] [--out DIR]
//
// 1. Critical step. A 5 x 1 x 1 cm cantilever of firm tissue (E = 30 kPa, linear)
//    sags under gravity applied at once, undamped, with central differences
//    (fem tet4 and tet10, nodal integration three ways; EFG, this project's
//    implicit method, takes part in parts 3 and 5 only).
//    The run's own estimate (2 / omega_max by Lanczos at rest) is the unit;
//    dt = f x estimate is bisected for the largest f whose run stays bounded
//    (kinetic + strain energy within twice the work of gravity).
// 2. Energy drift. The same cantilever, corotational, undamped, at 0.9 of
//    the estimate for many steps: max |K + U - W| / max U.
// 3. Zero-energy modes. The spectrum of K x = omega^2 M x (consistent mass)
//    of a free 2 x 1 x 1 cm block:
//    the modes after the 6 rigid ones whose omega^2 is below a tenth of the
//    lowest deformation mode of tet4 on the same block (spurious, near-zero
//    energy modes: no physical mode of the block is that soft).
// 4. A 200-piece zigzag cut (2D plate, nodal integration): each rule's
//    moment-matrix conditioning (all nodes, enriched nodes, nodes at the
//    tips) and critical step with the whole cut present, and a progressive
//    run (one piece every 8 steps) whose kinetic + strain energy is set
//    against the work of the load.
// 5. Locking. The cantilever under an end load, nu = 0.3 and 0.49, static:
//    tip deflection against fem tet10 at half the size.
// Claims (each what results/stability.md says in words; every planned run must
// finish, but a bisection's probe may diverge, which is what "unstable" means
// here: the state NaN or the energy past twice the load's work): the estimate is safe (stable at f = 1)
// and tight (unstable within the bisection's resolution) for every method, and
// the FEM element bound lies below it; no method's undamped energy drifts
// beyond 1e-4 of its strain energy; the stabilised methods have no spurious
// zero-energy mode and nodal integration without stabilisation has some; the
// multiplicative rule conditions the zigzag's enriched nodes 100 times worse
// than the grid, shortens the critical step and, growing, gains energy where
// every other rule creates none; tet4 keeps less than 80% of its deflection at
// nu = 0.49 and every other method more than 95%.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/run_report.h"
#include "discretization/body_factory.h"
#include "solvers/sparse_assembly.h"
#include "studies/study_scenes.h"
#include "studies/study_support.h"

namespace kerf {
namespace {

// Firm tissue: the cantilever sags a few per cent of its length, so the
// estimate at rest still holds in the corotational runs.
constexpr double young = 3.0e4, density = 1000.0;
constexpr double spacing = 0.0025;  // m: nodes and element size of the cantilever

/// One variant of a method: what it needs under `discretization`.
struct Variant {
  std::string label;
  Method method;
  ElementType element = ElementType::tet4;
  NodalGradient gradient = NodalGradient::direct;
  bool stabilized = true;
  bool explicit_steps = true;  // run with central differences here (EFG is this project's implicit method)
};

const std::vector<Variant>& all_methods() {
  static const std::vector<Variant> methods{
      {"fem_tet4", Method::fem},
      {"fem_tet10", Method::fem, ElementType::tet10},
      {"efg", Method::efg, ElementType::tet4, NodalGradient::direct, true, false},
      {"nodal", Method::nodal},
      {"nodal_smoothed", Method::nodal, ElementType::tet4, NodalGradient::smoothed},
      {"nodal_unstabilized", Method::nodal, ElementType::tet4, NodalGradient::direct, false},
  };
  return methods;
}

DiscretizationOptions discretization(const Variant& m, double h) {
  DiscretizationOptions d;
  d.method = m.method;
  d.fem.element = m.element;
  d.fem.size = h;
  d.meshless.spacing = h;
  d.meshless.gradient = m.gradient;
  d.meshless.stabilization = m.stabilized ? NodalStabilization::hourglass : NodalStabilization::none;
  return d;
}

/// The cantilever (5 x 1 x 1 cm, clamped at x = 0) of `m` at `h`, loads and solve left to the caller.
Scene cantilever(const Variant& m, MaterialModel model, double poisson, double h) {
  using namespace study_scene;
  Scene scene = box_body("stability", Vec3(0, 0, 0), Vec3(0.05, 0.01, 0.01));
  scene.material = material(model, young, poisson, density);
  scene.discretization = discretization(m, h);
  scene.boundary = {held(0, 0.0)};
  return scene;
}

/// The cantilever sagging under gravity, undamped, by central differences
/// (`steps` of `dt`, unstable steps allowed), with an energy probe.
Scene sagging_cantilever(const Variant& m, MaterialModel model, double dt, int steps) {
  Scene scene = cantilever(m, model, 0.3, spacing);
  scene.gravity = Vec3(0, 0, -9.81);
  scene.solve = study_scene::explicit_unstable_steps(dt, steps);
  scene.output.probes = {study_scene::energy_probe("energy")};
  return scene;
}

/// Energy figures of a dynamic run with an energy probe.
struct EnergyHistory {
  double max_mechanical = 0.0;  // max of kinetic + strain (J)
  double max_work = 0.0;        // max |work of the loads| (J)
  double max_strain = 0.0;      // J
  double max_imbalance = 0.0;   // max |kinetic + strain - work| (J)
  bool finite = true;
};

EnergyHistory energy_history(const std::string& run_dir) {
  const ProbeHistory h = read_probe_history(run_dir);
  EnergyHistory e;
  const auto& kinetic = h.at("energy_kinetic");
  const auto& strain = h.at("energy_strain");
  const auto& work = h.at("energy_external_work");
  for (std::size_t i = 0; i < kinetic.size(); ++i) {
    const double mechanical = kinetic[i] + strain[i];
    e.finite &= std::isfinite(mechanical) && std::isfinite(work[i]);
    e.max_mechanical = std::max(e.max_mechanical, mechanical);
    e.max_work = std::max(e.max_work, std::abs(work[i]));
    e.max_strain = std::max(e.max_strain, strain[i]);
    e.max_imbalance = std::max(e.max_imbalance, std::abs(mechanical - work[i]));
  }
  return e;
}

/// Bounded: no energy beyond twice what gravity did (undamped: K + U = W).
bool bounded(const EnergyHistory& e) { return e.finite && e.max_mechanical <= 2.0 * e.max_work + 1e-300; }

/// The eigenvalues of K x = omega^2 M x (1/s^2, ascending) of a free body,
/// with its consistent mass (a mode that hardly moves the field then has
/// little mass too, so only modes soft in energy show up as soft).
Eigen::VectorXd free_spectrum(const Scene& scene) {
  RunReport report;
  const std::unique_ptr<DiscreteBody> body = make_body(scene, report);
  SparseMatrix K = build_pattern(*body), M = build_pattern(*body);
  body->tangent(Vector::Zero(body->dof_count()), add_into(K), nullptr);
  body->consistent_mass(add_into(M));
  const Eigen::MatrixXd k = K, m = M;
  return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(k, m, Eigen::EigenvaluesOnly).eigenvalues();
}

/// A rule of the zigzag part: an enrichment and, for the grid, its lookup.
struct Rule {
  std::string label;
  Enrichment enrichment;
  GridLookup lookup = GridLookup::exact;
};

/// The zigzag: 200 pieces from the plate's left edge to its centre, +-0.1 mm
/// about y = 0.5 mm (between node rows), one piece every 4e-5 s when growing.
Scene zigzag_scene(const Rule& rule, bool growing, double dt, int steps) {
  using namespace study_scene;
  const int pieces = 200;
  Cut cut;
  for (int k = 0; k <= pieces; ++k) {
    const double x = -0.0205 + 0.0205 * k / pieces;
    const double y = 0.0005 + (k == 0 ? 0.0 : (k % 2 ? 1e-4 : -1e-4));
    cut.vertices.push_back(Vec3(as_written(x), as_written(y), 0));  // its end on the node column x = 0
    if (growing) cut.times.push_back(k < 2 ? 0.0 : (k - 1) * 4e-5);
  }
  if (!growing) cut.times.assign(cut.vertices.size(), 0.0);
  cut.enrichment = rule.enrichment;
  cut.grid_lookup = rule.lookup;
  Scene scene = box_body("zigzag", Vec3(-0.02, -0.02, 0), Vec3(0.02, 0.02, 0));
  scene.dimension = 2;
  scene.discretization.fem.element = ElementType::tri3;
  scene.material = material(MaterialModel::linear, 1.0e6, 0.3, 1000.0, 200.0);
  scene.discretization.method = Method::nodal;
  scene.discretization.meshless.spacing = 0.001;
  scene.discretization.meshless.support = 2.8;
  BoundaryCondition pulled;
  pulled.select = plane(1, 0.02);
  pulled.traction = Vec3(0, 1000, 0);
  scene.boundary = {held(1, -0.02, {true, true, false}), pulled};
  scene.cuts = {cut};
  scene.solve = study_scene::explicit_unstable_steps(dt, steps);
  scene.output.probes = {energy_probe("energy")};
  return scene;
}

/// What the five experiments share: the study's runner and tables, the
/// estimates part 1 finds (part 2 runs at 0.9 of them), and the claims, checked
/// after the results are written so that a failed claim still leaves them.
struct Experiments {
  bool quick;
  StudyRunner& runner;
  CsvTable& table;
  std::map<std::string, double> estimate;  // s, per explicit method
  std::vector<std::pair<bool, std::string>> claims;

  void number(const std::string& part, const std::string& item, const std::string& quantity, double value,
              const std::string& unit) {
    table.row({part, item, quantity, std::isfinite(value) ? Json(value) : Json(), unit});
  }
  void claim(bool holds, const std::string& what) { claims.emplace_back(holds, what); }
  /// A planned run that must finish (bisection probes may diverge by design).
  bool ran(const RunRecord& run, const std::string& label) {
    claim(run.ok(), label + " ran (" + (run.ok() ? std::string("ok") : run.error) + ")");
    return run.ok();
  }
};

int bisections(bool quick) { return quick ? 3 : 7; }

/// 1. The critical step: the run's estimate, then bisection on dt / estimate.
Json critical_step(Experiments& x) {
  const int probe_steps = x.quick ? 600 : 2000;  // steps of each stability probe
  Json critical = Json::object();
  for (const Variant& m : all_methods()) {
    if (!m.explicit_steps) continue;
    auto probe = [&](const std::string& label, double dt, int steps) {
      return x.runner.run(label, sagging_cantilever(m, MaterialModel::linear, dt, steps));
    };
    const RunRecord first = probe("critical_" + m.label + "_estimate", 1e-7, 1);
    x.ran(first, "critical_" + m.label + "_estimate");
    const SolverCounters& counters = first.report.solver;
    const double estimate = x.estimate[m.label] = counters.critical_dt_s.value_or(NAN);
    const double element_bound = counters.critical_dt_element_bound_s.value_or(NAN);
    // Unstable means the run diverged: its energy unbounded, or the state NaN
    // (summary.json's "diverged"). Any other failure is not a finding of
    // this study: it fails the study, naming the run.
    auto stable = [&](double f) {
      std::ostringstream label;
      label << "critical_" << m.label << "_f" << f;
      const RunRecord s = probe(label.str(), f * estimate, probe_steps);
      if (s.diverged) return false;
      if (!x.ran(s, label.str())) return false;
      return bounded(energy_history(x.runner.out_dir() + "/runs/" + label.str()));
    };
    const bool at_estimate = stable(1.0);
    double lo = at_estimate ? 1.0 : 0.5, hi = at_estimate ? 2.0 : 1.0;
    // A limit outside [0.5, 2] leaves the far end unknown (null in the results).
    if (at_estimate && stable(hi)) lo = hi, hi = NAN;
    if (!at_estimate && !stable(lo)) hi = lo, lo = NAN;
    for (int k = 0; k < bisections(x.quick) && std::isfinite(lo) && std::isfinite(hi); ++k) {
      const double mid = 0.5 * (lo + hi);
      (stable(mid) ? lo : hi) = mid;
    }
    critical[m.label] = {{"estimate_s", estimate},
                         {"element_bound_s", std::isfinite(element_bound) ? Json(element_bound) : Json()},
                         {"stable_at_estimate", at_estimate},
                         {"largest_stable_factor", std::isfinite(lo) ? Json(lo) : Json()},
                         {"first_unstable_factor", std::isfinite(hi) ? Json(hi) : Json()}};
    x.number("critical_step", m.label, "estimate", estimate, "s");
    x.number("critical_step", m.label, "element_bound", element_bound, "s");
    x.number("critical_step", m.label, "largest_stable_over_estimate", lo, "1");
    x.number("critical_step", m.label, "first_unstable_over_estimate", hi, "1");
    x.runner.say(m.label + ": estimate " + std::to_string(estimate) + " s, stable up to " + std::to_string(lo) +
                 " x, unstable at " + std::to_string(hi) + " x");
    // Safe, and as tight as the bisection can tell (results/stability.md: within 0.8%).
    const double resolution = std::ldexp(1.0, -bisections(x.quick));
    x.claim(at_estimate, m.label + " runs stably at its own critical-step estimate");
    x.claim(hi <= 1.0 + resolution * (1.0 + 1e-12),
            m.label + " is unstable within " + std::to_string(resolution) + " of its estimate (first unstable at " +
                std::to_string(hi) + " x)");
    if (std::isfinite(element_bound))
      x.claim(element_bound < estimate, m.label + "'s element bound is below the Lanczos estimate");
  }
  return critical;
}

/// 2. Long undamped runs at 0.9 of the estimate, corotational.
Json energy_drift(Experiments& x) {
  const int steps = x.quick ? 1000 : 20000;
  Json drift = Json::object();
  for (const Variant& m : all_methods()) {
    if (!m.explicit_steps) continue;
    const std::string label = "drift_" + m.label;
    const double dt = 0.9 * x.estimate[m.label];
    const RunRecord s = x.runner.run(label, sagging_cantilever(m, MaterialModel::corotational, dt, steps));
    const bool ok = x.ran(s, label);
    const EnergyHistory e = energy_history(x.runner.out_dir() + "/runs/" + label);
    const double relative = ok && e.finite && e.max_strain > 0.0 ? e.max_imbalance / e.max_strain : NAN;
    drift[m.label] = {{"status", s.ok() ? "ok" : "error"}, {"dt_s", dt}, {"steps", steps},
                      {"duration_s", dt * steps}, {"max_energy_error_over_max_strain", std::isfinite(relative) ? Json(relative) : Json()},
                      {"max_mechanical_over_max_work", e.max_work > 0 ? Json(e.max_mechanical / e.max_work) : Json()}};
    x.number("energy_drift", m.label, "max_energy_error_over_max_strain", relative, "1");
    x.runner.say(m.label + ": undamped energy error " + std::to_string(100 * relative) + " % of the strain energy over " +
                 std::to_string(steps) + " steps");
    // results/stability.md: no drift (2e-6 to 6e-6 measured over 20 000 steps).
    x.claim(relative < 1e-4, m.label + " keeps the undamped energy within 1e-4 of the strain energy (it is " +
                                 std::to_string(relative) + ")");
  }
  return drift;
}

/// 3. Near-zero-energy modes of a free block, against tet4's softest deformation mode.
Json zero_energy_modes(Experiments& x) {
  Json modes = Json::object();
  double softest_physical = NAN;  // tet4's 7th eigenvalue (1/s^2)
  for (const Variant& m : all_methods()) {
    if (m.element == ElementType::tet10) continue;
    Scene block = study_scene::box_body("modes", Vec3(0, 0, 0), Vec3(0.02, 0.01, 0.01));
    block.material = study_scene::material(MaterialModel::linear, young, 0.3, density);
    block.discretization = discretization(m, spacing);
    // Its file is kept beside the runs' scenes (a spectrum, not a run).
    const Eigen::VectorXd omega2 = free_spectrum(x.runner.write_scene("modes_" + m.label, block));
    if (m.label == "fem_tet4") softest_physical = omega2[6];
    int spurious = 0;
    for (Index i = 6; i < omega2.size(); ++i) spurious += omega2[i] < 0.1 * softest_physical;
    modes[m.label] = {{"spurious_soft_modes", spurious}, {"lowest_deformation_omega2", omega2[6]},
                      {"largest_omega2", omega2[omega2.size() - 1]}};
    x.number("zero_energy_modes", m.label, "modes_below_a_tenth_of_tet4_softest", spurious, "1");
    x.number("zero_energy_modes", m.label, "lowest_deformation_omega2", omega2[6], "1/s^2");
    x.runner.say(m.label + ": " + std::to_string(spurious) + " modes below a tenth of tet4's softest (omega^2 " +
                 std::to_string(softest_physical) + " 1/s^2); its softest " + std::to_string(omega2[6]));
    if (m.stabilized)
      x.claim(spurious == 0, m.label + " has no spurious near-zero-energy mode (it has " + std::to_string(spurious) + ")");
    else
      x.claim(spurious > 0, m.label + " shows spurious near-zero-energy modes without its stabilisation");
  }
  return modes;
}

/// 4. The 200-piece zigzag: whole cut at once, then growing.
Json zigzag_cut(Experiments& x, const std::vector<Rule>& rules) {
  Json zigzag = Json::object();
  const double growing_dt = 5e-6;
  for (const Rule& r : rules) {
    const std::string& rule = r.label;
    const RunRecord whole = x.runner.run("zigzag_whole_" + rule, zigzag_scene(r, false, 1e-7, 1));
    x.ran(whole, "zigzag_whole_" + rule);
    const std::string label = "zigzag_growing_" + rule;
    const RunRecord growing = x.runner.run(label, zigzag_scene(r, true, growing_dt, 2000));
    const bool ok = x.ran(growing, label);
    const EnergyHistory e = energy_history(x.runner.out_dir() + "/runs/" + label);
    const bool gain_known = ok && e.finite && e.max_work > 0;
    Json z = {{"critical_dt_s", whole.report.solver.critical_dt_s.value_or(NAN)},
              {"condition_median", whole.extra("mls_condition_median")},
              {"condition_near_cut_max", whole.extra("mls_condition_near_cut_max")},
              {"condition_near_tip_max", whole.extra("mls_condition_near_tip_max")},
              {"growing_status", growing.ok() ? "ok" : "error"},
              {"growing_dt_s", growing_dt},
              {"growing_mechanical_over_work", gain_known ? Json(e.max_mechanical / e.max_work) : Json()},
              {"cut_update_ms_median", growing.ok() ? Json(growing.cut_update_ms.median_ms) : Json()}};
    for (const auto& [key, value] : z.items())
      if (value.is_number()) x.number("zigzag", rule, key, value.get<double>(), "");
    zigzag[rule] = z;
    x.runner.say(rule + ": near-cut condition " + z["condition_near_cut_max"].dump() + ", critical dt " +
                 z["critical_dt_s"].dump() + " s, growing run K+U over work " + z["growing_mechanical_over_work"].dump());
    if (r.enrichment != Enrichment::multiplicative)
      x.claim(gain_known && e.max_mechanical <= e.max_work,
              "the growing zigzag cut with " + rule + " creates no energy (kinetic + strain <= work of the load; it is " +
                  z["growing_mechanical_over_work"].dump() + ")");
  }
  auto figure = [&](const std::string& rule, const char* key) {
    return zigzag[rule][key].is_number() ? zigzag[rule][key].get<double>() : NAN;
  };
  x.claim(figure("multiplicative", "condition_near_cut_max") > 100.0 * figure("grid", "condition_near_cut_max"),
          "the multiplicative rule conditions the zigzag's enriched nodes 100 times worse than the grid");
  x.claim(figure("multiplicative", "critical_dt_s") < figure("grid", "critical_dt_s"),
          "the multiplicative rule shortens the critical step of the zigzag-cut plate");
  x.claim(figure("multiplicative", "growing_mechanical_over_work") > 1.0,
          "the growing zigzag cut gains energy with the multiplicative rule (kinetic + strain over work " +
              zigzag["multiplicative"]["growing_mechanical_over_work"].dump() + ")");
  return zigzag;
}

/// 5. Locking: tip deflection under an end load against tet10 at half the size.
Json locking(Experiments& x) {
  Json out = Json::object();
  BoundaryCondition end_load;
  end_load.select = study_scene::plane(0, 0.05);
  end_load.traction = Vec3(0, 0, -10);
  const Variant reference{"fem_tet10_fine", Method::fem, ElementType::tet10};
  for (const char* nu : {"0.3", "0.49"}) {
    auto deflection = [&](const Variant& m, double h) {
      const std::string label = "locking_" + m.label + "_nu" + nu;
      Scene scene = cantilever(m, MaterialModel::linear, std::stod(nu), h);
      scene.boundary.push_back(end_load);
      scene.output.probes = {study_scene::displacement_probe("tip", Vec3(0.05, 0.005, 0.005))};
      const RunRecord s = x.runner.run(label, scene);
      return x.ran(s, label) ? -s.probe("tip", 2) : NAN;
    };
    const double exact = deflection(reference, x.quick ? spacing : spacing / 2);
    out["reference_deflection_m_nu" + std::string(nu)] = exact;
    for (const Variant& m : all_methods()) {
      const double ratio = deflection(m, spacing) / exact;
      out[m.label]["deflection_over_reference_nu" + std::string(nu)] = std::isfinite(ratio) ? Json(ratio) : Json();
      x.number("locking", m.label, "deflection_over_reference_nu" + std::string(nu), ratio, "1");
    }
  }
  // results/stability.md: tet4 loses 38% of its deflection; tet10 and the meshless methods 1-3%.
  for (const Variant& m : all_methods()) {
    const Json &stiff = out[m.label]["deflection_over_reference_nu0.49"], &soft = out[m.label]["deflection_over_reference_nu0.3"];
    const double kept = stiff.is_number() && soft.is_number() ? stiff.get<double>() / soft.get<double>() : NAN;
    if (m.label == "fem_tet4")
      x.claim(kept < 0.8, "tet4 locks: it keeps less than 80% of its deflection at nu = 0.49 (it keeps " +
                              std::to_string(kept) + ")");
    else
      x.claim(kept > 0.95, m.label + " does not lock: it keeps more than 95% of its deflection at nu = 0.49 (it keeps " +
                               std::to_string(kept) + ")");
  }
  return out;
}

Json headline(const Json& result) {
  const Json &critical = result["critical_step"], &locking = result["locking"], &zigzag = result["zigzag"];
  Json out = Json::array();
  for (const auto& [label, c] : critical.items())
    if (c["largest_stable_factor"].is_number())
      out.push_back({{"what", label + " largest stable dt over the Lanczos estimate"},
                     {"value", c["largest_stable_factor"]}, {"unit", "x"}});
  out.push_back({{"what", "nodal (stabilised) undamped energy error over max strain energy"},
                 {"value", result["energy_drift"]["nodal"]["max_energy_error_over_max_strain"]}, {"unit", "1"}});
  out.push_back({{"what", "nodal without stabilisation: spurious near-zero-energy modes (2 x 1 x 1 cm block)"},
                 {"value", result["zero_energy_modes"]["nodal_unstabilized"]["spurious_soft_modes"]}, {"unit", ""}});
  out.push_back({{"what", "zigzag 200 pieces, enriched-node condition number, grid"},
                 {"value", zigzag["grid"]["condition_near_cut_max"]}, {"unit", ""}});
  out.push_back({{"what", "zigzag 200 pieces, enriched-node condition number, multiplicative"},
                 {"value", zigzag["multiplicative"]["condition_near_cut_max"]}, {"unit", ""}});
  for (const char* element : {"tet4", "tet10"})
    out.push_back({{"what", std::string(element) + " tip deflection over reference at nu = 0.49"},
                   {"value", locking[std::string("fem_") + element]["deflection_over_reference_nu0.49"]}, {"unit", "1"}});
  return out;
}

}  // namespace

void stability_study(const StudyOptions& options) {
  const bool quick = options.quick;
  const Rule grid{"grid", Enrichment::grid}, interpolated{"grid-interpolated", Enrichment::grid, GridLookup::interpolated},
      multiplicative{"multiplicative", Enrichment::multiplicative}, visibility{"visibility", Enrichment::visibility},
      diffraction{"diffraction", Enrichment::diffraction};
  const std::vector<Rule> rules = quick ? std::vector<Rule>{grid, multiplicative}
                                        : std::vector<Rule>{grid, interpolated, multiplicative, visibility, diffraction};
  const int methods = static_cast<int>(all_methods().size());
  const int explicit_methods = static_cast<int>(
      std::count_if(all_methods().begin(), all_methods().end(), [](const Variant& m) { return m.explicit_steps; }));
  const int planned =
      explicit_methods * (bisections(quick) + 4) + 2 * static_cast<int>(rules.size()) + 2 * (methods + 1);
  StudyRunner runner("stability", options, planned);
  CsvTable table(runner.out_dir() + "/stability.csv", {"part", "case", "quantity", "value", "unit"});
  Experiments x{quick, runner, table, {}, {}};

  StudyResult result("stability", quick, {"stability.png"});
  result["critical_step"] = critical_step(x);
  result["energy_drift"] = energy_drift(x);
  result["zero_energy_modes"] = zero_energy_modes(x);
  result["zigzag"] = zigzag_cut(x, rules);
  result["locking"] = locking(x);
  result.set_headline(headline(result.json()));
  result.write(runner.out_dir());
  plot("stability", runner.out_dir());
  for (const auto& [holds, what] : x.claims) check_claim(holds, what);
}

}  // namespace kerf
