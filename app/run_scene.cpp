#include "app/run_scene.h"

#include "app/session.h"
#include "core/interrupt.h"

namespace kerf {

RunOutcome run_scene(const Scene& scene, const RunOptions& options) {
  const InterruptScope interrupt;  // Ctrl-C or SIGTERM: the run stops at its next check, its summary saying so
  Session session(scene, options);
  while (!session.done()) session.step();
  return session.finish();
}

}  // namespace kerf
