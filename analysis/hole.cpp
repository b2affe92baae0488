#include "analysis/hole.hpp"

#include <cmath>
#include <limits>

namespace hvi::analysis {

Hole find_hole(const Raster& r, double x0, double y0) {
  Hole hole;
  hole.inside.assign(r.material.size(), 0);
  const auto [i0, j0] = r.pixel_of(x0, y0);
  if (!r.contains(i0, j0)) {  // the impact point is off the sheet altogether
    hole.perforated = hole.open = true;
    return hole;
  }
  if (r.material[r.index(i0, j0)]) return hole;
  hole.perforated = true;
  // Flood fill over empty pixels.
  std::vector<std::array<int, 2>> stack{{i0, j0}};
  hole.inside[r.index(i0, j0)] = 1;
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    ++hole.pixels;
    if (i == 0 || j == 0 || i == r.nx - 1 || j == r.ny - 1) hole.open = true;
    for (const auto& [di, dj] :
         {std::array{1, 0}, std::array{-1, 0}, std::array{0, 1}, std::array{0, -1}}) {
      const int a = i + di, b = j + dj;
      if (!r.contains(a, b)) continue;
      const std::size_t k = r.index(a, b);
      if (r.material[k] || hole.inside[k]) continue;
      hole.inside[k] = 1;
      stack.push_back({a, b});
    }
  }
  hole.area = static_cast<double>(hole.pixels) * r.cell * r.cell;
  return hole;
}

double distance_to_boundary(const Raster& r, const Hole& hole, double x0, double y0, double theta,
                            bool* reached_border) {
  if (reached_border) *reached_border = false;
  auto [i, j] = r.pixel_of(x0, y0);
  if (!r.contains(i, j) || !hole.inside[r.index(i, j)]) return 0.0;
  const double inf = std::numeric_limits<double>::infinity();
  // Pixel coordinates: u = (x - x0_raster) / cell. The ray is u(t) = u0 + t (cos, sin), t in cells.
  const double u = (x0 - r.x0) / r.cell, v = (y0 - r.y0) / r.cell;
  const double c = std::cos(theta), s = std::sin(theta);
  // Directions within round-off of an axis run exactly along it (theta = 90 deg has cos ~ 6e-17).
  const double dx = std::abs(c) < 1e-12 ? 0.0 : c, dy = std::abs(s) < 1e-12 ? 0.0 : s;
  const int step_i = dx > 0 ? 1 : -1, step_j = dy > 0 ? 1 : -1;
  // t at which the ray crosses the next pixel edge along each axis, and the t between edges.
  double t_next_i = dx == 0 ? inf : ((dx > 0 ? std::floor(u) + 1 : std::floor(u)) - u) / dx;
  double t_next_j = dy == 0 ? inf : ((dy > 0 ? std::floor(v) + 1 : std::floor(v)) - v) / dy;
  const double t_step_i = dx == 0 ? inf : 1.0 / std::abs(dx),
               t_step_j = dy == 0 ? inf : 1.0 / std::abs(dy);
  for (;;) {
    double t;
    if (t_next_i < t_next_j) {
      t = t_next_i;
      t_next_i += t_step_i;
      i += step_i;
    } else {
      t = t_next_j;
      t_next_j += t_step_j;
      j += step_j;
    }
    if (!r.contains(i, j)) {
      if (reached_border) *reached_border = true;
      return t * r.cell;
    }
    if (!hole.inside[r.index(i, j)]) return t * r.cell;
  }
}

}  // namespace hvi::analysis
