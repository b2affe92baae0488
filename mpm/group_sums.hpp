#pragma once
// What one 2 x 2 x 2 group of owner blocks adds to the nodes in a pass that scatters, summed from
// zero before it is added (particle_bins.hpp): a node receives
//   n_I = ((0 + G_I^colour 0) + G_I^colour 1) + ... ,   G_I = (0 + a_I) + b_I + ... ,
// a, b, ... the patches of the group's owner blocks by key. Each G_I is a function of the group's
// points alone, so a process that holds some of a node's groups and one that holds the others
// can send each other their G_I per colour and add them in this order to the same bits as one
// process (the ghost exchange of a run over several ranks).
//
// The group's points reach the 3 x 3 x 3 blocks from its first one (reach block r = x + 3 y + 9 z).
// A block's sums are kept by rows of 4 nodes along x (16 rows a block): a row is zeroed when the
// group first writes it, and only the rows written are added to the grid once the group is done.
#include <array>
#include <cstdint>
#include <vector>

#include "mpm/grid.hpp"
#include "mpm/simd.hpp"

namespace hvi::mpm {

class GroupSums {
 public:
  static constexpr int reach_blocks = 27;
  static constexpr int S = SparseGrid::block_size;

  // Starts a group whose pass adds `components` arrays of 64 nodes per block.
  void begin(int components) {
    components_ = components;
    const std::size_t size = static_cast<std::size_t>(reach_blocks * components * S);
    if (data_.size() < size) data_.resize(size);
    for (const int r : touched_) {
      on_[static_cast<std::size_t>(r)] = false;
      rows_[static_cast<std::size_t>(r)] = 0;
    }
    touched_.clear();
  }
  // Reach block r is the grid's block b.
  void touch(int r, std::uint32_t b) {
    const auto k = static_cast<std::size_t>(r);
    if (on_[k]) return;
    on_[k] = true;
    block_[k] = b;
    touched_.push_back(r);
  }
  // Before the first write to the row of 4 nodes from local node l of reach block r: zeroes it.
  void open_row(int r, int l) {
    const auto bit = static_cast<std::uint16_t>(1u << (l >> 2));
    auto& rows = rows_[static_cast<std::size_t>(r)];
    if (rows & bit) return;
    rows = static_cast<std::uint16_t>(rows | bit);
    for (int c = 0; c < components_; ++c) simd::store<4>(at(r, c) + l, simd::d4{});
  }
  // Component c of reach block r: 64 nodes in the grid's local order.
  double* at(int r, int c) {
    return data_.data() + (static_cast<std::size_t>(r) * static_cast<std::size_t>(components_) +
                           static_cast<std::size_t>(c)) *
                              S;
  }
  // Adds every written row to target(b, c), the grid's 64 nodes of component c of block b. Each
  // node once: the order of the rows does not matter.
  template <class Target>
  void flush(Target&& target) {
    for (const int r : touched_) {
      const std::uint16_t rows = rows_[static_cast<std::size_t>(r)];
      for (int c = 0; c < components_; ++c) {
        double* to = target(block_[static_cast<std::size_t>(r)], c);
        const double* from = at(r, c);
        for (int j = 0; j < S / 4; ++j)
          if (rows & (1u << j))
            simd::store<4>(to + 4 * j, simd::load<4>(to + 4 * j) + simd::load<4>(from + 4 * j));
      }
    }
  }

 private:
  int components_ = 0;
  std::vector<double> data_;
  std::array<bool, reach_blocks> on_{};             // listed in touched_
  std::array<std::uint16_t, reach_blocks> rows_{};  // rows written, one bit each
  std::array<std::uint32_t, reach_blocks> block_{};
  std::vector<int> touched_;
};

}  // namespace hvi::mpm
