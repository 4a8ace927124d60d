#include "geometry/delaunay_volumes.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <cmath>

#include "core/check.h"

namespace kerf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

std::vector<double> volumes_3d(std::span<const Vec3> points) {
  using Vertex = CGAL::Triangulation_vertex_base_with_info_3<Index, Kernel>;
  using Data = CGAL::Triangulation_data_structure_3<Vertex, CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
  using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Data>;
  std::vector<std::pair<Kernel::Point_3, Index>> input;
  for (std::size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_3(points[i].x(), points[i].y(), points[i].z()), static_cast<Index>(i));
  Delaunay triangulation(input.begin(), input.end());
  KERF_CHECK(triangulation.number_of_vertices() == points.size(),
             "nodal volumes: ", points.size() - triangulation.number_of_vertices(), " of the ", points.size(),
             " nodes coincide with others; expected distinct nodes");
  std::vector<double> volume(points.size(), 0.0);
  for (auto cell = triangulation.finite_cells_begin(); cell != triangulation.finite_cells_end(); ++cell) {
    double v = std::abs(CGAL::to_double(triangulation.tetrahedron(cell).volume()));
    for (int k = 0; k < 4; ++k) volume[cell->vertex(k)->info()] += 0.25 * v;
  }
  return volume;
}

std::vector<double> areas_2d(std::span<const Vec3> points) {
  using Vertex = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
  using Data = CGAL::Triangulation_data_structure_2<Vertex>;
  using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, Data>;
  std::vector<std::pair<Kernel::Point_2, Index>> input;
  for (std::size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_2(points[i].x(), points[i].y()), static_cast<Index>(i));
  Delaunay triangulation(input.begin(), input.end());
  KERF_CHECK(triangulation.number_of_vertices() == points.size(),
             "nodal areas: ", points.size() - triangulation.number_of_vertices(), " of the ", points.size(),
             " nodes coincide with others; expected distinct nodes");
  std::vector<double> area(points.size(), 0.0);
  for (auto face = triangulation.finite_faces_begin(); face != triangulation.finite_faces_end(); ++face) {
    double a = std::abs(CGAL::to_double(triangulation.triangle(face).area()));
    for (int k = 0; k < 3; ++k) area[face->vertex(k)->info()] += a / 3.0;
  }
  return area;
}

}  // namespace

std::vector<double> delaunay_nodal_volumes(std::span<const Vec3> points, int dimension) {
  return dimension == 3 ? volumes_3d(points) : areas_2d(points);
}

}  // namespace kerf
