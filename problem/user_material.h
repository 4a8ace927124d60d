#pragma once
// Constitutive laws defined outside kerf (a project built against the
// installed kerf, examples/user_material): registered under a name before the
// scene is read, chosen by `material.model: NAME`, their own constants under
// `material.parameters`. young and poisson keep their meaning (the law's
// small-strain moduli): wave speeds, penalties and the stabilisation use them.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/types.h"

namespace kerf {

struct Material;

/// The law at a material point, as MaterialLaw's built-in models (material.h):
/// F the deformation gradient, P the first Piola-Kirchhoff stress, dPdF on
/// column-major vec(F). Called from many threads at once: no mutable state.
class UserMaterialLaw {
 public:
  virtual ~UserMaterialLaw() = default;
  virtual double energy(const Mat3& F) const = 0;
  virtual Mat3 stress(const Mat3& F) const = 0;
  virtual void stress_and_tangent(const Mat3& F, Mat3& P, Mat9& dPdF) const = 0;
  /// True when P is linear in F (the stiffness is then assembled once).
  virtual bool is_linear() const { return false; }
};

/// Makes the law from the scene's material (young, poisson, its parameters).
using UserMaterialFactory = std::function<std::shared_ptr<const UserMaterialLaw>(const Material&)>;

struct UserMaterialEntry {
  std::vector<std::string> parameters;  // every one required in material.parameters
  UserMaterialFactory make;
};

/// Registers a law under `name` (throws kerf::Error when the name is a
/// built-in model's or already registered). Returns true, so that a static
/// `const bool registered = register_material(...)` registers at start-up.
bool register_material(const std::string& name, std::vector<std::string> parameters, UserMaterialFactory make);

/// The registered law of that name, or null.
const UserMaterialEntry* find_user_material(const std::string& name);

/// The registered names, sorted.
std::vector<std::string> user_material_names();

}  // namespace kerf
