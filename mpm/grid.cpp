#include "mpm/grid.hpp"

#include <algorithm>
#include <cstring>
#include <utility>

namespace hvi::mpm {

Vec3 GridGeometry::upper() const {
  return {origin[0] + cells[0] * cell_size, origin[1] + cells[1] * cell_size,
          origin[2] + cells[2] * cell_size};
}

bool GridGeometry::contains(const double* x) const {
  for (int d = 0; d < 3; ++d) {
    const double s = (x[d] - origin[d]) / cell_size;
    if (!(s >= 0.0 && s < cells[d])) return false;  // also false for NaN
  }
  return true;
}

namespace {
constexpr std::uint64_t empty_key = ~std::uint64_t{0};
inline std::size_t hash_key(std::uint64_t k) {
  // 64-bit mix (a multiply-xorshift); block keys are dense in their low bits.
  k ^= k >> 31;
  k *= 0x9e3779b97f4a7c15ull;
  k ^= k >> 29;
  return static_cast<std::size_t>(k);
}
}  // namespace

SparseGrid::SparseGrid(const GridGeometry& geometry) : geometry_(geometry) {
  table_keys_.assign(1024, empty_key);
  table_values_.assign(1024, none);
}

void SparseGrid::clear() {
  keys_.clear();
  std::fill(table_keys_.begin(), table_keys_.end(), empty_key);
}

std::uint32_t SparseGrid::find(std::uint64_t key) const {
  const std::size_t mask = table_keys_.size() - 1;
  for (std::size_t slot = hash_key(key) & mask;; slot = (slot + 1) & mask) {
    if (table_keys_[slot] == key) return table_values_[slot];
    if (table_keys_[slot] == empty_key) return none;
  }
}

std::uint32_t SparseGrid::activate(std::uint64_t key) {
  if (2 * (keys_.size() + 1) > table_keys_.size()) grow_table();
  const std::size_t mask = table_keys_.size() - 1;
  for (std::size_t slot = hash_key(key) & mask;; slot = (slot + 1) & mask) {
    if (table_keys_[slot] == key) return table_values_[slot];
    if (table_keys_[slot] == empty_key) {
      const auto b = static_cast<std::uint32_t>(keys_.size());
      table_keys_[slot] = key;
      table_values_[slot] = b;
      keys_.push_back(key);
      return b;
    }
  }
}

void SparseGrid::grow_table() {
  const std::size_t capacity = table_keys_.size() * 2;
  table_keys_.assign(capacity, empty_key);
  table_values_.assign(capacity, none);
  const std::size_t mask = capacity - 1;
  for (std::uint32_t b = 0; b < keys_.size(); ++b) {
    std::size_t slot = hash_key(keys_[b]) & mask;
    while (table_keys_[slot] != empty_key) slot = (slot + 1) & mask;
    table_keys_[slot] = keys_[b];
    table_values_[slot] = b;
  }
}

void SparseGrid::allocate_nodes() {
  const std::size_t n = keys_.size() * static_cast<std::size_t>(block_values);
  if (values_.size() < n) values_.resize(n);
  // Zero in parallel: first touch also places pages near the thread that will use them.
  double* data = values_.data();
  const auto blocks = static_cast<std::int64_t>(keys_.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) std::fill_n(data + b * block_values, block_values, 0.0);
}

std::array<int, 3> SparseGrid::block_origin(std::uint32_t b) const {
  const auto c = block_coords(keys_[b]);
  return {c[0] * block_edge - index_shift, c[1] * block_edge - index_shift,
          c[2] * block_edge - index_shift};
}

std::optional<ConstGridNode> SparseGrid::node(int i, int j, int k) const {
  const std::uint32_t b = find(key_of_node(i, j, k));
  if (b == none) return std::nullopt;
  const int lx = (i + index_shift) % block_edge, ly = (j + index_shift) % block_edge,
            lz = (k + index_shift) % block_edge;
  return node(b, local_node(lx, ly, lz));
}

std::optional<GridNode> SparseGrid::node(int i, int j, int k) {
  const std::uint32_t b = find(key_of_node(i, j, k));
  if (b == none) return std::nullopt;
  const int lx = (i + index_shift) % block_edge, ly = (j + index_shift) % block_edge,
            lz = (k + index_shift) % block_edge;
  return node(b, local_node(lx, ly, lz));
}

std::size_t SparseGrid::bytes() const {
  return values_.capacity() * sizeof(double) + keys_.capacity() * sizeof(std::uint64_t) +
         table_keys_.capacity() * sizeof(std::uint64_t) +
         table_values_.capacity() * sizeof(std::uint32_t);
}

}  // namespace hvi::mpm
