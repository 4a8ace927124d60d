#pragma once
// A read position in the bytes of a .msh file, for kerf's own reader
// (geometry/msh_content.h): ASCII tokens and binary values, each read naming
// what it expects, so that a malformed file ends in a kerf::Error that says
// the file, the line, what was expected and what was found.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace kerf {

/// `text` between single quotes. (Built by appending: GCC 12 warns falsely
/// of an overlapping memcpy (-Wrestrict) on "literal" + std::string.)
std::string quoted(std::string_view text);

class MshCursor {
 public:
  MshCursor(std::string path, std::string_view bytes) : path_(std::move(path)), bytes_(bytes) {}

  bool at_end() const { return position_ >= bytes_.size(); }
  /// Moves past white space; true when nothing else is left.
  bool only_space_left() {
    skip_space();
    return at_end();
  }
  std::size_t remaining() const { return bytes_.size() - position_; }
  const std::string& path() const { return path_; }

  /// The next line without its end (\n or \r\n); blank lines are skipped.
  std::string_view line(const char* what);
  /// The next token separated by white space (within or across lines).
  std::string_view token(const char* what);
  /// The next token as a whole number or a real number.
  std::int64_t integer(const char* what);
  double real(const char* what);
  /// Moves past the rest of this line, which must be blank, and its end
  /// (before the binary data that follows a text line).
  void end_of_line(const char* what);
  /// Skips white space; then the next line must be `text`.
  void expect_line(std::string_view text);
  /// Moves past the line `$End<name>` (a section kerf does not read).
  void skip_section(std::string_view name);

  /// Binary values of the file's byte order (checked by the caller).
  template <class T>
  T binary(const char* what) {
    T value;
    need(sizeof value, what);
    std::memcpy(&value, bytes_.data() + position_, sizeof value);
    position_ += sizeof value;
    return value;
  }
  /// An unsigned count of `size_bytes` bytes (the header's data size: 4 or 8).
  std::uint64_t binary_size(int size_bytes, const char* what);
  /// Copies `count` values of `bytes_each` bytes; skips them when `out` is null.
  void binary_block(void* out, std::size_t count, std::size_t bytes_each, const char* what);

  /// Refuses a count that the rest of the file cannot hold at `bytes_each`
  /// bytes an item (before anything is allocated for it).
  void check_count(std::uint64_t count, std::size_t bytes_each, const char* what) const;

  /// Where the next item starts (past white space in a text file): a value's
  /// place for fail_value once it is read.
  std::size_t next_item(bool binary) {
    if (!binary) skip_space();
    return position_;
  }
  /// Throws kerf::Error: "<path>:<line>: expected <expected>, found <found>", at `position`.
  [[noreturn]] void fail_value(std::size_t position, const std::string& expected, const std::string& found) const;

  /// Throws kerf::Error: "<path>:<line>: expected <expected>, found '<...>'".
  [[noreturn]] void fail(const std::string& expected) const;
  [[noreturn]] void fail_at(std::size_t position, const std::string& expected) const;

 private:
  void need(std::size_t count, const char* what) const;
  void skip_space();
  std::size_t line_number(std::size_t position) const;

  std::string path_;
  std::string_view bytes_;
  std::size_t position_ = 0;
};

}  // namespace kerf
