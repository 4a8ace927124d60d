// MSH 4.1's $Entities, $Nodes and $Elements (gmsh's "MSH file format"
// reference): in binary files, counts and tags are size_t of the header's data
// size, entity dimensions, tags and element types are int, coordinates double.
#include <cmath>

#include "geometry/gmsh_element_sizes.h"
#include "geometry/msh_sections.h"

namespace kerf::msh {
namespace {

std::uint64_t read_tag(MshCursor& in, const Encoding& e, const char* what) {
  if (e.binary) return in.binary_size(e.size_bytes, what);
  const std::size_t at = in.next_item(false);
  const std::int64_t value = in.integer(what);
  if (value <= 0) in.fail_value(at, std::string(what) + " (a tag, 1 or more)", std::to_string(value));
  return static_cast<std::uint64_t>(value);
}

double read_real(MshCursor& in, const Encoding& e, const char* what) {
  if (!e.binary) return in.real(what);
  const std::size_t at = in.next_item(true);
  const double value = in.binary<double>(what);
  if (!std::isfinite(value)) in.fail_value(at, std::string(what) + " (a finite number)", std::to_string(value));
  return value;
}

/// Skips `count` ints (physical tags, bounding entities).
void skip_ints(MshCursor& in, const Encoding& e, std::uint64_t count, const char* what) {
  for (std::uint64_t i = 0; i < count; ++i) read_int(in, e, what);
}

/// A block's header: the entity (dimension, tag), then an int (parametric or type) and the count.
struct BlockHeader {
  int dimension, tag, kind;
  std::uint64_t count;
};

BlockHeader read_block_header(MshCursor& in, const Encoding& e, const Entities& entities, std::size_t min_bytes,
                              const char* kind_name) {
  BlockHeader h{};
  const std::size_t at = in.next_item(e.binary);
  h.dimension = read_int(in, e, "a block's entity dimension (0 to 3)");
  if (h.dimension < 0 || h.dimension > 3)
    in.fail_value(at, "a block's entity dimension (0 to 3)", std::to_string(h.dimension));
  h.tag = read_int(in, e, "a block's entity tag");
  if (!entities.has(h.dimension, h.tag))
    in.fail_value(at, "a block of an entity that $Entities declares",
                  "dimension " + std::to_string(h.dimension) + ", tag " + std::to_string(h.tag));
  h.kind = read_int(in, e, kind_name);
  h.count = read_count(in, e, min_bytes, "a block's number of items");
  return h;
}

}  // namespace

void read_entities_4(MshCursor& in, const Encoding& e, Entities& entities) {
  std::uint64_t counts[4];
  for (auto& count : counts) count = read_count(in, e, 4, "a number of entities");
  for (int dimension = 0; dimension < 4; ++dimension)
    for (std::uint64_t i = 0; i < counts[dimension]; ++i) {
      const int tag = read_int(in, e, "an entity's tag");
      for (int k = 0; k < (dimension == 0 ? 3 : 6); ++k) read_real(in, e, "an entity's coordinate or bounding box");
      skip_ints(in, e, read_count(in, e, 4, "an entity's number of physical tags"), "a physical tag");
      if (dimension > 0) skip_ints(in, e, read_count(in, e, 4, "an entity's number of bounding entities"),
                                   "a bounding entity's tag");
      entities.known.insert({dimension, tag});
    }
  entities.declared = true;
}

void read_nodes_4(MshCursor& in, const Encoding& e, const Entities& entities, MshContent& content) {
  const std::uint64_t blocks = read_count(in, e, 4, "the number of node blocks");
  const std::uint64_t total = read_count(in, e, e.binary ? 32 : 8, "the number of nodes");
  read_count(in, e, 0, "the smallest node tag");
  read_count(in, e, 0, "the largest node tag");
  content.node_tags.reserve(content.node_tags.size() + total);
  content.coordinates.reserve(content.coordinates.size() + 3 * total);
  std::uint64_t read = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::size_t at = in.next_item(e.binary);
    const BlockHeader h = read_block_header(in, e, entities, e.binary ? 32 : 8, "a node block's parametric flag");
    if (h.kind != 0 && h.kind != 1)
      in.fail_value(at, "a node block's parametric flag (0 or 1)", std::to_string(h.kind));
    const int parameters = h.kind == 1 ? h.dimension : 0;
    for (std::uint64_t i = 0; i < h.count; ++i) content.node_tags.push_back(read_tag(in, e, "a node tag"));
    for (std::uint64_t i = 0; i < h.count; ++i) {
      for (int k = 0; k < 3; ++k) content.coordinates.push_back(read_real(in, e, "a node's coordinate"));
      for (int k = 0; k < parameters; ++k) read_real(in, e, "a node's parametric coordinate");
    }
    read += h.count;
  }
  if (read != total)
    in.fail_value(in.next_item(e.binary), "as many nodes in the blocks as the header's " + std::to_string(total),
                  std::to_string(read));
}

bool read_elements_4(MshCursor& in, const Encoding& e, const Entities& entities, const MshCellRequest& request,
                     MshContent& content) {
  const std::uint64_t blocks = read_count(in, e, 4, "the number of element blocks");
  read_count(in, e, e.binary ? 16 : 4, "the number of elements");
  read_count(in, e, 0, "the smallest element tag");
  read_count(in, e, 0, "the largest element tag");
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const BlockHeader h = read_block_header(in, e, entities, e.binary ? 16 : 4, "an element type");
    const auto size = gmsh_element_size(h.kind);
    if (!size) return false;
    const std::size_t tag_bytes = e.binary ? static_cast<std::size_t>(e.size_bytes) : 2;  // "1 " at least
    in.check_count(h.count, tag_bytes * static_cast<std::size_t>(1 + size->nodes), "a block's number of elements");
    if (h.dimension == 3 && h.count > 0) content.has_volume_elements = true;
    const bool kept = h.dimension == request.dimension && (h.kind == request.types[0] || h.kind == request.types[1]);
    MshElementBlock* block = nullptr;
    if (kept) {
      block = &content.blocks.emplace_back();
      block->entity_tag = h.tag;
      block->type = h.kind;
      block->element_tags.reserve(h.count);
      block->node_tags.reserve(h.count * static_cast<std::uint64_t>(size->nodes));
    }
    for (std::uint64_t i = 0; i < h.count; ++i) {
      const std::uint64_t tag = read_tag(in, e, "an element tag");
      if (block) block->element_tags.push_back(tag);
      for (int k = 0; k < size->nodes; ++k) {
        const std::uint64_t node = read_tag(in, e, "an element's node tag");
        if (block) block->node_tags.push_back(node);
      }
    }
  }
  return true;
}

}  // namespace kerf::msh
