#include "cases/run/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <sys/resource.h>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "cases/run/bodies.hpp"

namespace hvi::driver {

namespace {

double box_volume(const geometry::Bounds& b) {
  double v = 1.0;
  for (int d = 0; d < 3; ++d) v *= std::max(0.0, b.upper[d] - b.lower[d]);
  return v;
}

geometry::Bounds overlap(const geometry::Bounds& a, const geometry::Bounds& b) {
  geometry::Bounds o;
  for (int d = 0; d < 3; ++d) {
    o.lower[d] = std::max(a.lower[d], b.lower[d]);
    o.upper[d] = std::min(a.upper[d], b.upper[d]);
  }
  return o;
}

// A refinement zone's box (a cylinder's bounding box).
geometry::Bounds zone_box(const geometry::RefinementZone& z) {
  if (z.shape == geometry::RefinementZone::Shape::box) return z.box;
  geometry::Bounds b;
  for (int d = 0; d < 3; ++d) {
    b.lower[d] = z.base[d] - (d == z.axis ? 0.0 : z.radius);
    b.upper[d] = z.base[d] + (d == z.axis ? z.length : z.radius);
  }
  return b;
}

std::string bytes_text(double bytes) {
  return fmt::format("{:.3g} GB", bytes / 1e9);
}

}  // namespace

double estimated_points(const scene::Scene& scene, std::size_t body, const geometry::Solid& solid) {
  const geometry::SamplingSettings s = sampling_settings(scene, body);
  const double h = s.spacing;
  double volume = solid.volume();
  // A wall thinner than the spacing is sampled one layer across: as if it were h thick.
  for (const auto& wall : solid.walls())
    if (wall.thickness < h)
      volume += std::hypot(wall.b[0] - wall.a[0], wall.b[1] - wall.a[1]) * (wall.z1 - wall.z0) *
                (h - wall.thickness);
  const double points = volume / (h * h * h);
  const geometry::Bounds bounds = solid.bounds();
  const double whole = box_volume(bounds);
  double refined = 0.0;
  for (const auto& z : s.zones)
    if (whole > 0)
      refined += points * (std::pow(z.factor, 3) - 1.0) *
                 (box_volume(overlap(bounds, zone_box(z))) / whole);
  return points + refined;
}

namespace {

// The first number of the line of `file` that starts with `key` (the whole file with key ""),
// times `unit`; NaN if there is none.
double number_in(const char* file, const std::string& key, double unit) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(key, 0) == 0) {
      std::istringstream words(line.substr(key.size()));
      double value = NAN;
      words >> value;
      return words ? value * unit : NAN;  // "max" (no limit) reads as nothing
    }
  return NAN;
}

}  // namespace

MemoryLimit available_memory() {
  MemoryLimit least;
  const auto consider = [&](double bytes, const char* what) {
    if (std::isfinite(bytes) && (least.bytes <= 0 || bytes < least.bytes))
      least = {std::max(bytes, 1.0), what};
  };
  consider(number_in("/proc/meminfo", "MemAvailable:", 1024.0),
           "the memory this machine has available");
  rlimit as{};
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
    consider(static_cast<double>(as.rlim_cur) - number_in("/proc/self/status", "VmSize:", 1024.0),
             "what the address-space limit (ulimit -v) leaves");
  consider(number_in("/sys/fs/cgroup/memory.max", "", 1.0) -
               number_in("/sys/fs/cgroup/memory.current", "", 1.0),
           "what this job's memory limit (cgroup memory.max) leaves");
  const double v1 = number_in("/sys/fs/cgroup/memory/memory.limit_in_bytes", "", 1.0);
  if (v1 < 1e18)  // v1 writes its "no limit" as a huge number
    consider(v1 - number_in("/sys/fs/cgroup/memory/memory.usage_in_bytes", "", 1.0),
             "what this job's memory limit (cgroup memory.limit_in_bytes) leaves");
  return least;
}

void check_memory(const scene::Scene& scene,
                  const std::vector<std::unique_ptr<geometry::Solid>>& solids, double limit,
                  int ranks) {
  const bool machine = limit <= 0;
  const MemoryLimit available = machine ? available_memory() : MemoryLimit{limit, "--max-memory"};
  limit = available.bytes;
  if (limit <= 0) return;  // nothing known to hold it against
  double points = 0, largest = 0;
  std::size_t which = 0;
  for (std::size_t b = 0; b < solids.size(); ++b) {
    const double n = estimated_points(scene, b, *solids[b]);
    points += n;
    if (n > largest) largest = n, which = b;
  }
  const double bytes = points * bytes_per_point / ranks;  // a rank's share
  if (bytes <= limit) return;
  const scene::BodySettings& body = scene.bodies[which];
  throw std::invalid_argument(fmt::format(
      "the bodies would hold about {:.3g} points, about {}{} at {:.0f} bytes a point, above {} "
      "({}); "
      "the largest is '{}' with {:.3g} points at a spacing of grid.cell_size {:.3g} m over "
      "particles_per_cell {}{}: raise the cell size or lower the particles per cell",
      points, bytes_text(bytes), ranks > 1 ? fmt::format(" on each of {} ranks", ranks) : "",
      bytes_per_point, bytes_text(limit), available.what, body.name, largest, scene.grid.cell_size,
      body.particles_per_cell, scene.refinements.empty() ? "" : " and the [[refinement]] factors"));
}

}  // namespace hvi::driver
