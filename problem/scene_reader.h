#pragma once
// Reads a scene file (YAML), applies --set overrides, validates every key and
// fills defaults. Any problem throws kerf::Error naming file, line, key, value
// and what was expected, before any work is done.
#include <string>
#include <vector>

#include "problem/scene.h"

namespace kerf {

/// `overrides` are "dotted.key=value" strings; values are parsed as YAML.
Scene read_scene(const std::string& path, const std::vector<std::string>& overrides = {});
/// The scene file's text (a study runs it again with its own overrides).
std::string read_scene_text(const std::string& path);

/// Same, from text; `file` names it in messages and relative paths start at `directory`.
Scene parse_scene(const std::string& yaml_text, const std::string& file,
                  const std::string& directory, const std::vector<std::string>& overrides = {});

}  // namespace kerf
