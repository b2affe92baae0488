#include "mpm/partition.hpp"

#include <algorithm>
#include <stdexcept>

#include "mpm/grid.hpp"

namespace hvi::mpm {

namespace {

// The 21 low bits of v spread to every third bit.
std::uint64_t spread(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | (v << 32)) & 0x1f00000000ffffULL;
  v = (v | (v << 16)) & 0x1f0000ff0000ffULL;
  v = (v | (v << 8)) & 0x100f00f00f00f00fULL;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ULL;
  v = (v | (v << 2)) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

std::uint64_t morton_code(std::uint64_t group_key) {
  const auto c = SparseGrid::block_coords(group_key);
  return spread(static_cast<std::uint64_t>(c[0])) |
         (spread(static_cast<std::uint64_t>(c[1])) << 1) |
         (spread(static_cast<std::uint64_t>(c[2])) << 2);
}

Partition::Partition(const std::vector<GroupLoad>& groups, int ranks) {
  if (ranks < 1) throw std::invalid_argument("a partition needs at least one rank");
  struct Along {
    std::uint64_t code, points;
  };
  std::vector<Along> curve;
  curve.reserve(groups.size());
  std::uint64_t total = 0;
  for (const auto& g : groups) {
    curve.push_back({morton_code(g.key), g.points});
    total += g.points;
  }
  std::sort(curve.begin(), curve.end(),
            [](const Along& a, const Along& b) { return a.code < b.code; });
  first_.assign(static_cast<std::size_t>(ranks), 0);
  // Rank r's piece starts at the first group whose midpoint reaches r W / N (in integers: twice
  // the midpoint times N against 2 r W), and runs to the next rank's start.
  const auto n = static_cast<unsigned __int128>(ranks);
  std::size_t g = 0;
  std::uint64_t before = 0;
  for (int r = 1; r < ranks; ++r) {
    const unsigned __int128 target = 2 * static_cast<unsigned __int128>(r) * total;
    while (g < curve.size() &&
           (2 * static_cast<unsigned __int128>(before) + curve[g].points) * n < target) {
      before += curve[g].points;
      ++g;
    }
    // Past the last group: this rank and the ones after it start beyond every code in use.
    first_[static_cast<std::size_t>(r)] = g < curve.size() ? curve[g].code : ~std::uint64_t{0};
  }
}

int Partition::rank_of(std::uint64_t group_key) const {
  const std::uint64_t code = morton_code(group_key);
  // The last rank whose piece starts at or before the code.
  const auto it = std::upper_bound(first_.begin() + 1, first_.end(), code);
  return static_cast<int>(it - first_.begin()) - 1;
}

std::vector<std::uint64_t> points_per_rank(const Partition& partition,
                                           const std::vector<GroupLoad>& groups) {
  std::vector<std::uint64_t> points(static_cast<std::size_t>(partition.ranks()), 0);
  for (const auto& g : groups)
    points[static_cast<std::size_t>(partition.rank_of(g.key))] += g.points;
  return points;
}

double imbalance(const std::vector<std::uint64_t>& points_per_rank) {
  if (points_per_rank.empty()) return 0.0;
  std::uint64_t total = 0, most = 0;
  for (const auto p : points_per_rank) {
    total += p;
    most = std::max(most, p);
  }
  if (total == 0) return 0.0;
  return static_cast<double>(most) * static_cast<double>(points_per_rank.size()) /
             static_cast<double>(total) -
         1.0;
}

bool needs_rebalance(const std::vector<std::uint64_t>& points_per_rank, double tolerance) {
  return imbalance(points_per_rank) > tolerance;
}

}  // namespace hvi::mpm
