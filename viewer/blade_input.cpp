#include "viewer/blade_input.h"

#include <array>

namespace kerf {

BladeInput::BladeInput(Session& session, Index cut, double above, double depth, double spacing)
    : session_(session), cut_(cut), above_(above), depth_(depth), spacing_(spacing),
      fed_(cut_surface(3, {}, {}, "the viewer's blade")) {}

bool BladeInput::move_to(const Vec3& picked, const Vec3& sight) {
  if (last_ && (picked - *last_).norm() < spacing_) return false;
  const std::array<Vec3, 2> ends{picked - above_ * sight, picked + depth_ * sight};
  try {
    session_.extend_cut(cut_, ends);
    extend_cut_surface(fed_, ends, session_.time());
  } catch (const std::exception& e) {
    refusal_ = e.what();
    return false;
  }
  refusal_.clear();
  last_ = picked;
  return true;
}

}  // namespace kerf
