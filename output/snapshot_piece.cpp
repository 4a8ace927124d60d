#include "output/snapshot_piece.h"

#include "core/check.h"

namespace kerf {
namespace {

constexpr Index unused = -1;

/// Each point's index in the piece (`unused` for points no piece cell uses).
std::vector<Index> piece_point_numbers(const BodySnapshot& whole, Index first_entry, Index end_entry) {
  std::vector<Index> number(whole.points.size(), unused);
  for (Index k = first_entry; k < end_entry; ++k) number[whole.connectivity[k]] = 0;
  Index next = 0;
  for (Index& n : number)
    if (n != unused) n = next++;
  return number;
}

}  // namespace

BodySnapshot snapshot_piece(const BodySnapshot& whole, std::pair<Index, Index> cells, int rank) {
  const auto [begin, end] = cells;
  KERF_CHECK(0 <= begin && begin <= end && end <= static_cast<Index>(whole.cell_types.size()), "cells [", begin,
             ", ", end, ") are not within the snapshot's ", whole.cell_types.size());
  const Index first_entry = begin == 0 ? 0 : whole.offsets[begin - 1];
  const Index end_entry = begin == end ? first_entry : whole.offsets[end - 1];
  const std::vector<Index> number = piece_point_numbers(whole, first_entry, end_entry);

  BodySnapshot piece;
  for (std::size_t p = 0; p < whole.points.size(); ++p)
    if (number[p] != unused) piece.points.push_back(whole.points[p]);
  for (Index k = first_entry; k < end_entry; ++k) piece.connectivity.push_back(number[whole.connectivity[k]]);
  for (Index c = begin; c < end; ++c) piece.offsets.push_back(whole.offsets[c] - first_entry);
  piece.cell_types.assign(whole.cell_types.begin() + begin, whole.cell_types.begin() + end);

  for (const OutputField& field : whole.point_fields) {
    OutputField& cut = piece.point_fields.emplace_back(OutputField{field.name, field.components, {}});
    for (std::size_t p = 0; p < whole.points.size(); ++p)
      if (number[p] != unused)
        cut.values.insert(cut.values.end(), field.values.begin() + p * field.components,
                          field.values.begin() + (p + 1) * field.components);
  }
  for (const OutputField& field : whole.cell_fields)
    piece.cell_fields.push_back(OutputField{field.name, field.components,
                                            {field.values.begin() + begin * field.components,
                                             field.values.begin() + end * field.components}});
  piece.cell_fields.push_back(OutputField{"rank", 1, std::vector<double>(end - begin, rank)});
  return piece;
}

}  // namespace kerf
