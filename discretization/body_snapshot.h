#pragma once
// What ParaView gets of a body or a cut at one instant, whatever the method:
// points, VTK cells and fields; and scalar fields on lattices (.vti).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"

namespace kerf {

/// A field written to ParaView: per point or per cell, `components` values each.
struct OutputField {
  std::string name;
  int components = 1;
  std::vector<double> values;
};

/// The body as ParaView sees it at one instant: reference points, cells with
/// VTK cell types, and fields. Points are always 3D (z = 0 in 2D).
struct BodySnapshot {
  std::vector<Vec3> points;
  std::vector<Index> connectivity;
  std::vector<Index> offsets;            // end of each cell in connectivity
  std::vector<std::uint8_t> cell_types;  // VTK cell type ids
  std::vector<OutputField> point_fields;
  std::vector<OutputField> cell_fields;
  /// This rank's piece of a body whose mesh is divided among the ranks (its
  /// own cells alone), written as it is; false: the whole body.
  bool piece = false;
};

/// A scalar field on a lattice (an Enrichment Grid's phi), for a .vti file.
struct LatticeSnapshot {
  std::string name;
  Vec3 origin = Vec3::Zero();  // m
  std::array<Vec3, 3> axes{Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};  // unit, world frame
  std::array<Index, 3> count{1, 1, 1};
  double spacing = 1.0;        // m
  std::vector<double> values;  // axis 0 fastest
};

}  // namespace kerf
