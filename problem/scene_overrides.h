#pragma once
// `--set KEY=VALUE` on a YAML tree: KEY is a dotted path, list items by index.
#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

namespace kerf {

/// Applies each override to `root` in order; returns the dotted keys that were set.
std::set<std::string> apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides);

}  // namespace kerf
