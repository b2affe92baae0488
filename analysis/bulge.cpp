#include "analysis/bulge.hpp"

#include <cmath>
#include <limits>
#include <unordered_map>

namespace hvi::analysis {

Bulge rear_bulge(const ParticleSet& initial, const ParticleSet& current,
                 std::span<const std::size_t> particles, Vec3 direction) {
  const double norm = std::hypot(direction[0], direction[1], direction[2]);
  for (double& d : direction) d /= norm;
  std::unordered_map<std::int64_t, std::size_t> by_id;
  by_id.reserve(initial.size());
  for (std::size_t p = 0; p < initial.size(); ++p) by_id.emplace(initial.id[p], p);
  Bulge b;
  b.displacement = -std::numeric_limits<double>::infinity();
  for (const std::size_t p : particles) {
    const auto it = by_id.find(current.id[p]);
    if (it == by_id.end()) {
      ++b.unmatched;
      continue;
    }
    const Vec3 x = current.x(p), x0 = initial.x(it->second);
    const double u = (x[0] - x0[0]) * direction[0] + (x[1] - x0[1]) * direction[1] +
                     (x[2] - x0[2]) * direction[2];
    if (u > b.displacement) {
      b.displacement = u;
      b.id = current.id[p];
      b.position = x;
    }
  }
  if (b.id < 0) b.displacement = 0;
  return b;
}

}  // namespace hvi::analysis
