#include "problem/scene_overrides.h"

#include <algorithm>
#include <cctype>

#include "core/check.h"

namespace kerf {
namespace {

std::vector<std::string> split_key(const std::string& key) {
  std::vector<std::string> parts;
  std::string part;
  for (char c : key) {
    if (c == '.') {
      parts.push_back(part);
      part.clear();
    } else {
      part += c;
    }
  }
  parts.push_back(part);
  return parts;
}

bool is_index(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

}  // namespace

std::set<std::string> apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides) {
  std::set<std::string> keys;
  for (const std::string& item : overrides) {
    auto eq = item.find('=');
    KERF_CHECK(eq != std::string::npos && eq > 0, "--set '", item,
               "': expected KEY=VALUE with a dotted key, e.g. material.young=2e6");
    std::string key = item.substr(0, eq);
    YAML::Node value;
    try {
      value = YAML::Load(item.substr(eq + 1));
    } catch (const YAML::Exception& e) {
      throw Error("--set '" + item + "': the value is not valid YAML (" + e.msg + ")");
    }
    std::vector<std::string> parts = split_key(key);
    for (const auto& p : parts)
      KERF_CHECK(!p.empty(), "--set '", item, "': empty component in key '", key, "'");
    // Walk down with fresh handles (yaml-cpp nodes are references; reassigning
    // a handle would overwrite the node it points at).
    std::vector<YAML::Node> path{root};
    for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
      YAML::Node parent = path.back();
      const std::string& p = parts[i];
      if (is_index(p)) {
        std::size_t index = std::stoul(p);
        KERF_CHECK(parent.IsSequence() && index < parent.size(), "--set '", item, "': '",
                   p, "' in key '", key, "' is not an item of an existing list");
        path.push_back(parent[index]);
      } else {
        KERF_CHECK(!parent.IsSequence() && !parent.IsScalar(), "--set '", item, "': '", p,
                   "' in key '", key, "' goes into a value that is not a map");
        if (!parent[p] || parent[p].IsNull()) parent[p] = YAML::Node(YAML::NodeType::Map);
        path.push_back(parent[p]);
      }
    }
    YAML::Node parent = path.back();
    const std::string& last = parts.back();
    if (is_index(last)) {
      std::size_t index = std::stoul(last);
      KERF_CHECK(parent.IsSequence() && index <= parent.size(), "--set '", item,
                 "': list index ", last, " is past the end of '", key, "'");
      if (index == parent.size())
        parent.push_back(value);
      else
        parent[index] = value;
    } else {
      KERF_CHECK(!parent.IsSequence() && !parent.IsScalar(), "--set '", item,
                 "': the parent of '", last, "' is not a map");
      parent[last] = value;
    }
    keys.insert(key);
  }
  return keys;
}

}  // namespace kerf
