#pragma once
// The background grid: a uniform lattice of cubic cells of edge h over a box (the domain), stored
// sparsely in blocks of 4x4x4 nodes that exist only near particles (and near nodes a coupled model
// asks for). Memory therefore grows with the material, not with the box. The grid is rebuilt every
// step, as MPM discards the deformed grid (paper Sec. 2.3, step 7).
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "mpm/types.hpp"

namespace hvi::mpm {

struct GridGeometry {
  Vec3 origin{};               // position of node (0, 0, 0), the lower corner of the domain
  double cell_size = 1.0;      // h, m
  std::array<int, 3> cells{};  // cells per axis; nodes run 0..cells[d]
  Vec3 upper() const;
  // True if x lies in the domain [origin, upper) on every axis.
  bool contains(const double* x) const;
};

// The values of a grid node. The vectors change meaning during a step:
//   after particles_to_grid: p = momentum (kg m/s), f = force (N)
//   after update_grid:       p = velocity at the start of the step v_n (m/s),
//                            f = velocity increment dt f / m over the step (m/s)
//   q: the MUSL remap, momentum of the updated particle velocities, then their nodal velocity
// A block stores each of them as an array of its 64 nodes (structure of arrays), so a pass reads
// and writes only the components it uses, four nodes of a row at a time.
namespace node_value {
constexpr int mass = 0, p = 1, f = 4, q = 7, count = 10;  // first component of each
constexpr int block_size = 64;
}  // namespace node_value

// One node: a view of its values in its block's arrays (T = double, or const double).
template <class T>
struct NodeView {
  struct Vector {
    T* at;
    T& operator[](int d) const { return at[d * node_value::block_size]; }
  };
  explicit NodeView(T* first)
      : mass(first[node_value::mass * node_value::block_size]),
        p{first + node_value::p * node_value::block_size},
        f{first + node_value::f * node_value::block_size},
        q{first + node_value::q * node_value::block_size} {}
  T& mass;
  Vector p, f, q;
};
using GridNode = NodeView<double>;
using ConstGridNode = NodeView<const double>;

class SparseGrid {
 public:
  static constexpr int block_edge = 4;
  static constexpr int block_size = block_edge * block_edge * block_edge;
  static_assert(block_size == node_value::block_size);
  static constexpr int block_values = node_value::count * block_size;  // doubles a block stores
  // Node indices are shifted by one block so that stencils of particles at the lower domain faces
  // (GIMP reaches one node below) have non-negative block coordinates.
  static constexpr int index_shift = block_edge;
  static constexpr std::uint32_t none = 0xffffffffu;

  explicit SparseGrid(const GridGeometry& geometry);
  const GridGeometry& geometry() const { return geometry_; }

  static std::uint64_t block_key(int bx, int by, int bz) {
    return static_cast<std::uint64_t>(bx) | (static_cast<std::uint64_t>(by) << 21) |
           (static_cast<std::uint64_t>(bz) << 42);
  }
  static std::array<int, 3> block_coords(std::uint64_t key) {
    constexpr std::uint64_t m = (1u << 21) - 1;
    return {static_cast<int>(key & m), static_cast<int>((key >> 21) & m),
            static_cast<int>((key >> 42) & m)};
  }
  // Key of the block holding global node (i, j, k).
  static std::uint64_t key_of_node(int i, int j, int k) {
    return block_key((i + index_shift) / block_edge, (j + index_shift) / block_edge,
                     (k + index_shift) / block_edge);
  }

  // Starts a new step: forgets all blocks.
  void clear();
  // Index of the block with this key, creating it if needed.
  std::uint32_t activate(std::uint64_t key);
  // Index of the block with this key, or `none`.
  std::uint32_t find(std::uint64_t key) const;
  // Sizes node storage for the active blocks and zeroes it.
  void allocate_nodes();

  std::size_t block_count() const { return keys_.size(); }
  std::uint64_t key(std::uint32_t block) const { return keys_[block]; }
  // Component c (node_value) of block b's 64 nodes, x fastest (local_node()).
  double* values(std::uint32_t b, int c) {
    return values_.data() + static_cast<std::size_t>(b) * block_values + c * block_size;
  }
  const double* values(std::uint32_t b, int c) const {
    return values_.data() + static_cast<std::size_t>(b) * block_values + c * block_size;
  }
  // Node `local` (local_node()) of block b.
  GridNode node(std::uint32_t b, int local) { return GridNode(values(b, 0) + local); }
  ConstGridNode node(std::uint32_t b, int local) const {
    return ConstGridNode(values(b, 0) + local);
  }
  // Global index of the first node of block b on each axis.
  std::array<int, 3> block_origin(std::uint32_t b) const;
  // Node (i, j, k) if its block is active.
  std::optional<GridNode> node(int i, int j, int k);
  std::optional<ConstGridNode> node(int i, int j, int k) const;

  std::size_t bytes() const;

 private:
  void grow_table();
  GridGeometry geometry_;
  std::vector<std::uint64_t> keys_;  // block index -> key
  std::vector<double> values_;       // block-major, block_values per block
  // Open-addressing hash table key -> block index (linear probing, power-of-two capacity).
  std::vector<std::uint64_t> table_keys_;
  std::vector<std::uint32_t> table_values_;
};

// Local index of node (lx, ly, lz) inside its block.
inline int local_node(int lx, int ly, int lz) {
  return (lz * SparseGrid::block_edge + ly) * SparseGrid::block_edge + lx;
}

}  // namespace hvi::mpm
