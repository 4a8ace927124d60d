// MSH 2.2's $Nodes and $Elements (gmsh's "MSH file format version 2"): the
// counts are text lines in binary files too; binary nodes are an int tag and
// three doubles, binary elements come in runs of one type, all ints.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "geometry/gmsh_element_sizes.h"
#include "geometry/msh_sections.h"

namespace kerf::msh {
namespace {

constexpr Encoding text{false, 8};

/// The elements' block for (entity, type): the last one if it matches, else a new one.
MshElementBlock& block_for(MshContent& content, int entity, int type) {
  if (content.blocks.empty() || content.blocks.back().entity_tag != entity || content.blocks.back().type != type) {
    MshElementBlock& block = content.blocks.emplace_back();
    block.entity_tag = entity;
    block.type = type;
  }
  return content.blocks.back();
}

/// One element after its type and tag count: false when gmsh must read the file.
bool read_element(MshCursor& in, const Encoding& e, int type, int tags, std::int64_t number,
                  const MshCellRequest& request, MshContent& content) {
  const auto size = gmsh_element_size(type);
  if (!size || tags < 2) return false;  // unknown type; no elementary entity
  const std::size_t at = in.next_item(e.binary);
  if (tags > 64) in.fail_value(at, "an element's number of tags (at most 64)", std::to_string(tags));
  if (number <= 0) in.fail_value(at, "an element number (1 or more)", std::to_string(number));
  int entity = 0;
  for (int t = 0; t < tags; ++t) {
    const int value = read_int(in, e, "an element's tag");
    if (t == 1) entity = value;
  }
  if (size->dimension == 3) content.has_volume_elements = true;
  const bool kept = size->dimension == request.dimension && (type == request.types[0] || type == request.types[1]);
  MshElementBlock* block = kept ? &block_for(content, entity, type) : nullptr;
  if (block) block->element_tags.push_back(static_cast<std::uint64_t>(number));
  for (int k = 0; k < size->nodes; ++k) {
    const std::size_t node_at = in.next_item(e.binary);
    const int node = read_int(in, e, "an element's node number");
    if (node <= 0) in.fail_value(node_at, "an element's node number (1 or more)", std::to_string(node));
    if (block) block->node_tags.push_back(static_cast<std::uint64_t>(node));
  }
  return true;
}

/// gmsh keeps each line of an element listed twice (once per physical
/// group); kerf leaves such a file to it.
bool numbers_repeat(const MshContent& content) {
  std::vector<std::uint64_t> numbers;
  for (const MshElementBlock& block : content.blocks)
    numbers.insert(numbers.end(), block.element_tags.begin(), block.element_tags.end());
  std::sort(numbers.begin(), numbers.end());
  return std::adjacent_find(numbers.begin(), numbers.end()) != numbers.end();
}

/// gmsh's MSH 2 reader keeps each entity's elements in the order of their
/// numbers, whatever the file's order (its MSH 4 reader keeps the file's).
void order_by_number(MshContent& content) {
  std::map<std::pair<int, int>, MshElementBlock> merged;  // (entity, type)
  for (MshElementBlock& block : content.blocks) {
    MshElementBlock& into = merged[{block.entity_tag, block.type}];
    into.entity_tag = block.entity_tag;
    into.type = block.type;
    into.element_tags.insert(into.element_tags.end(), block.element_tags.begin(), block.element_tags.end());
    into.node_tags.insert(into.node_tags.end(), block.node_tags.begin(), block.node_tags.end());
  }
  content.blocks.clear();
  for (auto& entry : merged) {
    const MshElementBlock& block = entry.second;  // (a structured binding cannot be captured under clang's OpenMP)
    const std::size_t count = block.element_tags.size();
    const std::size_t nodes = block.node_tags.size() / std::max<std::size_t>(count, 1);
    std::vector<std::size_t> order(count);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return block.element_tags[a] < block.element_tags[b];
    });
    MshElementBlock& sorted = content.blocks.emplace_back();
    sorted.entity_tag = block.entity_tag;
    sorted.type = block.type;
    for (std::size_t i : order) {
      sorted.element_tags.push_back(block.element_tags[i]);
      sorted.node_tags.insert(sorted.node_tags.end(), block.node_tags.begin() + static_cast<std::ptrdiff_t>(i * nodes),
                              block.node_tags.begin() + static_cast<std::ptrdiff_t>((i + 1) * nodes));
    }
  }
}

}  // namespace

void read_nodes_2(MshCursor& in, const Encoding& e, MshContent& content) {
  const std::uint64_t count = read_count(in, text, e.binary ? 28 : 8, "the number of nodes");
  if (e.binary) in.end_of_line("the end of the line of the number of nodes");
  content.node_tags.reserve(count);
  content.coordinates.reserve(3 * count);
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::size_t at = in.next_item(e.binary);
    const int tag = read_int(in, e, "a node number");
    if (tag <= 0) in.fail_value(at, "a node number (1 or more)", std::to_string(tag));
    content.node_tags.push_back(static_cast<std::uint64_t>(tag));
    for (int k = 0; k < 3; ++k) {
      const std::size_t x_at = in.next_item(e.binary);
      const double x = e.binary ? in.binary<double>("a node's coordinate") : in.real("a node's coordinate");
      if (!std::isfinite(x)) in.fail_value(x_at, "a node's coordinate (a finite number)", std::to_string(x));
      content.coordinates.push_back(x);
    }
  }
}

bool read_elements_2(MshCursor& in, const Encoding& e, const MshCellRequest& request, MshContent& content) {
  const std::uint64_t count = read_count(in, text, e.binary ? 16 : 8, "the number of elements");
  if (e.binary) in.end_of_line("the end of the line of the number of elements");
  for (std::uint64_t read = 0; read < count;) {
    if (e.binary) {
      const std::size_t at = in.next_item(true);
      const int type = read_int(in, e, "a run's element type");
      const int follow = read_int(in, e, "a run's number of elements");
      const int tags = read_int(in, e, "a run's number of tags");
      if (follow <= 0 || static_cast<std::uint64_t>(follow) > count - read)
        in.fail_value(at, "a run's number of elements (1 to the " + std::to_string(count - read) + " left)",
                      std::to_string(follow));
      for (int i = 0; i < follow; ++i)
        if (!read_element(in, e, type, tags, read_int(in, e, "an element number"), request, content)) return false;
      read += static_cast<std::uint64_t>(follow);
    } else {
      const std::int64_t number = in.integer("an element number");
      const int type = read_int(in, e, "an element type");
      if (!read_element(in, e, type, read_int(in, e, "an element's number of tags"), number, request, content))
        return false;
      ++read;
    }
  }
  if (numbers_repeat(content)) return false;
  order_by_number(content);
  return true;
}

}  // namespace kerf::msh
