#pragma once
// The boundaries of the barycentric dual cells of a node set's simplices (in
// each simplex, the part where a node's barycentric coordinate is the
// largest), cut into flat parts, and the samples smoothed gradients take on
// them (smoothed_gradient.h): 2D, two Gauss points on each dual segment
// (edge midpoint to centroid) and on each half boundary edge; 3D, the
// centroid of each triangle of the dual quadrilaterals (edge midpoint, face
// centroid, centroid, face centroid) and of the boundary faces' parts. Every
// rule is exact for linear fields.
#include <array>
#include <vector>

#include "core/types.h"
#include "discretization/enrichment/cut_weights.h"
#include "geometry/mesh.h"

namespace kerf {

/// A flat piece of a cell's boundary: a segment (2D, corners 0-1) or a
/// triangle (3D), with its outward normal times its length or area.
struct CellPart {
  std::array<Vec3, 3> corner;
  int corners = 2;
  Vec3 weighted_normal = Vec3::Zero();
};

/// Where shape functions are sampled for one cell: a point and the outward
/// normal times the quadrature weight (m^2 in 3D, m in 2D).
struct CellSample {
  Vec3 position = Vec3::Zero();
  Vec3 weighted_normal = Vec3::Zero();
};

/// Per node of the linear simplex mesh: the parts of its dual cell's boundary, outward.
std::vector<std::vector<CellPart>> dual_cell_parts(const Mesh& mesh);

/// Samples of one part: two Gauss points (segment) or the centroid (triangle).
/// With cuts, a part that a cut crosses is halved (segment, up to `depth`
/// times: 40 find the crossing to round-off) or quartered (triangle, when a
/// cut crosses an edge; 5 times), so no sample straddles a jump.
void sample_part(const CellPart& part, const CutWeights* cuts, int depth, std::vector<CellSample>& out);

}  // namespace kerf
