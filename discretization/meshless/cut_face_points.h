#pragma once
// Integration points on a cut's pieces that follow the borders of a node
// set's dual cells (smoothed gradients integrate the cut's faces cell by
// cell): each point with its weight and the node whose cell holds it.
#include <array>
#include <vector>

#include "geometry/cut_surface.h"
#include "geometry/mesh.h"
#include "geometry/point_location.h"

namespace kerf {

/// A point on a cut with its quadrature weight (m or m^2) and the node whose dual cell holds it.
struct CutPoint {
  Vec3 x;
  double weight;
  Index cell;
};

/// The piece is cut into parts about `length` long, and a part whose corners
/// lie in different cells is halved (2D, up to 40 times: the border is found
/// to round-off) or quartered (3D, up to 5 times); a part then gets two Gauss
/// points (2D) or its centroid (3D), each in the cell holding it. Parts
/// beyond the mesh are dropped.
class CutPoints {
 public:
  CutPoints(const Mesh& mesh, const CellLocator& locator);
  void of_piece(const CutPiece& piece, int dim, double length, std::vector<CutPoint>& out);

 private:
  Index cell_of(const Vec3& x) const;
  void emit(const Vec3& x, double weight, std::vector<CutPoint>& out) const;
  void segment(const Vec3& a, const Vec3& b, int depth, std::vector<CutPoint>& out) const;
  void triangle(const Vec3& a, const Vec3& b, const Vec3& c, int depth, std::vector<CutPoint>& out) const;

  const Mesh& mesh_;
  const CellLocator& locator_;
  std::array<Vec3, 2> box_;
};

}  // namespace kerf
