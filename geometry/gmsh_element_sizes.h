#pragma once
// gmsh's element types 1-31 (GmshDefines.h): the nodes an element of each
// type lists in a .msh file and the dimension of its entity, which kerf's own
// reader needs to step over the elements it does not keep. A type outside
// this table leaves the file to gmsh's reader.
#include <array>
#include <optional>

namespace kerf {

struct GmshElementSize {
  int nodes;
  int dimension;
};

inline std::optional<GmshElementSize> gmsh_element_size(long long type) {
  // clang-format off
  static constexpr std::array<GmshElementSize, 32> sizes{{
      {0, -1},                                                   // (no type 0)
      {2, 1}, {3, 2}, {4, 2}, {4, 3}, {8, 3}, {6, 3}, {5, 3},    // 1-7: line, tri, quad, tet, hex, prism, pyramid
      {3, 1}, {6, 2}, {9, 2}, {10, 3}, {27, 3}, {18, 3}, {14, 3},  // 8-14: their second order
      {1, 0}, {8, 2}, {20, 3}, {15, 3}, {13, 3},                 // 15 point; 16-19 serendipity ones
      {9, 2}, {10, 2}, {12, 2}, {15, 2}, {15, 2}, {21, 2},       // 20-25: triangles of order 3-5
      {4, 1}, {5, 1}, {6, 1},                                    // 26-28: lines of order 3-5
      {20, 3}, {35, 3}, {56, 3}}};                               // 29-31: tetrahedra of order 3-5
  // clang-format on
  if (type < 1 || type >= static_cast<long long>(sizes.size())) return std::nullopt;
  return sizes[static_cast<std::size_t>(type)];
}

}  // namespace kerf
