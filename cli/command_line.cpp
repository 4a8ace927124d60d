#include "cli/command_line.h"

#include <algorithm>
#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>

#include <unistd.h>

#include "app/resource_estimate.h"
#include "app/run_scene.h"
#include "core/check.h"
#include "core/interrupt.h"
#include "kerf/version.h"
#include "problem/scene_json.h"
#include "problem/scene_reader.h"
#include "solvers/petsc_session.h"
#include "solvers/rank_messages.h"
#include "solvers/rank_sum.h"
#include "studies/study.h"

namespace kerf {
namespace {

constexpr const char* usage =
    "usage:\n"
    "  kerf run SCENE.yaml [--set KEY=VALUE]... [--out DIR] [--quiet] [--force]\n"
    "  kerf check SCENE.yaml [--set KEY=VALUE]...   validate only, print the resolved scene and its estimate\n"
    "  (--force: run even when the estimated memory or output exceeds what the machine has)\n"
    "  kerf study [NAME] [--quick] [--out DIR] [--quiet]   the studies; no NAME lists them\n"
    "  kerf view SCENE.yaml [--set KEY=VALUE]... [--script FILE]   the scene in a window, the mouse as its blade\n"
    "  kerf --version\n";

struct Arguments {
  std::string command, target, out;
  std::vector<std::string> overrides;
  bool quiet = false, quick = false, force = false;
};

Arguments parse(const std::vector<std::string>& args) {
  Arguments a;
  if (args.empty()) throw Error(std::string("no command given\n") + usage);
  a.command = args[0];
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& s = args[i];
    auto value = [&](const char* flag) {
      KERF_CHECK(i + 1 < args.size(), flag, " needs a value\n", usage);
      return args[++i];
    };
    if (s == "--set") a.overrides.push_back(value("--set"));
    else if (s.rfind("--set=", 0) == 0) a.overrides.push_back(s.substr(6));
    else if (s == "--out") a.out = value("--out");
    else if (s == "--quiet") a.quiet = true;
    else if (s == "--quick") a.quick = true;
    else if (s == "--force") a.force = true;
    else if (s.rfind("--", 0) == 0) throw Error("unknown option '" + s + "'\n" + usage);
    else if (a.target.empty()) a.target = s;
    else throw Error("unexpected argument '" + s + "'\n" + usage);
  }
  return a;
}

/// `kerf study [NAME]`: without a name, the list; a failed claim or run exits with 1.
int study_command(const Arguments& a) {
  KERF_CHECK(a.overrides.empty(), "study takes no --set (each study builds its own scenes)\n", usage);
  if (a.target.empty()) {
    std::cout << "studies (kerf study NAME [--quick] [--out DIR] [--quiet]):\n";
    for (const StudyEntry& s : all_studies()) std::cout << "  " << s.name << "  " << s.summary << "\n";
    return 0;
  }
  StudyOptions options;
  options.quick = a.quick;
  options.out_dir = a.out;
  options.quiet = a.quiet;
  const InterruptScope interrupt;  // one for the whole study: a signal between its runs is kept
  try {
    run_study(a.target, options);
  } catch (const std::exception& e) {
    std::cerr << "kerf: error: study " << a.target << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}

/// Under mpirun only PETSc's solvers share a linear solve between ranks: a
/// serial one is refused before any work (explicit runs solve nothing).
void refuse_serial_solver_on_ranks(const Scene& scene, int ranks) {
  if (ranks == 1 || !scene.solve.solves_linear_systems() || linear_backend(scene.solve.linear_solver).spans_ranks)
    return;
  throw Error(scene.locate("solve.linear_solver").describe() + ": " + to_string(scene.solve.linear_solver) +
              " cannot run on " + std::to_string(ranks) +
              " MPI ranks; expected petsc (PETSc's KSP shares the solve between ranks)");
}

/// The lowest rank for which `refused`, or -1 when none. Under mpirun a
/// collective: every rank must call it.
int first_refusing_rank(const RankShare& ranks, bool refused) {
  if (!ranks.distributed()) return refused ? 0 : -1;
  const std::vector<std::vector<double>> each = values_of_every_rank({refused ? 1.0 : 0.0}, ranks);
  for (int r = 0; r < ranks.count; ++r)
    if (each[r][0] != 0.0) return r;
  return -1;
}

/// `kerf view`: the arguments handed to kerf-view beside this program (VTK's
/// rendering is loaded by it alone). Returns only when it cannot be started.
int run_viewer(const std::vector<std::string>& args) {
  const std::filesystem::path viewer = std::filesystem::read_symlink("/proc/self/exe").parent_path() / "kerf-view";
  std::vector<std::string> words{viewer.string()};
  words.insert(words.end(), args.begin() + 1, args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  execv(viewer.c_str(), argv.data());
  std::cerr << "kerf: error: kerf view needs the viewer program " << viewer.string() << " (built and installed with "
            << "kerf): " << std::strerror(errno) << "\n";
  return 1;
}

}  // namespace

int run_command_line(const std::vector<std::string>& args) {
  if (!args.empty() && args[0] == "view") return run_viewer(args);
  Arguments a;
  Scene scene;
  RankShare ranks;
  try {
    ranks = mpi_ranks();  // first: under mpirun, even a usage error is printed once
  } catch (const std::exception& e) {
    std::cerr << "kerf: error: " << e.what() << "\n";
    return 1;
  }
  std::string refusal;  // why the command line or the scene cannot run
  try {
    a = parse(args);
    if (a.command == "--version" || a.command == "version") {
      std::cout << "kerf " << version << "\n";
      return 0;
    }
    if (a.command == "--help" || a.command == "help") {
      std::cout << usage;
      return 0;
    }
    if (a.command == "study") return study_command(a);
    KERF_CHECK(a.command == "run" || a.command == "check", "unknown command '", a.command, "'\n", usage);
    KERF_CHECK(!a.target.empty(), a.command, " needs a scene file\n", usage);
    scene = read_scene(a.target, a.overrides);
    refuse_unrunnable(scene);
    refuse_serial_solver_on_ranks(scene, ranks.count);
  } catch (const std::exception& e) {
    refusal = e.what();
  }
  // Every rank that read the scene (or failed to) gets here: they agree on
  // who refused it, and the first of them alone says why.
  if (const int first = first_refusing_rank(ranks, !refusal.empty()); first >= 0) {
    if (ranks.rank == first)
      std::cerr << "kerf: error: " << (first != 0 ? "rank " + std::to_string(first) + ": " : "") << refusal << "\n";
    return 2;
  }
  if (a.command == "check") {
    std::cout << scene_to_json(scene).dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) << "\n";
    if (ranks.rank == 0) std::cerr << describe(estimate_resources(scene, ranks.count));
    return 0;
  }
  try {
    RunOptions options;
    options.out_dir = a.out;
    options.force = a.force;
    // Under mpirun every rank runs the scene; rank 0 alone prints and writes (but the series' pieces).
    options.quiet = a.quiet || ranks.rank != 0;
    options.mpi = petsc_mpi_context(ranks);
    RunOutcome outcome = run_scene(scene, options);
    if (!options.quiet) {
      for (const std::string& note : outcome.report.notes) std::cerr << "kerf: note: " << note << "\n";
      std::cerr << "kerf: results in " << outcome.directory << "\n";
    }
    return 0;
  } catch (const std::exception& e) {
    // The summary says "error" (run_scene wrote it); the other ranks must not wait for this one.
    if (ranks.distributed()) stop_every_rank(ranks, 1, e.what(), dynamic_cast<const SharedFailure*>(&e) != nullptr);
    std::cerr << "kerf: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace kerf
