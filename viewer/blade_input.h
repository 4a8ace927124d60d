#pragma once
// The mouse as a blade: each point the pointer picks on the body (reference
// coordinates) becomes the next vertex pair of the scene's live cut, the
// blade's two ends along the line of sight: `above` in front of the picked
// point, `depth` behind it. Positions closer than `spacing` to the last one
// fed are skipped (a piece that thin would be degenerate). A position the
// session refuses (the strip would fold) is reported and not kept. A live
// cut is one strip: a new stroke of the mouse goes on from the last position.
#include <optional>
#include <string>

#include "app/session.h"
#include "geometry/cut_surface.h"

namespace kerf {

class BladeInput {
 public:
  BladeInput(Session& session, Index cut, double above, double depth, double spacing);
  /// The blade at `picked` (m, reference) pointing along `sight` (unit, into
  /// the body): true when a new position was fed.
  bool move_to(const Vec3& picked, const Vec3& sight);
  /// The cut as fed so far (the viewer drops the cells it crosses).
  const CutSurface& cut() const { return fed_; }
  /// Why the last position was refused ("" when it was not).
  const std::string& refusal() const { return refusal_; }
  Index positions() const { return static_cast<Index>(fed_.vertices.size() / 2); }

 private:
  Session& session_;
  Index cut_;
  double above_, depth_, spacing_;
  std::optional<Vec3> last_;
  CutSurface fed_;
  std::string refusal_;
};

}  // namespace kerf
