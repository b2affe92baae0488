// The partition of a run's 2 x 2 x 2 block groups among ranks (mpm/partition.hpp): Morton codes
// against the bit-by-bit interleave, the octants of an even cube, and on random loads every group
// on one rank, pieces contiguous along the curve, each rank within W / N + max w of the points.
#include <algorithm>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "mpm/grid.hpp"
#include "mpm/partition.hpp"

namespace hvi::mpm {
namespace {

std::uint64_t interleaved(int x, int y, int z) {
  std::uint64_t code = 0;
  for (int bit = 0; bit < 21; ++bit) {
    code |= static_cast<std::uint64_t>((x >> bit) & 1) << (3 * bit);
    code |= static_cast<std::uint64_t>((y >> bit) & 1) << (3 * bit + 1);
    code |= static_cast<std::uint64_t>((z >> bit) & 1) << (3 * bit + 2);
  }
  return code;
}

TEST(Partition, MortonCodeInterleavesTheCoordinates) {
  EXPECT_EQ(morton_code(SparseGrid::block_key(1, 0, 0)), 1u);
  EXPECT_EQ(morton_code(SparseGrid::block_key(0, 1, 0)), 2u);
  EXPECT_EQ(morton_code(SparseGrid::block_key(0, 0, 1)), 4u);
  EXPECT_EQ(morton_code(SparseGrid::block_key(3, 5, 7)), interleaved(3, 5, 7));
  std::mt19937 random(7);
  std::uniform_int_distribution<int> coordinate(0, (1 << 21) - 1);
  for (int k = 0; k < 1000; ++k) {
    const int x = coordinate(random), y = coordinate(random), z = coordinate(random);
    ASSERT_EQ(morton_code(SparseGrid::block_key(x, y, z)), interleaved(x, y, z));
  }
}

// 8 x 8 x 8 groups of equal points on 8 ranks: each rank holds one 4 x 4 x 4 octant, the
// octants in Morton order.
TEST(Partition, AnEvenCubeGoesOctantByOctant) {
  std::vector<GroupLoad> groups;
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) groups.push_back({SparseGrid::block_key(x, y, z), 100});
  const Partition partition(groups, 8);
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        ASSERT_EQ(partition.rank_of(SparseGrid::block_key(x, y, z)),
                  (x / 4) | ((y / 4) << 1) | ((z / 4) << 2));
  EXPECT_EQ(points_per_rank(partition, groups), std::vector<std::uint64_t>(8, 6400));
  EXPECT_EQ(imbalance(points_per_rank(partition, groups)), 0.0);
}

// 5,000 groups at random places with 0 to 1,000 points each.
TEST(Partition, RandomLoadsStayWithinTheBound) {
  std::mt19937 random(2026);
  std::uniform_int_distribution<int> coordinate(0, 63);
  std::uniform_int_distribution<std::uint64_t> points(0, 1000);
  std::set<std::uint64_t> keys;
  while (keys.size() < 5000)
    keys.insert(SparseGrid::block_key(coordinate(random), coordinate(random), coordinate(random)));
  std::vector<GroupLoad> groups;
  std::uint64_t total = 0, most = 0;
  for (const auto k : keys) {
    groups.push_back({k, points(random)});
    total += groups.back().points;
    most = std::max(most, groups.back().points);
  }
  std::vector<GroupLoad> along = groups;
  std::sort(along.begin(), along.end(),
            [](const auto& a, const auto& b) { return morton_code(a.key) < morton_code(b.key); });
  for (const int ranks : {1, 2, 3, 7, 64, 4999, 6000}) {
    SCOPED_TRACE(std::to_string(ranks) + " ranks");
    const Partition partition(groups, ranks);
    ASSERT_EQ(partition.ranks(), ranks);
    int last = 0;
    for (const auto& g : along) {  // one piece per rank, in rank order along the curve
      const int r = partition.rank_of(g.key);
      ASSERT_GE(r, last);
      ASSERT_LT(r, ranks);
      last = r;
    }
    const auto per_rank = points_per_rank(partition, groups);
    std::uint64_t sum = 0, heaviest = 0;
    for (const auto p : per_rank) {
      sum += p;
      heaviest = std::max(heaviest, p);
    }
    EXPECT_EQ(sum, total);
    EXPECT_LE(static_cast<double>(heaviest),
              static_cast<double>(total) / ranks + static_cast<double>(most));
    EXPECT_LE(imbalance(per_rank),
              static_cast<double>(ranks) * static_cast<double>(most) / static_cast<double>(total) +
                  1e-12);
  }
}

TEST(Partition, MoreRanksThanGroupsAndOneRank) {
  const std::vector<GroupLoad> groups{{SparseGrid::block_key(0, 0, 0), 10},
                                      {SparseGrid::block_key(5, 1, 0), 10},
                                      {SparseGrid::block_key(2, 2, 2), 10}};
  const Partition partition(groups, 5);
  std::set<int> used;
  for (const auto& g : groups) used.insert(partition.rank_of(g.key));
  EXPECT_EQ(used.size(), 3u);  // each group alone on a rank; two ranks hold nothing
  for (const int r : used) EXPECT_LT(r, 5);
  EXPECT_EQ(Partition().rank_of(SparseGrid::block_key(9, 9, 9)), 0);
  EXPECT_THROW(Partition(groups, 0), std::invalid_argument);
}

TEST(Partition, RebalancesPastTheTolerance) {
  EXPECT_FALSE(needs_rebalance({100, 100}));
  EXPECT_FALSE(needs_rebalance({105, 95}));  // 5% above the mean
  EXPECT_TRUE(needs_rebalance({112, 88}));   // 12%
  EXPECT_FALSE(needs_rebalance({112, 88}, 0.15));
  EXPECT_DOUBLE_EQ(imbalance({300, 0, 0}), 2.0);
}

}  // namespace
}  // namespace hvi::mpm
