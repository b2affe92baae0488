#include "analysis/top_view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace hvi::analysis {

std::array<int, 2> Raster::pixel_of(double x, double y) const {
  return {static_cast<int>(std::floor((x - x0) / cell)),
          static_cast<int>(std::floor((y - y0) / cell))};
}

std::array<double, 2> footprint_half_width(const ParticleSet& set, std::size_t p,
                                           const TopViewOptions& options) {
  if (!set.half_width.empty()) return {set.half_width[3 * p], set.half_width[3 * p + 1]};
  const double h = set.spacing.empty() ? options.spacing : set.spacing[p];
  return {h / 2, h / 2};
}

namespace {

// Pixels [lo, hi] whose centres x0 + (i + 1/2) cell lie in the half-open interval [a, b).
std::array<int, 2> covered(double a, double b, double x0, double cell) {
  return {static_cast<int>(std::ceil((a - x0) / cell - 0.5)),
          static_cast<int>(std::ceil((b - x0) / cell - 0.5)) - 1};
}

// The pixel offsets of a disc of `radius` pixels.
std::vector<std::array<int, 2>> disc(double radius) {
  std::vector<std::array<int, 2>> out;
  const int r = static_cast<int>(std::floor(radius));
  for (int dj = -r; dj <= r; ++dj)
    for (int di = -r; di <= r; ++di)
      if (di * di + dj * dj <= radius * radius) out.push_back({di, dj});
  return out;
}

// out(i, j) = 1 when `all` (erosion) or any (dilation) of in(i + di, j + dj) over the disc is 1.
std::vector<std::uint8_t> morph(const Raster& r, const std::vector<std::uint8_t>& in,
                                const std::vector<std::array<int, 2>>& offsets, bool all) {
  std::vector<std::uint8_t> out(in.size());
#pragma omp parallel for schedule(static)
  for (int j = 0; j < r.ny; ++j)
    for (int i = 0; i < r.nx; ++i) {
      bool value = all;
      for (const auto& [di, dj] : offsets) {
        const bool m = r.contains(i + di, j + dj) && in[r.index(i + di, j + dj)];
        if (all ? !m : m) {
          value = !all;
          break;
        }
      }
      out[r.index(i, j)] = value;
    }
  return out;
}

}  // namespace

void close_material(Raster& raster, double radius) {
  if (!(radius > 0)) return;
  const auto offsets = disc(radius / raster.cell);
  raster.material = morph(raster, morph(raster, raster.material, offsets, false), offsets, true);
}

Raster top_view(const ParticleSet& set, std::span<const std::size_t> particles,
                const TopViewOptions& options) {
  if (particles.empty()) throw std::invalid_argument("top view: no particles");
  double finest = std::numeric_limits<double>::infinity();
  double lo[2] = {finest, finest}, hi[2] = {-finest, -finest};
  for (const std::size_t p : particles) {
    const auto a = footprint_half_width(set, p, options);
    if (!(a[0] > 0 && a[1] > 0))
      throw std::invalid_argument("top view: a particle has no footprint (give the point spacing)");
    finest = std::min({finest, 2 * a[0], 2 * a[1]});
    for (int d = 0; d < 2; ++d) {
      lo[d] = std::min(lo[d], set.position[3 * p + d] - a[d]);
      hi[d] = std::max(hi[d], set.position[3 * p + d] + a[d]);
    }
  }
  if (options.include)
    for (int d = 0; d < 2; ++d) {
      lo[d] = std::min(lo[d], (*options.include)[d]);
      hi[d] = std::max(hi[d], (*options.include)[d]);
    }
  Raster r;
  r.cell = options.resolution > 0 ? options.resolution : finest / 4;
  const double closing = options.gap_closing * finest;
  // An empty margin wider than the closing radius, so dilation never reaches the border.
  const int margin = static_cast<int>(std::ceil(closing / r.cell)) + 2;
  const double nx = std::ceil((hi[0] - lo[0]) / r.cell) + 2 * margin;
  const double ny = std::ceil((hi[1] - lo[1]) / r.cell) + 2 * margin;
  if (nx * ny > 1e9)
    throw std::invalid_argument(fmt::format(
        "top view: {:.0f} x {:.0f} pixels of {:.4g} mm is too many; choose a coarser resolution",
        nx, ny, r.cell * 1e3));
  r.nx = static_cast<int>(nx);
  r.ny = static_cast<int>(ny);
  r.x0 = lo[0] - margin * r.cell;
  r.y0 = lo[1] - margin * r.cell;
  r.spacing = finest;
  r.closing_radius = closing;
  r.material.assign(static_cast<std::size_t>(r.nx) * r.ny, 0);
  for (const std::size_t p : particles) {
    const auto a = footprint_half_width(set, p, options);
    const double x = set.position[3 * p], y = set.position[3 * p + 1];
    const auto [i0, i1] = covered(x - a[0], x + a[0], r.x0, r.cell);
    const auto [j0, j1] = covered(y - a[1], y + a[1], r.y0, r.cell);
    for (int j = std::max(j0, 0); j <= std::min(j1, r.ny - 1); ++j)
      for (int i = std::max(i0, 0); i <= std::min(i1, r.nx - 1); ++i) r.material[r.index(i, j)] = 1;
  }
  close_material(r, closing);
  return r;
}

}  // namespace hvi::analysis
