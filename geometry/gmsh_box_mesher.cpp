#include "geometry/gmsh_meshing.h"

#include <gmsh.h>

#include "core/check.h"
#include "core/thread_scope.h"
#include "geometry/gmsh_cuts.h"
#include "geometry/gmsh_session.h"

namespace kerf {

Mesh gmsh_mesh_box(const BoxMeshRequest& r) {
  SingleThreadScope serial;  // gmsh meshes differently from run to run on several threads
  ensure_gmsh_initialized();
  gmsh::clear();
  gmsh::model::add("kerf_box");
  Vec3 extent = r.max - r.min;
  const int body = r.dimension == 3
                       ? gmsh::model::occ::addBox(r.min.x(), r.min.y(), r.min.z(), extent.x(), extent.y(), extent.z())
                       : gmsh::model::occ::addRectangle(r.min.x(), r.min.y(), 0.0, extent.x(), extent.y());
  CutGroups cuts;
  if (r.cuts.empty())
    gmsh::model::occ::synchronize();
  else
    try {
      cuts = embed_cuts(r.dimension, body, r.cuts, r.min, r.max);
    } catch (const std::exception& e) {
      throw Error(std::string("gmsh failed to embed the cuts in the box: ") + e.what());
    }

  // Size from fields only: the global size, and each refine box below it.
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeMax", r.size);
  gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay
  gmsh::option::setNumber("Mesh.Optimize", 1);
  if (!r.refine.empty()) {
    std::vector<double> fields;
    for (const SizeBox& b : r.refine) {
      int f = gmsh::model::mesh::field::add("Box");
      gmsh::model::mesh::field::setNumber(f, "VIn", b.size);
      gmsh::model::mesh::field::setNumber(f, "VOut", r.size);
      gmsh::model::mesh::field::setNumber(f, "XMin", b.min.x());
      gmsh::model::mesh::field::setNumber(f, "XMax", b.max.x());
      gmsh::model::mesh::field::setNumber(f, "YMin", b.min.y());
      gmsh::model::mesh::field::setNumber(f, "YMax", b.max.y());
      gmsh::model::mesh::field::setNumber(f, "ZMin", r.dimension == 3 ? b.min.z() : -1.0);
      gmsh::model::mesh::field::setNumber(f, "ZMax", r.dimension == 3 ? b.max.z() : 1.0);
      gmsh::model::mesh::field::setNumber(f, "Thickness", 2.0 * r.size);
      fields.push_back(f);
    }
    int minimum = gmsh::model::mesh::field::add("Min");
    gmsh::model::mesh::field::setNumbers(minimum, "FieldsList", fields);
    gmsh::model::mesh::field::setAsBackgroundMesh(minimum);
  }
  try {
    gmsh::model::mesh::generate(r.dimension);
    if (r.order == 2) gmsh::model::mesh::setOrder(2);
    open_cuts(r.dimension, cuts);
  } catch (const std::exception& e) {
    throw Error(std::string("gmsh failed to mesh the box: ") + e.what());
  }
  Mesh mesh;
  extract_gmsh_mesh(r.dimension, "the gmsh mesh of the box", mesh);
  gmsh::clear();
  return mesh;
}

}  // namespace kerf
