#pragma once
// A .msh file written again by gmsh in another of its formats, for tests of
// kerf's own reader against gmsh's on the same mesh.
#include <string>

namespace kerf::testing {

/// gmsh's current model written to `path` as MSH `version`, binary or ASCII,
/// then cleared (the options set back to text).
void write_current_model(const std::string& path, double version, bool binary);

/// gmsh reads `from` and writes it to `to` as MSH `version` (4.1, 4.0, 2.2),
/// binary or ASCII.
void write_msh_as(const std::string& from, const std::string& to, double version, bool binary);

/// gmsh meshes a 2D plate (0.1 x 0.05 m, a hole of radius 0.01 m in its
/// middle) at `size` (m) into triangles of `order` and writes it as MSH 4.1 text.
void write_plate_with_hole(const std::string& path, double size, int order);

/// gmsh meshes two boxes side by side (volumes 1 and 2, each 1 x 0.5 x 0.5,
/// conforming) into tetrahedra at 0.3 and writes them as MSH 2.2 text.
void write_two_boxes(const std::string& path);

}  // namespace kerf::testing
