// FEM benchmarks (Google Benchmark): the implicit step of a corotational tet4
// block under gravity (the paper's SOFA FEM baseline took 195 ms a step), and
// stiffness assembly and CHOLMOD factorization at three sizes.
//   build/tests/kerf_benchmarks --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <omp.h>

#include <algorithm>
#include <vector>

#include "discretization/body_capabilities.h"
#include "discretization/body_factory.h"
#include "floor_report.h"
#include "problem/material.h"
#include "tet4_assembly_floor.h"
#include "problem/scene_reader.h"
#include "solvers/linear_solver.h"
#include "solvers/stepper.h"

namespace kerf {
namespace {

// Element sizes giving 1 848, 3 728 and 6 786 nodes on the 10 cm cube, and
// (level 3) 6 389: the node count of the SOFA block issue 40's step goal names.
const double sizes[] = {0.0085, 0.0065, 0.0052, 0.00529};

Scene block_scene(double size, const std::string& solver) {
  std::string yaml = R"(
name: block
domain: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}
material: {model: corotational, young: 1.0e5, poisson: 0.3, density: 1000}
discretization: {fem: {element: tet4}}
boundary:
  - select: {plane: {axis: z, at: 0.0}}
    fix: [x, y, z]
body_force: {gravity: [0, 0, -9.81]}
solve: {analysis: dynamic, integrator: implicit-euler, dt: 0.01, duration: 10.0, newton: {max_iterations: 1}}
output: {vtk: false}
)";
  return parse_scene(yaml, "benchmark", ".",
                     {"discretization.fem.size=" + std::to_string(size), "solve.linear_solver=" + solver,
                      "solve.petsc=-ksp_type cg -pc_type gamg -ksp_reuse_preconditioner"});
}

void implicit_step(benchmark::State& state, const std::string& solver) {
  Scene scene = block_scene(sizes[state.range(0)], solver);
  RunReport report;
  auto body = make_body(scene, report);
  MechanicalSystem mechanics(*body, scene, report);
  auto stepper = make_stepper(mechanics, stepper_settings(scene), report);
  SolverState s;
  stepper->initialize(s);
  // Steady state: the first steps pay for the symbolic analysis and first factorization.
  for (int warm = 0; warm < 3; ++warm) stepper->advance(s, scene.solve.dt);
  std::vector<double> steps;
  const PhaseTimes warm = report.phases;
  for (auto _ : state) {
    double start = now_seconds();
    stepper->advance(s, scene.solve.dt);
    steps.push_back(now_seconds() - start);
  }
  std::sort(steps.begin(), steps.end());
  state.counters["median_step_ms"] = 1e3 * steps[steps.size() / 2];
  // Where a step's time goes (means over the timed steps): assembly holds the combination of K and M.
  for (Phase phase : {Phase::assembly, Phase::factorize, Phase::solve})
    state.counters[std::string(phase_names[static_cast<std::size_t>(phase)]) + "_ms"] =
        1e3 * (report.phases.seconds(phase) - warm.seconds(phase)) / steps.size();
  state.counters["factorizations"] = report.solver.factorizations;
  state.counters["pcg_iterations_per_step"] = static_cast<double>(report.solver.pcg_iterations) / (steps.size() + 3);
  state.counters["nodes"] = body->node_count();
  state.counters["dofs"] = body->dof_count();
}

void BM_ImplicitEulerStepCorotationalCholmod(benchmark::State& state) { implicit_step(state, "cholmod"); }
void BM_ImplicitEulerStepCorotationalPetscGamg(benchmark::State& state) { implicit_step(state, "petsc"); }

// One explicit central-difference step (internal forces only, lumped mass) at
// 0.9 times the critical step; the paper's meshless method took 20.11 ms a step.
void BM_CentralDifferenceStepCorotational(benchmark::State& state) {
  Scene probe = block_scene(sizes[state.range(0)], "cholmod");
  probe.solve.integrator = Integrator::central_difference;
  probe.solve.dt = 1e-7;
  RunReport probe_report;
  auto probe_body = make_body(probe, probe_report);
  MechanicalSystem probe_mechanics(*probe_body, probe, probe_report);
  make_stepper(probe_mechanics, stepper_settings(probe), probe_report);
  Scene scene = probe;
  scene.solve.dt = 0.9 * probe_report.solver.critical_dt_s.value();
  RunReport report;
  auto body = make_body(scene, report);
  MechanicalSystem mechanics(*body, scene, report);
  auto stepper = make_stepper(mechanics, stepper_settings(scene), report);
  SolverState s;
  stepper->initialize(s);
  for (auto _ : state) stepper->advance(s, scene.solve.dt);
  state.counters["dt_us"] = 1e6 * scene.solve.dt;
  state.counters["nodes"] = body->node_count();
}

/// The block at size level `level`, discretized.
std::unique_ptr<DiscreteBody> block_body(int level) {
  RunReport report;
  return make_body(block_scene(sizes[level], "cholmod"), report);
}

void BM_StiffnessAssemblyCorotational(benchmark::State& state) {
  auto body = block_body(state.range(0));
  SparseMatrix K = build_pattern(*body);
  Vector u = Vector::Constant(body->dof_count(), 1e-4);
  Vector f;
  // As the implicit steppers assemble: straight into the matrix's arrays.
  const MatrixAssembly* direct = capability<MatrixAssembly>(*body);
  for (auto _ : state) {
    std::fill(K.valuePtr(), K.valuePtr() + K.nonZeros(), 0.0);
    direct->add_tangent_into(u, csr_view(K), &f);
  }
  state.counters["elements"] = body->element_count();
}

// The element kernels alone (stress, tangent, element matrices), blocks discarded:
// the difference to the assembly above is the cost of scattering into the matrix.
void BM_ElementKernelsCorotational(benchmark::State& state) {
  auto body = block_body(state.range(0));
  Vector u = Vector::Constant(body->dof_count(), 1e-4);
  Vector f;
  BlockSink discard = [](std::span<const Index>, std::span<const double> values) {
    benchmark::DoNotOptimize(values.data());
  };
  for (auto _ : state) body->tangent(u, discard, &f);
  state.counters["elements"] = body->element_count();
}

/// The block's stiffness at rest restricted to its free dofs, and a CHOLMOD
/// solver that has analysed it.
struct FreeStiffness {
  std::unique_ptr<DiscreteBody> body;
  FreeDofs free;
  RunReport report;
  std::unique_ptr<LinearSolver> solver;
  explicit FreeStiffness(int level)
      : body(block_body(level)), free(body->dof_count(), body->dirichlet(0.0)),
        solver(make_linear_solver({}, report)) {
    SparseMatrix K = build_pattern(*body);
    body->tangent(Vector::Zero(body->dof_count()), add_into(K), nullptr);
    free.prepare_matrix(K);
    free.restrict_values(K);
    solver->analyze(free.restricted());
  }
};

// One solve with a CHOLMOD factor (forward and back substitution): what each
// CG iteration preconditioned by the factor pays beside its product with K.
void BM_CholmodSolve(benchmark::State& state) {
  FreeStiffness system(state.range(0));
  system.solver->factorize(system.free.restricted());
  Vector b = Vector::Ones(system.free.free_count()), x;
  for (auto _ : state) system.solver->solve(b, x);
  const double entries = static_cast<double>(system.solver->factor_entries());
  state.counters["dofs"] = system.free.free_count();
  state.counters["factor_entries"] = entries;
  state.counters["bytes_per_step"] = 2.0 * sizeof(double) * entries;  // read forward and back
}

// The same solve with the factor's single-precision copy (what the stale-factor CG preconditions with).
void BM_CholmodSolveSinglePrecision(benchmark::State& state) {
  FreeStiffness system(state.range(0));
  system.solver->keep_single_precision_copy();
  system.solver->factorize(system.free.restricted());
  Vector b = Vector::Ones(system.free.free_count()), x;
  for (auto _ : state) system.solver->precondition(b, x);
  const double entries = static_cast<double>(system.solver->factor_entries());
  state.counters["factor_entries"] = entries;
  state.counters["bytes_per_step"] = 2.0 * sizeof(float) * entries;
}

void BM_CholmodFactorization(benchmark::State& state) {
  FreeStiffness system(state.range(0));
  for (auto _ : state) system.solver->factorize(system.free.restricted());
  state.counters["dofs"] = system.free.free_count();
}

/// The bare assembly floor of the block at size `level`, with its body and pattern.
struct FloorSetup {
  std::unique_ptr<DiscreteBody> body;
  SparseMatrix K;
  std::unique_ptr<bench::Tet4AssemblyFloor> floor;
  explicit FloorSetup(int level) : body(block_body(level)), K(build_pattern(*body)) {
    const Lame lame = Lame::from_young_poisson(1.0e5, 0.3);
    floor = std::make_unique<bench::Tet4AssemblyFloor>(capability<MeshedBody>(*body)->mesh(), K, lame.lambda,
                                                       lame.mu, omp_get_max_threads());
  }
};

void BM_StiffnessAssemblyFloor(benchmark::State& state) {
  FloorSetup setup(state.range(0));
  Vector u = Vector::Constant(setup.body->dof_count(), 1e-4), f(setup.body->dof_count());
  for (auto _ : state) setup.floor->assemble(u.data(), setup.K, f.data());
  benchmark::DoNotOptimize(f.data());
}

// The least work of one implicit step that solves iteratively with a factor
// as preconditioner: assemble K and f (the floor above), restrict K to the
// free dofs, one product with it and one solve with a factor computed once:
// one preconditioned CG iteration, where kerf takes several.
void BM_ImplicitStepFloor(benchmark::State& state) {
  FloorSetup setup(state.range(0));
  RunReport report;
  const Index n = setup.body->dof_count();
  Vector u = Vector::Zero(n), f(n);
  setup.floor->assemble(u.data(), setup.K, f.data());
  FreeDofs free(n, setup.body->dirichlet(0.0));
  free.prepare_matrix(setup.K);
  free.restrict_values(setup.K);
  auto solver = make_linear_solver({}, report);
  solver->analyze(free.restricted());
  solver->factorize(free.restricted());
  Vector x = Vector::Zero(free.free_count()), Ax(free.free_count());
  for (auto _ : state) {
    setup.floor->assemble(u.data(), setup.K, f.data());
    free.restrict_values(setup.K);
    const Vector b = free.restrict_vector(f);
    Ax.noalias() = free.restricted() * x;
    solver->solve(b - Ax, x);
  }
  benchmark::DoNotOptimize(x.data());
}

BENCHMARK(BM_ImplicitEulerStepCorotationalCholmod)->DenseRange(0, 3)->Iterations(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ImplicitEulerStepCorotationalPetscGamg)->Arg(2)->Iterations(10)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CentralDifferenceStepCorotational)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StiffnessAssemblyCorotational)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ElementKernelsCorotational)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CholmodFactorization)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CholmodSolve)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CholmodSolveSinglePrecision)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StiffnessAssemblyFloor)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ImplicitStepFloor)->DenseRange(0, 3)->Iterations(40)->Unit(benchmark::kMillisecond);

const bool paired =
    (bench::pair_with_floor("BM_ImplicitEulerStepCorotationalCholmod/2", "BM_ImplicitStepFloor/2",
                            "bare linear tet4 assembly + one CG iteration with a fixed CHOLMOD factor"),
     bench::pair_with_floor("BM_ImplicitEulerStepCorotationalCholmod/3", "BM_ImplicitStepFloor/3",
                            "bare linear tet4 assembly + one CG iteration with a fixed CHOLMOD factor"),
     bench::pair_with_floor("BM_ImplicitEulerStepCorotationalPetscGamg/2", "BM_ImplicitStepFloor/2",
                            "bare linear tet4 assembly + one CG iteration with a fixed CHOLMOD factor"),
     bench::pair_with_floor("BM_CholmodSolveSinglePrecision/2", "BM_CholmodSolve/2",
                            "not a floor but the reference: CHOLMOD's double solve of the same factor (the floor "
                            "is the bytes/memory column)"),
     bench::pair_with_floor("BM_StiffnessAssemblyCorotational/2", "BM_StiffnessAssemblyFloor/2",
                            "bare LINEAR tet4 K_e, f_e through a slot table"),
     bench::pair_with_floor("BM_ElementKernelsCorotational/2", "BM_StiffnessAssemblyFloor/2",
                            "bare LINEAR tet4 K_e, f_e through a slot table"),
     true);

}  // namespace
}  // namespace kerf
