#include "geometry/msh_cursor.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "core/check.h"

namespace kerf {
namespace {

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t' || c == '\f' || c == '\v'; }

/// The word at `position` (at most 40 characters), unprintable bytes as '?'.
std::string shown(std::string_view bytes, std::size_t position) {
  if (position >= bytes.size()) return "the end of the file";
  std::string text;
  for (std::size_t i = position; i < bytes.size() && text.size() < 40 && !is_space(bytes[i]); ++i)
    text += (bytes[i] >= 32 && bytes[i] < 127) ? bytes[i] : '?';
  return quoted(text);
}

}  // namespace

std::string quoted(std::string_view text) {
  std::string q(1, '\'');
  q.append(text).push_back('\'');
  return q;
}

std::size_t MshCursor::line_number(std::size_t position) const {
  const std::size_t end = std::min(position, bytes_.size());
  const auto newlines = std::count(bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(end), '\n');
  return 1 + static_cast<std::size_t>(newlines);
}

void MshCursor::fail_at(std::size_t position, const std::string& expected) const {
  throw Error(path_ + ":" + std::to_string(line_number(position)) + ": expected " + expected + ", found " +
              shown(bytes_, position));
}

void MshCursor::fail_value(std::size_t position, const std::string& expected, const std::string& found) const {
  throw Error(path_ + ":" + std::to_string(line_number(position)) + ": expected " + expected + ", found " + found);
}

void MshCursor::fail(const std::string& expected) const { fail_at(position_, expected); }

void MshCursor::need(std::size_t count, const char* what) const {
  if (count > remaining()) fail_at(position_, std::string(what) + " (" + std::to_string(count) + " bytes)");
}

void MshCursor::skip_space() {
  while (position_ < bytes_.size() && is_space(bytes_[position_])) ++position_;
}

std::string_view MshCursor::line(const char* what) {
  skip_space();
  if (at_end()) fail(what);
  const std::size_t start = position_;
  const std::size_t end = std::min(bytes_.find('\n', start), bytes_.size());
  position_ = std::min(end + 1, bytes_.size());
  std::size_t stop = end;
  while (stop > start && is_space(bytes_[stop - 1])) --stop;
  return bytes_.substr(start, stop - start);
}

std::string_view MshCursor::token(const char* what) {
  skip_space();
  if (at_end()) fail(what);
  const std::size_t start = position_;
  while (position_ < bytes_.size() && !is_space(bytes_[position_])) ++position_;
  return bytes_.substr(start, position_ - start);
}

std::int64_t MshCursor::integer(const char* what) {
  const std::size_t start = (skip_space(), position_);
  const std::string_view text = token(what);
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) fail_at(start, std::string(what) + " (a whole number)");
  return value;
}

double MshCursor::real(const char* what) {
  const std::size_t start = (skip_space(), position_);
  const std::string_view text = token(what);
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    fail_at(start, std::string(what) + " (a finite number)");
  return value;
}

void MshCursor::end_of_line(const char* what) {
  while (position_ < bytes_.size() && bytes_[position_] != '\n' && is_space(bytes_[position_])) ++position_;
  if (at_end() || bytes_[position_] != '\n') fail(what);
  ++position_;
}

void MshCursor::expect_line(std::string_view text) {
  const std::size_t start = (skip_space(), position_);
  if (at_end() || line("") != text) fail_at(start, quoted(text));
}

void MshCursor::skip_section(std::string_view name) {
  const std::string end = std::string("$End").append(name);
  for (std::size_t at = bytes_.find(end, position_); at != std::string_view::npos; at = bytes_.find(end, at + 1)) {
    const bool starts_line = at == 0 || bytes_[at - 1] == '\n';
    const std::size_t after = at + end.size();
    if (starts_line && (after == bytes_.size() || is_space(bytes_[after]))) {
      position_ = after;
      return;
    }
  }
  fail(quoted(end).append(" to close $").append(name));
}

std::uint64_t MshCursor::binary_size(int size_bytes, const char* what) {
  if (size_bytes == 4) return binary<std::uint32_t>(what);
  return binary<std::uint64_t>(what);
}

void MshCursor::binary_block(void* out, std::size_t count, std::size_t bytes_each, const char* what) {
  if (bytes_each != 0 && count > remaining() / bytes_each) fail(what);
  const std::size_t bytes = count * bytes_each;
  if (out) std::memcpy(out, bytes_.data() + position_, bytes);
  position_ += bytes;
}

void MshCursor::check_count(std::uint64_t count, std::size_t bytes_each, const char* what) const {
  if (bytes_each != 0 && count > remaining() / bytes_each)
    throw Error(path_ + ":" + std::to_string(line_number(position_)) + ": " + what + " " + std::to_string(count) +
                " is more than the rest of the file (" + std::to_string(remaining()) +
                " bytes) can hold: is it cut short?");
}

}  // namespace kerf
