#pragma once
// A table that describes each value of an enum once: one row per value, in
// the enum's order (core/element_types.h, core/linear_backends.h,
// problem/methods.h). The row of a value is then an index, its spelling the
// row's `name`.
#include <array>
#include <cstddef>

namespace kerf {

/// Does row i describe the enum's value i, for every row? (for a static_assert)
template <class Row, std::size_t N, class Kind>
constexpr bool rows_follow_enum(const std::array<Row, N>& rows, Kind Row::*kind) {
  for (std::size_t i = 0; i < N; ++i)
    if (static_cast<std::size_t>(rows[i].*kind) != i) return false;
  return true;
}

/// The row describing `kind`.
template <class Row, std::size_t N, class Kind>
constexpr const Row& row_of(const std::array<Row, N>& rows, Kind kind) {
  return rows[static_cast<std::size_t>(kind)];
}

/// Each row's name, in the enum's order: the scene file's spellings.
template <class Row, std::size_t N>
constexpr std::array<const char*, N> names_of(const std::array<Row, N>& rows) {
  std::array<const char*, N> spelled{};
  for (std::size_t i = 0; i < N; ++i) spelled[i] = rows[i].name;
  return spelled;
}

}  // namespace kerf
