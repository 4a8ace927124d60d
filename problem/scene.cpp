#include "problem/scene.h"

namespace kerf {

SourceLocation Scene::locate(const std::string& key) const {
  if (auto found = sources.find(key); found != sources.end()) return found->second;
  // A key the file left out (a default): the nearest ancestor it wrote.
  SourceLocation where;
  where.file = file;
  for (std::string parent = key; !parent.empty();) {
    const std::size_t dot = parent.rfind('.');
    parent = dot == std::string::npos ? std::string() : parent.substr(0, dot);
    if (auto found = sources.find(parent); found != sources.end()) {
      where = found->second;
      where.text.clear();
      break;
    }
  }
  where.key = key;
  return where;
}

bool BoundaryCondition::is_dirichlet() const {
  for (int i = 0; i < 3; ++i)
    if (fixed[i] || displacement[i]) return true;
  return false;
}

}  // namespace kerf
