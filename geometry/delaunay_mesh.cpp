#include "geometry/delaunay_mesh.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include "core/check.h"

namespace kerf {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// The finite simplices of a triangulation whose vertices carry their point index.
template <class Triangulation, class Simplices>
void collect(const Triangulation& triangulation, Simplices simplices, int corners, std::size_t points, Mesh& mesh) {
  KERF_CHECK(triangulation.number_of_vertices() == points,
             "Delaunay triangulation: ", points - triangulation.number_of_vertices(), " of the ", points,
             " nodes coincide with others; expected distinct nodes");
  for (auto simplex : simplices)
    for (int k = 0; k < corners; ++k) mesh.cells.push_back(simplex->vertex(k)->info());
  orient_cells(mesh);
}

template <class Point, class Triangulation>
Mesh triangulate(std::span<const Vec3> points, int dimension) {
  std::vector<std::pair<Point, Index>> input;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if constexpr (Point::Ambient_dimension::value == 3)
      input.emplace_back(Point(points[i].x(), points[i].y(), points[i].z()), static_cast<Index>(i));
    else
      input.emplace_back(Point(points[i].x(), points[i].y()), static_cast<Index>(i));
  }
  Triangulation triangulation(input.begin(), input.end());
  Mesh mesh;
  mesh.dimension = dimension;
  mesh.nodes.assign(points.begin(), points.end());
  if constexpr (Point::Ambient_dimension::value == 3)
    collect(triangulation, triangulation.finite_cell_handles(), 4, points.size(), mesh);
  else
    collect(triangulation, triangulation.finite_face_handles(), 3, points.size(), mesh);
  return mesh;
}

}  // namespace

Mesh delaunay_mesh(std::span<const Vec3> points, int dimension) {
  using Vertex2 = CGAL::Triangulation_vertex_base_with_info_2<Index, Kernel>;
  using Delaunay2 = CGAL::Delaunay_triangulation_2<Kernel, CGAL::Triangulation_data_structure_2<Vertex2>>;
  using Vertex3 = CGAL::Triangulation_vertex_base_with_info_3<Index, Kernel>;
  using Data3 = CGAL::Triangulation_data_structure_3<Vertex3, CGAL::Delaunay_triangulation_cell_base_3<Kernel>>;
  using Delaunay3 = CGAL::Delaunay_triangulation_3<Kernel, Data3>;
  return dimension == 3 ? triangulate<Kernel::Point_3, Delaunay3>(points, 3)
                        : triangulate<Kernel::Point_2, Delaunay2>(points, 2);
}

}  // namespace kerf
