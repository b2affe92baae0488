#include "mpm/grid_update.hpp"

#include <cstdint>

namespace hvi::mpm {

void update_nodes(SparseGrid& grid, bool velocity, bool increment, double dt) {
  const auto blocks = static_cast<std::int64_t>(grid.block_count());
  constexpr int S = SparseGrid::block_size;
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const auto block = static_cast<std::uint32_t>(b);
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
  }
}

void update_remapped(SparseGrid& grid) {
  const auto blocks = static_cast<std::int64_t>(grid.block_count());
  constexpr int S = SparseGrid::block_size;
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const auto block = static_cast<std::uint32_t>(b);
    const double* m = grid.values(block, node_value::mass);
    double* q = grid.values(block, node_value::q);
    for (int l = 0; l < S; ++l) {
      const double inv_m = m[l] > 0.0 ? 1.0 / m[l] : 0.0;
      for (int d = 0; d < 3; ++d) q[d * S + l] *= inv_m;
    }
  }
}

}  // namespace hvi::mpm
