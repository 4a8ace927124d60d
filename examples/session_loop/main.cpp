// A simulator's loop around a kerf session (app/session.h): open a scene,
// step it, read the state between steps (here the body's lowest point),
// finish. Usage: kerf_session_loop SCENE.yaml OUT_DIR [KEY=VALUE ...], the
// overrides as `kerf run --set` takes them.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/session.h"
#include "core/denormals.h"
#include "core/thread_policy.h"
#include "problem/scene_reader.h"

int main(int argc, char** argv) {
  kerf::apply_thread_policy(argv);
  kerf::flush_denormals_to_zero();
  if (argc < 3) {
    std::fprintf(stderr, "usage: kerf_session_loop SCENE.yaml OUT_DIR [KEY=VALUE ...]\n");
    return 2;
  }
  try {
    std::vector<std::string> overrides(argv + 3, argv + argc);
    overrides.push_back(std::string("output.dir=") + argv[2]);
    kerf::RunOptions options;
    options.quiet = true;
    kerf::Session session(kerf::read_scene(argv[1], overrides), options);
    const int dim = session.dofs_per_node();
    while (!session.done()) {
      session.step();
      const kerf::Vector& u = session.displacement();  // the host reads the state between steps
      double lowest = 0.0;
      for (kerf::Index n = 0; n < session.node_count(); ++n) lowest = std::min(lowest, u[dim * n + dim - 1]);
      if (session.done() || session.steps_taken() % 50 == 0)
        std::printf("step %d  t = %.4f s  lowest displacement %.4f mm\n", session.steps_taken(), session.time(),
                    1e3 * lowest);
    }
    const kerf::RunOutcome outcome = session.finish();
    std::printf("probes %s\n", outcome.summary["probes"].dump().c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "kerf_session_loop: %s\n", e.what());
    return 1;
  }
}
