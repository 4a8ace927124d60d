#pragma once
// The one check of a scene, whoever built it (the YAML reader calls it last; a
// run calls it first, so a Scene built in code gets the same refusals): every
// value in range, the items consistent with each other, and what is not built
// yet refused before any work. Each refusal throws kerf::Error naming the
// file, line and key (Scene::locate), the value, and what was expected.
// The cuts' geometry (zero-length pieces, folds) is checked where the cuts are
// built, once per run (discretization/cut_timeline.h).
#include "problem/scene.h"

namespace kerf {

void validate(const Scene& scene);

}  // namespace kerf
