#pragma once
// A scene's selections of the boundary (a plane, a box, the node nearest a
// point), and which points of a discretization one takes (shared by every method).
#include <span>
#include <vector>

#include "core/types.h"
#include "problem/source_location.h"

namespace kerf {

struct Box {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  bool contains(const Vec3& p, double tolerance) const;
};

struct Selection {
  enum class Kind { plane, box, point };
  Kind kind = Kind::plane;
  int axis = 0;            // plane: 0, 1, 2 for x, y, z
  double at = 0.0;         // plane: coordinate (m)
  Box box;                 // box
  Vec3 point = Vec3::Zero();  // point: the nearest node is taken
  SourceLocation where;
};

/// plane: boundary points within 1e-9 * domain_size of the plane; box: boundary
/// points inside the closed box; point: the one point nearest to it.
/// Throws, naming the selection's scene line, when it takes nothing.
std::vector<Index> select_points(const Selection& selection, std::span<const Vec3> points,
                                 std::span<const char> on_boundary, double domain_size);

}  // namespace kerf
