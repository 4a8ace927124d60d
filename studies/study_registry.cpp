#include <array>

#include "core/check.h"
#include "studies/study.h"

namespace kerf {

std::span<const StudyEntry> all_studies() {
  static const std::array<StudyEntry, 11> entries{{
      {"hertz", "indentation of a block by a rigid sphere against Hertz's solution, every method", hertz_study},
      {"timing", "time of a step of each method and integrator, phase by phase, beside the paper's", timing_study},
      {"stability", "critical steps, undamped energy, zero-energy modes, a 200-piece zigzag cut, locking",
       stability_study},
      {"pareto", "wall time against error of every method and resolution, on Hertz and on a crack", pareto_study},
      {"cut", "a sagging block cut progressively: meshless grid against fem remesh and fem remove", cut_study},
      {"cut_convergence", "the cut block held still: every method refined against converged tet10 remesh",
       cut_convergence_study},
      {"crack3d", "the 3D cracked slab: every method's crack opening refined against converged tet10 remesh",
       crack3d_study},
      {"organ", "a curved body from a gmsh mesh sagging: each meshless way refined against converged tet10",
       organ_study},
      {"solvers", "the FEM implicit step with each linear solver at three sizes: which is fastest where",
       solvers_study},
      {"scaling", "the same FEM scene on 1, 2 and 3 MPI ranks, phase by phase (strong and weak scaling)",
       scaling_study},
      {"haptic", "a haptic loop at 1 kHz: blade fed every step, sphere pressed, each method's iteration beside its floor",
       haptic_study},
  }};
  return entries;
}

void run_study(const std::string& name, StudyOptions options) {
  std::string known;
  for (const StudyEntry& s : all_studies()) {
    if (name == s.name) {
      if (options.out_dir.empty()) options.out_dir = "results/" + name;
      s.run(options);
      return;
    }
    known += std::string(known.empty() ? "" : ", ") + s.name;
  }
  throw Error("no study named '" + name + "'; expected one of: " + known);
}

}  // namespace kerf
