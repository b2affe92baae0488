#include "mpm/boundary.hpp"

#include <algorithm>
#include <cstdint>

namespace hvi::mpm {

void apply_grid_conditions(SparseGrid& grid, const std::vector<GridBoundary>& conditions) {
  if (conditions.empty()) return;
  const auto blocks = static_cast<std::int64_t>(grid.block_count());
  constexpr int E = SparseGrid::block_edge;
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) {
    const auto block = static_cast<std::uint32_t>(b);
    const auto origin = grid.block_origin(block);
    for (const auto& c : conditions) {
      // Range of local indices along the axis that the condition covers.
      int lo = 0, hi = E - 1;
      if (c.outside_below)
        hi = std::min(hi, c.plane - origin[c.axis]);
      else
        lo = std::max(lo, c.plane - origin[c.axis]);
      if (lo > hi) continue;
      for (int lz = 0; lz < E; ++lz)
        for (int ly = 0; ly < E; ++ly)
          for (int lx = 0; lx < E; ++lx) {
            const int l[3] = {lx, ly, lz};
            if (l[c.axis] < lo || l[c.axis] > hi) continue;
            const GridNode n = grid.node(block, local_node(lx, ly, lz));
            if (c.type == BoundaryType::fixed) {
              for (int d = 0; d < 3; ++d) n.p[d] = n.f[d] = n.q[d] = 0.0;
            } else {
              n.p[c.axis] = n.f[c.axis] = n.q[c.axis] = 0.0;
            }
          }
    }
  }
}

std::vector<MirrorPlane> mirror_planes(const GridGeometry& geometry,
                                       const std::vector<GridBoundary>& conditions) {
  std::vector<MirrorPlane> planes;
  for (const auto& c : conditions)
    if (c.type == BoundaryType::symmetry)
      planes.push_back({c.axis, geometry.origin[c.axis] + c.plane * geometry.cell_size,
                        c.outside_below ? 1.0 : -1.0});
  return planes;
}

std::size_t reflect_at_symmetry_planes(Particles& particles, const GridGeometry& geometry,
                                       const std::vector<GridBoundary>& conditions) {
  std::size_t reflected = 0;
  const auto n = static_cast<std::int64_t>(particles.size());
  double* x = particles.position.data();
  double* v = particles.velocity.data();
  double* vg = particles.grid_velocity.data();
  for (const auto& m : mirror_planes(geometry, conditions)) {
#pragma omp parallel for schedule(static) reduction(+ : reflected)
    for (std::int64_t p = 0; p < n; ++p)
      if (reflect(m, &x[3 * p], &v[3 * p], &vg[3 * p])) ++reflected;
  }
  return reflected;
}

}  // namespace hvi::mpm
