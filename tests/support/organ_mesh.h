#pragma once
// A curved body no lattice fits, as users bring them: an ellipsoid (semi-axes
// 35 x 25 x 15 mm about the origin) cut flat at z = -12 mm where it rests,
// meshed by gmsh into linear tetrahedra, graded along x, written as a .msh file.
#include <string>

namespace kerf::testing {

/// Writes the organ's mesh to `path` (gmsh 4.1 text): edge length `size_left`
/// (m) at x = -35 mm growing linearly to `size_right` at x = +35 mm. With
/// `order` 2 the same cells gain mid-edge nodes on the curved surface.
void write_organ_mesh(const std::string& path, double size_left, double size_right, int order = 1);

/// The organ graded 3 to 6 mm, written once per process into a folder of the
/// process's own (ctest runs tests two at a time, each in its process, and
/// output_directory empties the folder it makes); its path.
const std::string& graded_organ_file();

}  // namespace kerf::testing
