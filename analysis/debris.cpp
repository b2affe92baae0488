#include "analysis/debris.hpp"

#include <algorithm>
#include <cmath>

namespace hvi::analysis {

Debris debris_cloud(const ParticleSet& set, const DebrisOptions& o,
                    std::span<const std::size_t> excluded) {
  std::vector<std::uint8_t> skip(set.size(), 0);
  for (const std::size_t p : excluded) skip[p] = 1;
  Vec3 d = o.direction;
  const double norm = std::hypot(d[0], d[1], d[2]);
  for (double& c : d) c /= norm;
  Debris out;
  for (std::size_t p = 0; p < set.size(); ++p) {
    if (skip[p]) continue;
    const Vec3 x = set.x(p);
    const Vec3 r{x[0] - o.axis_point[0], x[1] - o.axis_point[1], x[2] - o.axis_point[2]};
    const double along = r[0] * d[0] + r[1] * d[1] + r[2] * d[2];
    const double behind = along - o.back_face;
    if (!(behind > o.threshold)) continue;
    const double across = std::hypot(r[0] - along * d[0], r[1] - along * d[1], r[2] - along * d[2]);
    ++out.particles;
    if (!set.mass.empty()) out.mass += set.mass[p];
    if (!set.mass.empty() && !set.velocity.empty()) {
      const double* v = &set.velocity[3 * p];
      out.kinetic_energy += 0.5 * set.mass[p] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    out.axial_extent = std::max(out.axial_extent, behind);
    out.radial_extent = std::max(out.radial_extent, across);
  }
  return out;
}

}  // namespace hvi::analysis
