#pragma once
// What a run spread over ranks sends between them: whole points (every field that outlives a
// step, so a point that migrates or is copied as a ghost is the same point on its new rank), the
// groups' loads for the partition, and exact sums.
#include <cstdint>
#include <span>
#include <vector>

#include "mpm/communicator.hpp"
#include "mpm/exact_sum.hpp"
#include "mpm/particles.hpp"
#include "mpm/partition.hpp"

namespace hvi::mpm {

// The points `which` (indices into `particles`), every non-scratch field, as doubles: a signature
// of the fields, then per point the real fields by name, then the integer fields (their bits) by
// name. No points: an empty message.
std::vector<double> pack_points(const Particles& particles, std::span<const std::uint32_t> which);
// Appends points packed by pack_points() on a rank whose particles declare the same fields (in
// any order); throws std::logic_error if they differ.
void append_points(Particles& particles, std::span<const double> packed);

// Every rank's group loads (any order, a group possibly on several ranks), summed per group, by
// key.
std::vector<GroupLoad> global_loads(Communicator& comm, const std::vector<GroupLoad>& mine);

// Adds each rank's sums[k] into sums[k] on every rank: the exact totals over all ranks.
void add_over_ranks(Communicator& comm, std::span<ExactSum> sums);

// The key of the 2 x 2 x 2 group holding the block with this key.
std::uint64_t group_of_block(std::uint64_t block_key);

}  // namespace hvi::mpm
