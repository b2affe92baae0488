#include "geometry/lattice_sampler.hpp"

#include <cmath>
#include <stdexcept>

namespace hvi::geometry {

PointSet sample_lattice(const Solid& solid, double spacing, const Point& anchor,
                        const Bounds* clip) {
  const Bounds b = solid.bounds();
  long lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    // Lattice points are anchor + (i + 1/2) spacing.
    lo[d] = static_cast<long>(std::floor((b.lower[d] - anchor[d]) / spacing - 0.5));
    hi[d] = static_cast<long>(std::ceil((b.upper[d] - anchor[d]) / spacing - 0.5));
  }
  auto inside_clip = [clip](const Point& x) {
    if (!clip) return true;
    for (int d = 0; d < 3; ++d)
      if (x[d] < clip->lower[d] || x[d] >= clip->upper[d]) return false;
    return true;
  };
  PointSet points;
  std::size_t in_solid = 0;
  for (long k = lo[2]; k <= hi[2]; ++k)
    for (long j = lo[1]; j <= hi[1]; ++j)
      for (long i = lo[0]; i <= hi[0]; ++i) {
        const Point x = {anchor[0] + (i + 0.5) * spacing, anchor[1] + (j + 0.5) * spacing,
                         anchor[2] + (k + 0.5) * spacing};
        if (!solid.contains(x)) continue;
        ++in_solid;
        if (inside_clip(x)) points.position.insert(points.position.end(), x.begin(), x.end());
      }
  const std::size_t n = points.position.size() / 3;
  if (in_solid == 0)
    throw std::invalid_argument(
        "the solid contains no lattice point: it is thinner than the point spacing");
  if (n == 0) throw std::invalid_argument("no point of the solid lies inside the clip box");
  points.volume.assign(n, solid.volume() / static_cast<double>(in_solid));
  points.half_width.assign(3 * n, spacing / 2);
  return points;
}

}  // namespace hvi::geometry
