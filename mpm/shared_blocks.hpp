#pragma once
// The blocks of grid nodes a rank shares with other ranks, in a run spread over ranks
// (solver_ranks.cpp): blocks that groups of more than one rank write. In a pass that adds to the
// nodes, what this rank's groups add to a shared block is kept apart, per colour, instead of being
// added to the nodes (group_sums.hpp); the ranks sharing the block send each other these sums, and
// each then sets the block's nodes to
//   n_I = ((0 + G_I^colour 0) + G_I^colour 1) + ... ,
// the sum one rank forms (at most one group of each colour writes a block, and it is on one
// rank): every copy of a shared node holds the one-rank bits, and nothing needs to go back before
// the gather. (A group's sums start from +0.0 and so are never -0.0: adding the zeros of a row a
// group did not write changes no bit.)
#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "mpm/grid.hpp"

namespace hvi::mpm {

struct SharedBlocks {
  static constexpr int colours = 8;
  static constexpr int S = SparseGrid::block_size;
  // Where component c of grid block b's 64 nodes live in the array a pass adds to (the grid's
  // values, the node average's sums).
  using Target = std::function<double*(std::uint32_t b, int c)>;
  // Set by the solver: after a pass that added `components` per node, exchanges the shared
  // blocks' sums with the other ranks and sets each shared block's nodes in `target` to the
  // colour-ordered sum (solver_ranks.cpp). Every rank calls it after the same passes.
  std::function<void(int components, const Target& target)> combine;

  std::vector<std::uint32_t> slot;      // per grid block: its slot, or SparseGrid::none
  std::vector<std::uint32_t> block;     // per slot: the grid block
  std::vector<std::vector<int>> ranks;  // per slot: the other ranks whose groups write it
  int components = 0;                   // of the pass under way
  std::vector<double> local, remote;    // slot x colour x component x 64 nodes
  std::vector<std::uint8_t> has_local, has_remote;  // slot x colour

  std::size_t count() const { return block.size(); }
  // Before a pass that adds `c` components per node: no colour written yet.
  void start(int c) {
    components = c;
    const std::size_t values = count() * colours * static_cast<std::size_t>(c) * S;
    if (local.size() < values) local.resize(values);
    if (remote.size() < values) remote.resize(values);
    has_local.assign(count() * colours, 0);
    has_remote.assign(count() * colours, 0);
  }
  // Where colour k's group puts its sums of component c of grid block b, or nullptr for a block
  // this rank alone writes. Zeroes the colour's sums on first use (one group, so one thread, per
  // block and colour).
  double* capture(std::uint32_t b, int k, int c) {
    if (b >= slot.size() || slot[b] == SparseGrid::none) return nullptr;
    const std::size_t at =
        static_cast<std::size_t>(slot[b]) * colours + static_cast<std::size_t>(k);
    double* sums = local.data() + at * static_cast<std::size_t>(components) * S;
    if (!has_local[at]) {
      std::fill_n(sums, components * S, 0.0);
      has_local[at] = 1;
    }
    return sums + c * S;
  }
};

}  // namespace hvi::mpm
