#include "geometry/sampler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace hvi::geometry {

namespace {

// The largest factor of the zones containing x (1: none).
int refinement_at(const std::vector<RefinementZone>& zones, const Point& x) {
  int k = 1;
  for (const auto& z : zones)
    if (z.factor > k && z.contains(x)) k = z.factor;
  return k;
}

void push(PointSet& s, const Point& x, double volume, const Point& half_width) {
  s.position.insert(s.position.end(), x.begin(), x.end());
  s.volume.push_back(volume);
  s.half_width.insert(s.half_width.end(), half_width.begin(), half_width.end());
}

// The lattice points of `solid`, one layer of coarse cells (index k along z) per task; layers are
// joined in order, so the result does not depend on the number of threads.
PointSet sample_lattice_cells(const Solid& solid, const SamplingSettings& s, std::size_t& refined) {
  const double h = s.spacing;
  const Bounds b = solid.bounds();
  long lo[3], hi[3];  // coarse cells [anchor + i h, anchor + (i + 1) h) that overlap the bounds
  for (int d = 0; d < 3; ++d) {
    const double from = std::floor((b.lower[d] - s.anchor[d]) / h);
    const double to = std::ceil((b.upper[d] - s.anchor[d]) / h) - 1;
    if (!(to >= from)) return {};  // empty (or NaN) bounds: no points
    // A lattice index must fit its integer: bounds this far out are a mistake, not a body.
    if (!(std::abs(from) < 1e15 && std::abs(to) < 1e15))
      throw std::invalid_argument(
          "a solid reaches 1e15 lattice cells from the grid's origin: its bounds (or clip) are "
          "not finite or far outside the grid");
    lo[d] = static_cast<long>(from);
    hi[d] = static_cast<long>(to);
  }
  const long layers = std::max(0L, hi[2] - lo[2] + 1);
  std::vector<PointSet> layer(static_cast<std::size_t>(layers));
  std::vector<std::size_t> layer_refined(layer.size(), 0);
#pragma omp parallel for schedule(dynamic)
  for (long kk = 0; kk < layers; ++kk) {
    const long k = lo[2] + kk;
    PointSet& out = layer[static_cast<std::size_t>(kk)];
    for (long j = lo[1]; j <= hi[1]; ++j)
      for (long i = lo[0]; i <= hi[0]; ++i) {
        const long cell[3] = {i, j, k};
        Point centre;
        for (int d = 0; d < 3; ++d)
          centre[d] = s.anchor[d] + (static_cast<double>(cell[d]) + 0.5) * h;
        const int f = refinement_at(s.zones, centre);
        if (f == 1) {
          if (solid.contains(centre)) push(out, centre, h * h * h, {h / 2, h / 2, h / 2});
          continue;
        }
        const double hf = h / f;
        for (int c = 0; c < f; ++c)
          for (int bb = 0; bb < f; ++bb)
            for (int a = 0; a < f; ++a) {
              const int sub[3] = {a, bb, c};
              Point x;
              for (int d = 0; d < 3; ++d)
                x[d] = s.anchor[d] + (static_cast<double>(cell[d] * f + sub[d]) + 0.5) * hf;
              if (!solid.contains(x)) continue;
              push(out, x, hf * hf * hf, {hf / 2, hf / 2, hf / 2});
              ++layer_refined[static_cast<std::size_t>(kk)];
            }
      }
  }
  PointSet points;
  std::size_t total = 0;
  for (const auto& l : layer) total += l.size();
  points.reserve(total);
  for (std::size_t k = 0; k < layer.size(); ++k) {
    points.append(layer[k]);
    layer[k] = PointSet{};
    refined += layer_refined[k];
  }
  return points;
}

// One layer of points on each wall mid-surface (see sampler.hpp).
PointSet sample_walls(const std::vector<ThinWall>& walls, const SamplingSettings& s,
                      std::size_t& refined) {
  const double h = s.spacing;
  std::vector<PointSet> per_wall(walls.size());
  std::vector<std::size_t> wall_refined(walls.size(), 0);
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const ThinWall& wall = walls[w];
    const double dx = wall.b[0] - wall.a[0], dy = wall.b[1] - wall.a[1];
    const double length = std::hypot(dx, dy), height = wall.z1 - wall.z0;
    if (!(length > 0.0) || !(height > 0.0)) continue;
    // Whole numbers of points, no farther apart than h (1e-9: a length that is a whole number of
    // spacings up to round-off).
    const long nu = std::max(1L, static_cast<long>(std::ceil(length / h - 1e-9)));
    const long nz = std::max(1L, static_cast<long>(std::ceil(height / h - 1e-9)));
    const double du = length / static_cast<double>(nu), dz = height / static_cast<double>(nz);
    // Volume per unit of wall area: the trims take the junction overlaps out evenly along the wall.
    const double effective = std::max(0.0, length - wall.trim[0] - wall.trim[1]) / length;
    PointSet& out = per_wall[w];
    auto at = [&](double u, double z) -> Point {
      return {wall.a[0] + u / length * dx, wall.a[1] + u / length * dy, z};
    };
    for (long j = 0; j < nz; ++j)
      for (long i = 0; i < nu; ++i) {
        const double u0 = static_cast<double>(i) * du, z0 = wall.z0 + static_cast<double>(j) * dz;
        const int f = refinement_at(s.zones, at(u0 + du / 2, z0 + dz / 2));
        const double duf = du / f, dzf = dz / f;
        const double volume = wall.thickness * effective * duf * dzf;
        for (int b = 0; b < f; ++b)
          for (int a = 0; a < f; ++a)
            push(out, at(u0 + (a + 0.5) * duf, z0 + (b + 0.5) * dzf), volume,
                 {duf / 2, duf / 2, dzf / 2});
        if (f > 1) wall_refined[w] += static_cast<std::size_t>(f * f);
      }
  }
  PointSet points;
  std::size_t total = 0;
  for (const auto& w : per_wall) total += w.size();
  points.reserve(total);
  for (std::size_t w = 0; w < walls.size(); ++w) {
    points.append(per_wall[w]);
    per_wall[w] = PointSet{};
    refined += wall_refined[w];
  }
  return points;
}

}  // namespace

double PointSet::total_volume() const {
  // Neumaier's compensated sum: exact to about one rounding for millions of terms, so that a
  // symmetry cut halves the sampled volume to round-off of the result, not of the sum.
  double sum = 0.0, compensation = 0.0;
  for (const double x : volume) {
    const double t = sum + x;
    compensation += std::fabs(sum) >= std::fabs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  return sum + compensation;
}

void PointSet::reserve(std::size_t n) {
  position.reserve(3 * n);
  volume.reserve(n);
  half_width.reserve(3 * n);
}

void PointSet::append(const PointSet& other) {
  position.insert(position.end(), other.position.begin(), other.position.end());
  volume.insert(volume.end(), other.volume.begin(), other.volume.end());
  half_width.insert(half_width.end(), other.half_width.begin(), other.half_width.end());
}

bool RefinementZone::contains(const Point& x) const {
  if (shape == Shape::box) return box.contains(x);
  const double along = x[axis] - base[axis];
  if (along < 0.0 || along >= length) return false;
  double r2 = 0.0;
  for (int d = 0; d < 3; ++d)
    if (d != axis) r2 += (x[d] - base[d]) * (x[d] - base[d]);
  return r2 < radius * radius;
}

PointSet sample(const Solid& solid, const SamplingSettings& settings, SampleReport* report) {
  if (!(settings.spacing > 0.0)) throw std::invalid_argument("the point spacing must be positive");
  SampleReport r;
  r.exact_volume = solid.volume();
  const std::vector<ThinWall> walls = solid.walls();
  r.point_type = !walls.empty() && (settings.thin_walls == ThinWallModel::point_type ||
                                    (settings.thin_walls == ThinWallModel::automatic &&
                                     solid.wall_thickness() < 2 * settings.spacing));
  PointSet points = r.point_type ? sample_walls(walls, settings, r.refined_points)
                                 : sample_lattice_cells(solid, settings, r.refined_points);
  r.points = points.size();
  r.lattice_volume = points.total_volume();
  if (r.points == 0 || !(r.lattice_volume > 0.0))
    throw std::invalid_argument(
        is_empty(solid.bounds())
            ? "nothing of the solid lies inside the clip box"
            : "the solid contains no lattice point: it is thinner than the point spacing");
  const double scale = r.exact_volume / r.lattice_volume;
  for (double& v : points.volume) v *= scale;
  if (report) *report = r;
  return points;
}

}  // namespace hvi::geometry
