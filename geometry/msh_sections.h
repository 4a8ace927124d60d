#pragma once
// Inside kerf's .msh reader (geometry/msh_content.cpp dispatches): the
// sections of each format version, read from just after their opening line
// to just before their closing one.
#include <set>
#include <utility>

#include "geometry/msh_content.h"
#include "geometry/msh_cursor.h"

namespace kerf::msh {

/// The header's file type and data size (bytes of a size_t in binary files).
struct Encoding {
  bool binary = false;
  int size_bytes = 8;
};

/// The entities $Entities declares, as (dimension, tag); `declared` false
/// when the file has no $Entities (then any entity is taken).
struct Entities {
  bool declared = false;
  std::set<std::pair<int, int>> known;
  bool has(int dimension, int tag) const { return !declared || known.count({dimension, tag}) > 0; }
};

// MSH 4.1
void read_entities_4(MshCursor& in, const Encoding& e, Entities& entities);
void read_nodes_4(MshCursor& in, const Encoding& e, const Entities& entities, MshContent& content);
/// false: an element type outside the table (the file is left to gmsh).
bool read_elements_4(MshCursor& in, const Encoding& e, const Entities& entities, const MshCellRequest& request,
                     MshContent& content);

// MSH 2.2
void read_nodes_2(MshCursor& in, const Encoding& e, MshContent& content);
/// false: a file left to gmsh (an unknown type, no elementary tag).
bool read_elements_2(MshCursor& in, const Encoding& e, const MshCellRequest& request, MshContent& content);

/// An int read as text or binary (entity dimensions and tags, element types).
int read_int(MshCursor& in, const Encoding& e, const char* what);

/// A count read as text or binary, refused when negative or larger than the
/// rest of the file can hold at `min_bytes` bytes an item.
std::uint64_t read_count(MshCursor& in, const Encoding& e, std::size_t min_bytes, const char* what);

}  // namespace kerf::msh
