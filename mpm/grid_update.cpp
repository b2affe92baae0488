#include "mpm/grid_update.hpp"

#include <cstdint>

namespace hvi::mpm {

namespace {

constexpr int S = SparseGrid::block_size;

// Runs `kernel(block)` on every block of the grid, the blocks shared among the threads.
template <class Kernel>
void for_each_block(SparseGrid& grid, const Kernel& kernel) {
  const auto blocks = static_cast<std::int64_t>(grid.block_count());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) kernel(static_cast<std::uint32_t>(b));
}

}  // namespace

void update_nodes(SparseGrid& grid, bool velocity, bool increment, double dt) {
  for_each_block(grid, [&](std::uint32_t block) {
    const double* m = grid.values(block, node_value::mass);
    double* p = grid.values(block, node_value::p);
    double* f = grid.values(block, node_value::f);
    double* q = grid.values(block, node_value::q);
    // Branch-free, so the loop runs on whole vectors: a node without mass gets zeros.
    for (int l = 0; l < S; ++l) {
      const bool has_mass = m[l] > 0.0;
      const double inv_m = has_mass ? 1.0 / m[l] : 0.0;
      for (int d = 0; d < 3; ++d) {
        if (velocity) p[d * S + l] = has_mass ? p[d * S + l] * inv_m : 0.0;
        if (increment) f[d * S + l] = has_mass ? f[d * S + l] * (dt * inv_m) : 0.0;
        if (!velocity) p[d * S + l] = has_mass ? p[d * S + l] : 0.0;
        if (!increment) f[d * S + l] = has_mass ? f[d * S + l] : 0.0;
        q[d * S + l] = has_mass ? q[d * S + l] : 0.0;
      }
    }
  });
}

void update_remapped(SparseGrid& grid) {
  for_each_block(grid, [&](std::uint32_t block) {
    const double* m = grid.values(block, node_value::mass);
    double* q = grid.values(block, node_value::q);
    for (int l = 0; l < S; ++l) {
      const double inv_m = m[l] > 0.0 ? 1.0 / m[l] : 0.0;
      for (int d = 0; d < 3; ++d) q[d * S + l] *= inv_m;
    }
  });
}

}  // namespace hvi::mpm
