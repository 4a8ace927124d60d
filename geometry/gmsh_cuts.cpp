#include "geometry/gmsh_cuts.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gmsh.h>

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>
#include <utility>


namespace kerf {
namespace {

using DimTags = std::vector<std::pair<int, int>>;

/// OpenCASCADE points and lines shared between pieces, so the strip or the
/// polyline is one connected curve or surface before fragmenting.
class SharedEntities {
 public:
  int point(const Vec3& x) {
    auto key = std::make_tuple(x.x(), x.y(), x.z());
    auto it = points_.find(key);
    if (it != points_.end()) return it->second;
    return points_[key] = gmsh::model::occ::addPoint(x.x(), x.y(), x.z());
  }
  /// The line a -> b; its tag is negated when it was made b -> a.
  int line(const Vec3& a, const Vec3& b) {
    const int p = point(a), q = point(b);
    auto it = lines_.find({std::min(p, q), std::max(p, q)});
    if (it != lines_.end()) return p < q ? it->second : -it->second;
    const int tag = gmsh::model::occ::addLine(std::min(p, q), std::max(p, q));
    lines_[{std::min(p, q), std::max(p, q)}] = tag;
    return p < q ? tag : -tag;
  }

 private:
  std::map<std::tuple<double, double, double>, int> points_;
  std::map<std::pair<int, int>, int> lines_;
};

/// Where the centre of an entity lies relative to the box: strictly inside,
/// on its boundary, or outside (within a tolerance of the box's size).
enum class Placement { inside, boundary, outside };

Placement placement(const Vec3& x, int dimension, const Vec3& min, const Vec3& max) {
  const double tolerance = 1e-9 * (max - min).norm();
  bool on_boundary = false;
  for (int k = 0; k < dimension; ++k) {
    if (x[k] < min[k] - tolerance || x[k] > max[k] + tolerance) return Placement::outside;
    if (x[k] < min[k] + tolerance || x[k] > max[k] - tolerance) on_boundary = true;
  }
  return on_boundary ? Placement::boundary : Placement::inside;
}

Vec3 entity_centre(int dim, int tag) {
  double x = 0, y = 0, z = 0;
  if (dim == 0) {
    std::vector<double> coordinates;
    gmsh::model::getValue(0, tag, {}, coordinates);
    return {coordinates[0], coordinates[1], coordinates[2]};
  }
  gmsh::model::occ::getCenterOfMass(dim, tag, x, y, z);
  return {x, y, z};
}

/// The piece the point x (on the cut) lies on: the nearest.
const CutPiece& piece_under(const std::vector<CutPiece>& pieces, int dimension, const Vec3& x) {
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  auto point = [](const Vec3& p) { return Kernel::Point_3(p.x(), p.y(), p.z()); };
  const CutPiece* nearest = &pieces.front();
  double best = std::numeric_limits<double>::infinity();
  for (const CutPiece& p : pieces) {
    const double d = dimension == 2
                         ? CGAL::squared_distance(point(x), Kernel::Segment_3(point(p.corner[0]), point(p.corner[1])))
                         : CGAL::squared_distance(point(x), Kernel::Triangle_3(point(p.corner[0]), point(p.corner[1]),
                                                                               point(p.corner[2])));
    if (d < best) best = d, nearest = &p;
  }
  return *nearest;
}

/// The Crack plugin tells the two sides of the crack apart by its mesh
/// elements' normals, which follow each entity's own orientation: mesh every
/// part of the crack with the normal of the piece it came from.
void orient_like_pieces(int dimension, const std::vector<int>& crack, const std::vector<CutPiece>& pieces) {
  for (int tag : crack) {
    const Vec3 centre = entity_centre(dimension - 1, tag);
    Vec3 normal;
    if (dimension == 2) {
      std::vector<double> low, high, tangent;
      gmsh::model::getParametrizationBounds(1, tag, low, high);
      gmsh::model::getDerivative(1, tag, {0.5 * (low[0] + high[0])}, tangent);
      normal = Vec3(-tangent[1], tangent[0], 0.0);  // the plugin's (0, 0, 1) x tangent
    } else {
      std::vector<double> uv, n;
      gmsh::model::getParametrization(2, tag, {centre.x(), centre.y(), centre.z()}, uv);
      gmsh::model::getNormal(tag, uv, n);
      normal = Vec3(n[0], n[1], n[2]);
    }
    if (normal.dot(piece_under(pieces, dimension, centre).normal) < 0.0)
      gmsh::model::mesh::setReverse(dimension - 1, tag);
  }
}

}  // namespace

CutGroups embed_cuts(int dimension, int body, const std::vector<CutPiece>& pieces, const Vec3& min, const Vec3& max) {
  CutGroups groups;
  if (pieces.empty()) return groups;
  const int cut_dim = dimension - 1;
  SharedEntities shared;
  DimTags tools;
  for (const CutPiece& p : pieces) {
    if (dimension == 2) {
      tools.emplace_back(1, std::abs(shared.line(p.corner[0], p.corner[1])));
      continue;
    }
    const int loop = gmsh::model::occ::addCurveLoop({shared.line(p.corner[0], p.corner[1]),
                                                    shared.line(p.corner[1], p.corner[2]),
                                                    shared.line(p.corner[2], p.corner[0])});
    tools.emplace_back(2, gmsh::model::occ::addPlaneSurface({loop}));
  }
  DimTags fragments;
  std::vector<DimTags> map;
  gmsh::model::occ::fragment({{dimension, body}}, tools, fragments, map);

  // The pieces now meet the body's boundary conformingly; what lies outside goes.
  DimTags entities, outside;
  gmsh::model::occ::getEntities(entities, cut_dim);
  std::vector<int> crack;
  for (const auto& [dim, tag] : entities) {
    const Placement where = placement(entity_centre(dim, tag), dimension, min, max);
    if (where == Placement::inside) crack.push_back(tag);
    if (where == Placement::outside) outside.emplace_back(dim, tag);
  }
  if (!outside.empty()) gmsh::model::occ::remove(outside, true);
  gmsh::model::occ::synchronize();
  if (crack.empty()) return groups;
  orient_like_pieces(dimension, crack, pieces);
  groups.crack = gmsh::model::addPhysicalGroup(cut_dim, crack);

  // The cut's edges on the domain's boundary: an edge crack opens up to the surface.
  std::vector<int> open;
  for (int tag : crack) {
    DimTags boundary;
    gmsh::model::getBoundary({{cut_dim, tag}}, boundary, false, false, false);
    for (const auto& [dim, edge] : boundary)
      if (placement(entity_centre(dim, std::abs(edge)), dimension, min, max) == Placement::boundary)
        open.push_back(std::abs(edge));
  }
  std::sort(open.begin(), open.end());
  open.erase(std::unique(open.begin(), open.end()), open.end());
  if (!open.empty()) groups.open = gmsh::model::addPhysicalGroup(cut_dim - 1, open);
  return groups;
}

void open_cuts(int dimension, const CutGroups& groups) {
  if (groups.crack == 0) return;
  gmsh::plugin::setNumber("Crack", "Dimension", dimension - 1);
  gmsh::plugin::setNumber("Crack", "PhysicalGroup", groups.crack);
  gmsh::plugin::setNumber("Crack", "OpenBoundaryPhysicalGroup", groups.open);
  // 2D: the plane the crack lies in, to tell its two sides apart.
  gmsh::plugin::setNumber("Crack", "NormalX", 0.0);
  gmsh::plugin::setNumber("Crack", "NormalY", 0.0);
  gmsh::plugin::setNumber("Crack", "NormalZ", 1.0);
  gmsh::plugin::run("Crack");
}

}  // namespace kerf
