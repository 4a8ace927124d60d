#include "problem/user_material.h"

#include <algorithm>
#include <mutex>

#include "core/check.h"
#include "problem/scene.h"

namespace kerf {
namespace {

struct Registry {
  std::mutex mutex;
  std::map<std::string, UserMaterialEntry> entries;
};

/// Built on first use: registrations from other translation units' static
/// initialisers may come before this file's own statics exist.
Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

bool register_material(const std::string& name, std::vector<std::string> parameters, UserMaterialFactory make) {
  const auto& builtin = EnumNames<MaterialModel>::names;
  KERF_CHECK(std::find(builtin.begin(), builtin.end(), name) == builtin.end(), "register_material: '", name,
             "' is a built-in material model; expected another name");
  KERF_CHECK(!name.empty() && make, "register_material: expected a name and a factory");
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  KERF_CHECK(!r.entries.count(name), "register_material: '", name, "' is already registered");
  r.entries[name] = UserMaterialEntry{std::move(parameters), std::move(make)};
  return true;
}

const UserMaterialEntry* find_user_material(const std::string& name) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  auto it = r.entries.find(name);
  return it == r.entries.end() ? nullptr : &it->second;
}

std::vector<std::string> user_material_names() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& entry : r.entries) names.push_back(entry.first);
  return names;
}

}  // namespace kerf
