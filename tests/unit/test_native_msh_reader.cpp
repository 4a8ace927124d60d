// kerf's own .msh reader (geometry/native_msh_reader.h) against gmsh's reader
// (the gmsh module's, in its child process) on the same files: every format
// kerf reads gives gmsh's mesh exactly (nodes bit for bit, in gmsh's order;
// the same cells), on a curved graded organ and a plate with a hole, linear,
// quadratic and raised to second order; other files are left to gmsh; a
// malformed file is refused naming its line.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <sstream>

#include "core/check.h"
#include "geometry/gmsh_module.h"
#include "geometry/native_msh_reader.h"
#include "support/msh_conversion.h"
#include "support/organ_mesh.h"
#include "support/test_support.h"

namespace kerf {
namespace {

std::string text_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// Nodes compared bit for bit, cells and orders exactly.
void expect_same_mesh(const Mesh& ours, const Mesh& gmsh, const std::string& what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(ours.dimension, gmsh.dimension);
  EXPECT_EQ(ours.order, gmsh.order);
  ASSERT_EQ(ours.nodes.size(), gmsh.nodes.size());
  std::size_t differing = 0, first = 0;
  for (std::size_t i = 0; i < ours.nodes.size(); ++i)
    if (ours.nodes[i] != gmsh.nodes[i] && differing++ == 0) first = i;
  EXPECT_EQ(differing, 0u) << "first at node " << first << ": " << ours.nodes[first].transpose() << " against "
                           << gmsh.nodes[first].transpose();
  EXPECT_TRUE(ours.cells == gmsh.cells) << "the cells differ";
}

/// Both readers on `path`, at both orders asked.
void expect_gmshs_mesh(const std::string& path, int dimension, int expected_file_order) {
  for (MshOrder order : {MshOrder::as_in_file, MshOrder::second}) {
    int ours_order = 0, gmsh_order = 0;
    const std::optional<Mesh> ours = read_msh_without_gmsh(path, dimension, order, &ours_order);
    ASSERT_TRUE(ours) << path << ": left to gmsh";
    const Mesh gmsh = gmsh_module().read_msh(path, dimension, order, &gmsh_order);
    expect_same_mesh(*ours, gmsh, path + (order == MshOrder::second ? ", second order" : ", as in the file"));
    EXPECT_EQ(ours_order, expected_file_order);
    EXPECT_EQ(gmsh_order, expected_file_order);
  }
}

TEST(NativeMshReader, GivesGmshsMeshInEveryFormatItReads) {
  const std::string dir = testing::output_directory("NativeMshReader_formats");
  struct Source {
    std::string name;
    int dimension, order;
  };
  const Source sources[] = {{"organ1", 3, 1}, {"organ2", 3, 2}, {"plate1", 2, 1}, {"plate2", 2, 2}};
  testing::write_organ_mesh(dir + "/organ1.msh", 0.004, 0.008, 1);
  testing::write_organ_mesh(dir + "/organ2.msh", 0.004, 0.008, 2);
  testing::write_plate_with_hole(dir + "/plate1.msh", 0.004, 1);
  testing::write_plate_with_hole(dir + "/plate2.msh", 0.004, 2);
  for (const Source& s : sources) {
    const std::string original = dir + "/" + s.name + ".msh";
    expect_gmshs_mesh(original, s.dimension, s.order);  // MSH 4.1 text
    for (auto [version, binary] : {std::pair{4.1, true}, {2.2, false}, {2.2, true}}) {
      const std::string path = dir + "/" + s.name + "_" + std::to_string(version).substr(0, 3) +
                               (binary ? "_binary" : "_text") + ".msh";
      testing::write_msh_as(original, path, version, binary);
      expect_gmshs_mesh(path, s.dimension, s.order);
    }
  }
}

/// The lines of a text file's section (between its opening line, and for
/// $Elements its count, and its closing line), and a writer putting them back.
struct SectionLines {
  std::string text;
  std::size_t start = 0, end = 0;
  std::vector<std::string> lines;
  SectionLines(const std::string& path, const std::string& name, int header_lines) : text(text_of(path)) {
    start = text.find("$" + name + "\n");
    for (int i = 0; i <= header_lines; ++i) start = text.find('\n', start) + 1;
    end = text.find("$End" + name);
    std::istringstream section(text.substr(start, end - start));
    for (std::string line; std::getline(section, line);) lines.push_back(line);
  }
  void write(const std::string& path) const {
    std::string joined;
    for (const std::string& line : lines) joined += line + "\n";
    write_text(path, std::string(text).replace(start, end - start, joined));
  }
};

// gmsh lists cells volume by volume in ascending tags. Within a volume its MSH
// 2 reader sorts them by number, its MSH 4 reader keeps the file's order.
TEST(NativeMshReader, ListsTheCellsVolumeByVolumeAsGmshDoes) {
  const std::string dir = testing::output_directory("NativeMshReader_volumes");
  testing::write_two_boxes(dir + "/boxes.msh");
  // MSH 2.2: volume 2's tetrahedra renumbered below volume 1's, volume 1's listed first, in descending numbers.
  SectionLines msh2(dir + "/boxes.msh", "Elements", 1);
  std::vector<std::vector<std::string>> others, volume[2];
  for (const std::string& line : msh2.lines) {
    std::istringstream in(line);
    std::vector<std::string> words{std::istream_iterator<std::string>(in), {}};
    (words[1] == "4" ? volume[std::stoi(words[4]) - 1] : others).push_back(words);
  }
  ASSERT_FALSE(volume[0].empty() || volume[1].empty());
  int number = 1;
  for (auto* group : {&others, &volume[1], &volume[0]})
    for (auto& words : *group) words[0] = std::to_string(number++);
  std::reverse(volume[0].begin(), volume[0].end());
  msh2.lines.clear();
  for (auto* group : {&others, &volume[0], &volume[1]})
    for (auto& words : *group) {
      std::string line;
      for (const std::string& w : words) line += (line.empty() ? "" : " ") + w;
      msh2.lines.push_back(line);
    }
  msh2.write(dir + "/renumbered.msh");
  expect_gmshs_mesh(dir + "/renumbered.msh", 3, 1);

  // MSH 4.1: volume 1's block reversed.
  testing::write_msh_as(dir + "/boxes.msh", dir + "/boxes_4.1.msh", 4.1, false);
  std::string text = text_of(dir + "/boxes_4.1.msh");
  const std::size_t header = text.find("\n3 1 4 ", text.find("$Elements")) + 1;
  const std::size_t first = text.find('\n', header) + 1;
  const long count = std::stol(text.substr(text.rfind(' ', first - 2) + 1));
  std::size_t last = first;
  for (long i = 0; i < count; ++i) last = text.find('\n', last) + 1;
  std::istringstream block(text.substr(first, last - first));
  std::vector<std::string> lines;
  for (std::string line; std::getline(block, line);) lines.push_back(line);
  std::string reversed;
  for (auto it = lines.rbegin(); it != lines.rend(); ++it) reversed += *it + "\n";
  write_text(dir + "/reversed_4.1.msh", text.replace(first, last - first, reversed));
  expect_gmshs_mesh(dir + "/reversed_4.1.msh", 3, 1);
}

TEST(NativeMshReader, LeavesOtherFilesToGmsh) {
  const std::string dir = testing::output_directory("NativeMshReader_others");
  testing::write_plate_with_hole(dir + "/plate.msh", 0.01, 1);
  testing::write_msh_as(dir + "/plate.msh", dir + "/plate_4.0.msh", 4.0, false);
  EXPECT_FALSE(read_msh_without_gmsh(dir + "/plate_4.0.msh", 2, MshOrder::as_in_file));
  expect_same_mesh(read_msh(dir + "/plate_4.0.msh", 2), read_msh(dir + "/plate.msh", 2), "MSH 4.0, through gmsh");

  // MSH 2.2 with an element listed twice (gmsh writes one per physical group).
  testing::write_msh_as(dir + "/plate.msh", dir + "/plate_2.2.msh", 2.2, false);
  std::string text = text_of(dir + "/plate_2.2.msh");
  const std::size_t end = text.find("$EndElements");
  const std::size_t last = text.rfind('\n', end - 2) + 1;
  const std::string twice = text.substr(last, end - last);
  text.insert(end, twice);
  const std::size_t count_line = text.find('\n', text.find("$Elements")) + 1;
  const std::size_t count_end = text.find('\n', count_line);
  const long count = std::stol(text.substr(count_line, count_end - count_line));
  text.replace(count_line, count_end - count_line, std::to_string(count + 1));
  write_text(dir + "/twice.msh", text);
  EXPECT_FALSE(read_msh_without_gmsh(dir + "/twice.msh", 2, MshOrder::as_in_file));
}

/// The message of reading `path`, which must fail.
std::string refusal(const std::string& path, int dimension = 2) {
  try {
    read_msh_without_gmsh(path, dimension, MshOrder::as_in_file);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " was read";
  return "";
}

/// The 1-based line of the first occurrence of `text` after `after`.
std::size_t line_of(const std::string& file, const std::string& text, const std::string& after) {
  const std::size_t at = file.find(text, file.find(after));
  return 1 + static_cast<std::size_t>(std::count(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

TEST(NativeMshReader, NamesTheLineAndTheValueOfAMalformedFile) {
  const std::string dir = testing::output_directory("NativeMshReader_malformed");
  testing::write_plate_with_hole(dir + "/plate.msh", 0.01, 1);
  const std::string good = text_of(dir + "/plate.msh");

  // A coordinate that is not a number: the first node's x (lines: the counts, a point's block header, its tag).
  std::string text = good;
  std::size_t coordinate_line = text.find("$Nodes");
  for (int i = 0; i < 4; ++i) coordinate_line = text.find('\n', coordinate_line) + 1;
  text.replace(coordinate_line, text.find(' ', coordinate_line) - coordinate_line, "0.05e");
  write_text(dir + "/bad_number.msh", text);
  const std::string message = refusal(dir + "/bad_number.msh");
  EXPECT_NE(message.find(dir + "/bad_number.msh:" + std::to_string(line_of(text, "0.05e", "$Nodes")) +
                         ": expected a node's coordinate (a finite number), found '0.05e'"),
            std::string::npos)
      << message;

  // A cell's node that $Nodes does not define.
  text = good;
  const std::size_t last_element = text.rfind('\n', text.find("$EndElements") - 2) + 1;
  const std::size_t first_node = text.find(' ', last_element) + 1;
  const std::string element = text.substr(last_element, first_node - last_element - 1);
  text.replace(first_node, text.find(' ', first_node) - first_node, "999999");
  write_text(dir + "/undefined_node.msh", text);
  EXPECT_NE(refusal(dir + "/undefined_node.msh")
                .find("undefined_node.msh: element " + element + " uses node 999999, which $Nodes does not define"),
            std::string::npos);

  // Cut off within $Elements.
  text = good.substr(0, good.find("$EndElements") - 20);
  write_text(dir + "/truncated.msh", text);
  EXPECT_NE(refusal(dir + "/truncated.msh").find("found the end of the file"), std::string::npos);

  // A node count no file of this size can hold: refused before any allocation.
  text = good;
  const std::size_t counts = text.find('\n', text.find("$Nodes")) + 1;
  const std::size_t second = text.find(' ', counts) + 1;
  text.replace(second, text.find(' ', second) - second, "900000000000000");
  write_text(dir + "/huge_count.msh", text);
  EXPECT_NE(refusal(dir + "/huge_count.msh").find("the number of nodes 900000000000000 is more than the rest"),
            std::string::npos);

  // A binary file cut within its nodes.
  testing::write_msh_as(dir + "/plate.msh", dir + "/plate_binary.msh", 4.1, true);
  const std::string binary = text_of(dir + "/plate_binary.msh");
  write_text(dir + "/binary_truncated.msh", binary.substr(0, binary.find("$EndNodes") - 100));
  EXPECT_NE(refusal(dir + "/binary_truncated.msh").find("binary_truncated.msh:"), std::string::npos);

  // A 3D mesh in a 2D scene, and a 2D one where tetrahedra are expected.
  testing::write_organ_mesh(dir + "/organ.msh", 0.008, 0.008, 1);
  EXPECT_NE(refusal(dir + "/organ.msh", 2).find("holds 3D cells (tetrahedra) but the scene is 2D"), std::string::npos);
  EXPECT_NE(refusal(dir + "/plate.msh", 3).find("holds no tetrahedra"), std::string::npos);
}

// A malformed file kerf leaves to gmsh still ends in a message: gmsh's reader
// runs in a child process (tests/malformed/meshes hold files gmsh crashes on).
TEST(GmshMshReader, ACrashOfGmshsReaderEndsInAMessage) {
  const std::string meshes = testing::source_path("tests/malformed/meshes/");
  auto gmsh_refusal = [&](const std::string& name) {
    try {
      gmsh_module().read_msh(meshes + name, 3, MshOrder::as_in_file, nullptr);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("read");
  };
  EXPECT_NE(gmsh_refusal("segfault_binary.msh").find("gmsh crashed reading this file"), std::string::npos);
  EXPECT_NE(gmsh_refusal("gmsh_bad_alloc.msh").find("gmsh could not read the mesh: std::bad_alloc"),
            std::string::npos);
}

}  // namespace
}  // namespace kerf
