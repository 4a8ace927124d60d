#include "geometry/native_msh_reader.h"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <unordered_map>

#include "core/check.h"
#include "geometry/mesh_from_cells.h"
#include "geometry/mid_edge_nodes.h"
#include "geometry/msh_content.h"

namespace kerf {
namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  KERF_CHECK(in, path, ": cannot open the mesh file");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Each node tag's position in the content's node list: a table by tag
/// where tags are dense, a hash map where they are not.
class NodePositions {
 public:
  NodePositions(const std::string& path, const std::vector<std::uint64_t>& tags) {
    const std::uint64_t largest = tags.empty() ? 0 : *std::max_element(tags.begin(), tags.end());
    const bool dense = largest <= 4 * tags.size() + 1024;
    if (dense) table_.assign(largest + 1, none);
    for (std::size_t i = 0; i < tags.size(); ++i) {
      std::size_t& slot = dense ? table_[tags[i]] : map_.try_emplace(tags[i], none).first->second;
      KERF_CHECK(slot == none, path, ": node ", tags[i], " is defined twice in $Nodes");
      slot = i;
    }
  }
  std::size_t operator()(std::uint64_t tag) const {
    if (!table_.empty()) return tag < table_.size() ? table_[tag] : none;
    const auto it = map_.find(tag);
    return it == map_.end() ? none : it->second;
  }
  static constexpr std::size_t none = ~std::size_t{0};

 private:
  std::vector<std::size_t> table_;
  std::unordered_map<std::uint64_t, std::size_t> map_;
};

}  // namespace

std::optional<Mesh> read_msh_without_gmsh(const std::string& path, int dimension, MshOrder order, int* file_order) {
  const std::string bytes = file_bytes(path);
  const int linear_type = element_descriptor(dimension, 1).gmsh_type;
  const int quadratic_type = element_descriptor(dimension, 2).gmsh_type;
  std::optional<MshContent> content = read_msh_content(path, bytes, {dimension, {linear_type, quadratic_type}});
  if (!content) return std::nullopt;
  bool has_linear = false, has_quadratic = false;
  for (const MshElementBlock& block : content->blocks) {
    has_linear |= block.type == linear_type && !block.element_tags.empty();
    has_quadratic |= block.type == quadratic_type && !block.element_tags.empty();
  }
  const int order_in_file = cell_order_of(path, dimension, content->has_volume_elements, has_linear, has_quadratic);
  if (file_order) *file_order = order_in_file;

  // gmsh lists the cells entity by entity, in ascending tags, each in the file's order (MSH 2's come sorted by
  // element number within an entity: msh2_sections.cpp).
  std::stable_sort(content->blocks.begin(), content->blocks.end(),
                   [](const MshElementBlock& a, const MshElementBlock& b) { return a.entity_tag < b.entity_tag; });
  const NodePositions position(path, content->node_tags);
  std::vector<std::size_t> cells;
  std::vector<std::uint64_t> element_tags;
  for (const MshElementBlock& block : content->blocks) {
    const std::size_t per_cell = block.node_tags.size() / std::max<std::size_t>(block.element_tags.size(), 1);
    for (std::size_t i = 0; i < block.node_tags.size(); ++i) {
      const std::size_t p = position(block.node_tags[i]);
      KERF_CHECK(p != NodePositions::none, path, ": element ", block.element_tags[i / per_cell], " uses node ",
                 block.node_tags[i], ", which $Nodes does not define");
      cells.push_back(p);
    }
    element_tags.insert(element_tags.end(), block.element_tags.begin(), block.element_tags.end());
  }
  content->node_tags = {};
  if (order == MshOrder::second && order_in_file == 1) {
    cells = add_mid_edge_nodes(dimension, cells, content->coordinates);
    return mesh_from_cells(path, dimension, 2, cells, content->coordinates, element_tags);
  }
  return mesh_from_cells(path, dimension, order_in_file, cells, content->coordinates, element_tags);
}

}  // namespace kerf
