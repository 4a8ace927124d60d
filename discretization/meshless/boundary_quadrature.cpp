#include "discretization/meshless/boundary_quadrature.h"

#include "discretization/fem/simplex_quadrature.h"

namespace kerf {

void BoundaryQuadrature::append(const BoundaryQuadrature& other) {
  position.insert(position.end(), other.position.begin(), other.position.end());
  weighted_normal.insert(weighted_normal.end(), other.weighted_normal.begin(), other.weighted_normal.end());
}

BoundaryQuadrature facet_quadrature(const Mesh& mesh, const BoundaryFacets& facets, std::span<const int> per_direction) {
  const int fdim = mesh.dimension - 1;
  BoundaryQuadrature out;
  QuadratureRule rule;
  int rule_points = -1;
  for (Index f = 0; f < facets.count(); ++f) {
    if (per_direction[f] != rule_points) rule_points = per_direction[f], rule = collapsed_gauss(fdim, rule_points);
    auto fn = facets.facet(f);
    const Vec3 a = mesh.nodes[fn[0]], b = mesh.nodes[fn[1]];
    const Vec3 c = fdim == 2 ? mesh.nodes[fn[2]] : a;
    // The outward area normal of the straight facet: |.| = d(area)/d(reference area).
    const Vec3 area_normal = fdim == 2 ? Vec3((b - a).cross(c - a)) : Vec3((b - a).y(), -(b - a).x(), 0.0);
    for (std::size_t q = 0; q < rule.points.size(); ++q) {
      const Vec3& r = rule.points[q];
      out.position.push_back(Vec3(a + r.x() * (b - a) + (fdim == 2 ? r.y() : 0.0) * (c - a)));
      out.weighted_normal.push_back(rule.weights[q] * area_normal);
    }
  }
  return out;
}

BoundaryQuadrature cut_face_quadrature(const Mesh& cells, std::span<const Index> candidates, const CutPiece& piece,
                                       double hair) {
  BoundaryQuadrature out;
  PartPoints points;
  // A piece on a cell face goes to one cell: decided a far smaller hair off than the faces' points stand.
  for (const CutPart& part : cut_parts(cells, candidates, piece, 1e-3 * hair)) {
    part_quadrature(part, cells.dimension, points);
    for (std::size_t q = 0; q < points.position.size(); ++q) {
      const Vec3& x = points.position[q];
      const Vec3 n = points.weight[q] * piece.normal;
      out.position.push_back(x + hair * piece.normal);  // the region n points into: outward -n
      out.weighted_normal.push_back(-n);
      out.position.push_back(x - hair * piece.normal);
      out.weighted_normal.push_back(n);
    }
  }
  return out;
}

}  // namespace kerf
