#include "geometry/msh_content.h"

#include <limits>

#include "core/check.h"
#include "geometry/msh_sections.h"

namespace kerf {
namespace msh {

int read_int(MshCursor& in, const Encoding& e, const char* what) {
  if (e.binary) return in.binary<std::int32_t>(what);
  const std::size_t at = in.next_item(false);
  const std::int64_t value = in.integer(what);
  if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max())
    in.fail_value(at, std::string(what) + " (an int)", std::to_string(value));
  return static_cast<int>(value);
}

std::uint64_t read_count(MshCursor& in, const Encoding& e, std::size_t min_bytes, const char* what) {
  std::uint64_t count = 0;
  if (e.binary) {
    count = in.binary_size(e.size_bytes, what);
  } else {
    const std::size_t at = in.next_item(false);
    const std::int64_t value = in.integer(what);
    if (value < 0) in.fail_value(at, std::string(what) + " (a count, not negative)", std::to_string(value));
    count = static_cast<std::uint64_t>(value);
  }
  in.check_count(count, min_bytes, what);
  return count;
}

}  // namespace msh

namespace {

/// The header after "$MeshFormat": its version (nullopt for one gmsh reads alone) and encoding.
std::optional<msh::Encoding> read_format(MshCursor& in, int& major) {
  const std::string_view version = in.token("the format version (4.1 or 2.2)");
  const std::size_t at = in.next_item(false);
  const std::int64_t file_type = in.integer("the file type (0: ASCII, 1: binary)");
  const std::int64_t size_bytes = in.integer("the data size (bytes of a size_t)");
  if (file_type != 0 && file_type != 1)
    in.fail_value(at, "the file type 0 (ASCII) or 1 (binary)", std::to_string(file_type));
  msh::Encoding e{file_type == 1, static_cast<int>(size_bytes)};
  if (version == "4.1") {
    major = 4;
  } else if (version == "2.2") {
    major = 2;
  } else {
    return std::nullopt;
  }
  if (e.binary) {
    if (size_bytes != 4 && size_bytes != 8) return std::nullopt;
    in.end_of_line("the end of the format line");
    if (in.binary<std::int32_t>("the binary one that gives the byte order") != 1) return std::nullopt;
  }
  in.expect_line("$EndMeshFormat");
  return e;
}

/// One section from its opening line; false when the file is left to gmsh.
bool read_section(MshCursor& in, std::string_view name, int major, const msh::Encoding& e, msh::Entities& entities,
                  const MshCellRequest& request, MshContent& content) {
  if (name == "PartitionedEntities" || name == "ParametricNodes") return false;
  if (major == 4 && name == "Entities") {
    msh::read_entities_4(in, e, entities);
  } else if (name == "Nodes") {
    if (major == 4)
      msh::read_nodes_4(in, e, entities, content);
    else
      msh::read_nodes_2(in, e, content);
  } else if (name == "Elements") {
    const bool read = major == 4 ? msh::read_elements_4(in, e, entities, request, content)
                                 : msh::read_elements_2(in, e, request, content);
    if (!read) return false;
  } else {
    in.skip_section(name);
    return true;
  }
  in.expect_line(std::string("$End").append(name));
  return true;
}

}  // namespace

std::optional<MshContent> read_msh_content(const std::string& path, std::string_view bytes,
                                           const MshCellRequest& request) {
  MshCursor in(path, bytes);
  if (in.at_end() || in.line("'$MeshFormat'") != "$MeshFormat")
    throw Error(path + ":1: not a gmsh mesh: expected the first line to be '$MeshFormat', found " +
                quoted(bytes.substr(0, std::min<std::size_t>(bytes.find('\n'), 40))));
  int major = 0;
  const std::optional<msh::Encoding> encoding = read_format(in, major);
  if (!encoding) return std::nullopt;
  MshContent content;
  msh::Entities entities;
  bool has_nodes = false, has_elements = false;
  while (!in.only_space_left()) {
    const std::string_view opening = in.line("a section");
    if (opening.front() != '$')
      in.fail_value(static_cast<std::size_t>(opening.data() - bytes.data()),
                    "a section's opening line ('$Nodes', '$Elements', ...)",
                    quoted(opening.substr(0, 40)));
    const std::string name(opening.substr(1));
    if (!read_section(in, name, major, *encoding, entities, request, content)) return std::nullopt;
    has_nodes |= name == "Nodes";
    has_elements |= name == "Elements";
  }
  KERF_CHECK(has_nodes && has_elements, path, ": holds no ", has_nodes ? "$Elements" : "$Nodes",
             " section: expected a gmsh mesh with nodes and elements");
  return content;
}

}  // namespace kerf
