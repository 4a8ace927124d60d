#pragma once
// What kerf's own .msh reader takes from a file (MSH 4.1 and 2.2, ASCII or
// binary): every node, and the elements of the cell types asked for, block by
// block as the file holds them. geometry/native_msh_reader.h makes a Mesh of it.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace kerf {

struct MshElementBlock {
  int entity_tag = 0;
  int type = 0;  // gmsh's element type
  std::vector<std::uint64_t> element_tags;
  std::vector<std::uint64_t> node_tags;  // the nodes of each element in turn
};

struct MshContent {
  std::vector<std::uint64_t> node_tags;
  std::vector<double> coordinates;  // x, y, z of each node
  /// Elements of the kept types in entities of the cells' dimension, in file order.
  std::vector<MshElementBlock> blocks;
  bool has_volume_elements = false;  // elements in a 3D entity (a 2D scene refuses them)
};

/// What the reader keeps: elements of `types` in entities of `dimension`.
struct MshCellRequest {
  int dimension = 3;
  std::array<int, 2> types{};
};

/// The file's content, or nullopt for a file left to gmsh (another version
/// than 4.1 or 2.2, a partitioned mesh, parametric nodes of MSH 2, an element
/// type outside geometry/gmsh_element_sizes.h, the other byte order, MSH 2
/// elements without an elementary entity or with repeated numbers). A
/// malformed file throws kerf::Error naming its line.
std::optional<MshContent> read_msh_content(const std::string& path, std::string_view bytes,
                                           const MshCellRequest& request);

}  // namespace kerf
