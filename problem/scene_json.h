#pragma once
// The resolved scene (defaults filled in) as JSON, in the shape of the scene
// file, so that summary.json and `kerf check` echo exactly what a run used.
#include <nlohmann/json.hpp>

#include "problem/scene.h"

namespace kerf {

nlohmann::ordered_json scene_to_json(const Scene& scene);

}  // namespace kerf
