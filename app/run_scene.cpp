#include "app/run_scene.h"

#include "app/session.h"

namespace kerf {

RunOutcome run_scene(const Scene& scene, const RunOptions& options) {
  Session session(scene, options);
  while (!session.done()) session.step();
  return session.finish();
}

}  // namespace kerf
