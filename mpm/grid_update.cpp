#include "mpm/grid_update.hpp"

#include <cstdint>

namespace hvi::mpm {

void update_nodes(SparseGrid& grid, bool velocity, bool increment, double dt) {
  const auto nodes = grid.nodes();
  const auto count = static_cast<std::int64_t>(grid.block_count() * SparseGrid::block_size);
  GridNode* n = nodes.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    GridNode& node = n[i];
    if (node.mass > 0.0) {
      const double inv_m = 1.0 / node.mass;
      if (velocity)
        for (int d = 0; d < 3; ++d) node.p[d] *= inv_m;
      if (increment)
        for (int d = 0; d < 3; ++d) node.f[d] *= dt * inv_m;
    } else {
      for (int d = 0; d < 3; ++d) node.p[d] = node.f[d] = node.q[d] = 0.0;
    }
  }
}

void update_remapped(SparseGrid& grid) {
  const auto count = static_cast<std::int64_t>(grid.block_count() * SparseGrid::block_size);
  GridNode* n = grid.nodes().data();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    GridNode& node = n[i];
    const double inv_m = node.mass > 0.0 ? 1.0 / node.mass : 0.0;
    for (int d = 0; d < 3; ++d) node.q[d] *= inv_m;
  }
}

}  // namespace hvi::mpm
