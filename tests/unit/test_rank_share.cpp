// Which rank's even part holds an item: the inverse of even_part, for every
// item of splits with and without a remainder, and with fewer items than ranks.
#include <gtest/gtest.h>

#include "core/rank_share.h"

namespace kerf {
namespace {

TEST(RankShare, EvenPartOwnerIsTheRankWhosePartHoldsTheItem) {
  for (Index n : {0, 1, 3, 7, 12, 100, 101})
    for (int count : {1, 2, 3, 4, 7})
      for (int rank = 0; rank < count; ++rank) {
        const auto [begin, end] = even_part(n, rank, count);
        for (Index i = begin; i < end; ++i)
          EXPECT_EQ(even_part_owner(n, i, count), rank) << "item " << i << " of " << n << " on " << count << " ranks";
      }
}

}  // namespace
}  // namespace kerf
