#pragma once
// How a run spread over several processes (ranks) shares its points: by the 2 x 2 x 2 groups of
// owner blocks the scatter colours (particle_bins.hpp). The groups are laid along a Morton
// (Z-order) curve through their coordinates and the curve is cut into one contiguous piece per
// rank, each holding about the same number of points. A piece is given by the Morton code it
// starts at, so every rank can tell the owner of any group, also of one no point has reached yet
// (a point crossing into it migrates there), from the cuts alone.
//
// The cuts: group g, with W_g points before it along the curve and w_g of its own, goes to rank
//   r = floor((W_g + w_g / 2) N / W),   W the points of all groups, N the ranks.
// A rank's groups then have their midpoints in [r W / N, (r + 1) W / N), so it holds at most
// W / N + max_g w_g points: the imbalance (most points on a rank over the mean, less one) is at
// most N max_g w_g / W.
#include <cstdint>
#include <vector>

namespace hvi::mpm {

// A group: its key (SparseGrid::block_key of the halved block coordinates) and its points.
struct GroupLoad {
  std::uint64_t key = 0;
  std::uint64_t points = 0;
};

// The Morton code of a group key: the bits of its x, y and z coordinates interleaved, x lowest.
std::uint64_t morton_code(std::uint64_t group_key);

class Partition {
 public:
  // One rank holding every group.
  Partition() = default;
  // Cuts the curve through `groups` (any order; each key once) into `ranks` pieces.
  Partition(const std::vector<GroupLoad>& groups, int ranks);

  int ranks() const { return static_cast<int>(first_.size()); }
  // The rank holding the group with this key.
  int rank_of(std::uint64_t group_key) const;
  // The Morton code each rank's piece starts at (the first is 0; a rank whose piece is empty
  // starts where the next one does).
  const std::vector<std::uint64_t>& first_codes() const { return first_; }

 private:
  std::vector<std::uint64_t> first_{0};
};

// Points per rank of `groups` under `partition`.
std::vector<std::uint64_t> points_per_rank(const Partition& partition,
                                           const std::vector<GroupLoad>& groups);

// The most points on a rank over the mean, less one (0: perfectly even).
double imbalance(const std::vector<std::uint64_t>& points_per_rank);

// Whether the points have drifted past `tolerance` (default 10%) and the curve should be cut anew.
bool needs_rebalance(const std::vector<std::uint64_t>& points_per_rank, double tolerance = 0.1);

}  // namespace hvi::mpm
