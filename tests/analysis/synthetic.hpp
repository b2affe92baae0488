#pragma once
// Synthetic facesheets for the analysis tests: a square plate in the x-y plane sampled on a cubic
// lattice of spacing h with centres at (i + 1/2) h (so the lattice is symmetric about x = 0 and
// y = 0, as a half or quarter model's cut is), with a hole of known shape.
#include <cmath>
#include <functional>
#include <limits>

#include "analysis/particle_set.hpp"

namespace hvi::analysis::test {

using Inside = std::function<bool(double, double)>;

// Particles of a plate |x|, |y| < half_size, z in [z_top - layers h, z_top]; those whose centre is
// inside `hole` are marked failed (or left out, with `remove`). Ids count from `first_id`.
inline ParticleData plate(double half_size, double h, int layers, const Inside& hole,
                          bool remove = false, std::int64_t body = 0, double z_top = 0.0,
                          std::int64_t first_id = 0, double density = 2700.0) {
  ParticleData p;
  const int n = static_cast<int>(std::round(half_size / h));
  std::int64_t id = first_id;
  for (int k = 0; k < layers; ++k)
    for (int j = -n; j < n; ++j)
      for (int i = -n; i < n; ++i) {
        const double x = (i + 0.5) * h, y = (j + 0.5) * h, z = z_top - (k + 0.5) * h;
        const bool in = hole && hole(x, y);
        if (in && remove) continue;
        p.position.insert(p.position.end(), {x, y, z});
        p.id.push_back(id++);
        p.body.push_back(body);
        p.volume.push_back(h * h * h);
        p.mass.push_back(density * h * h * h);
        p.failed.push_back(in ? 1.0 : 0.0);
        p.spacing.push_back(h);
      }
  return p;
}

// The particles of `set` with x >= 0 (if `x_half`) and y >= 0 (if `y_half`): a half or quarter
// model.
inline ParticleData cut(const ParticleSet& set, bool x_half, bool y_half) {
  ParticleData out;
  for (std::size_t p = 0; p < set.size(); ++p) {
    const Vec3 x = set.x(p);
    if ((x_half && x[0] < 0) || (y_half && x[1] < 0)) continue;
    out.position.insert(out.position.end(), x.begin(), x.end());
    out.id.push_back(set.id[p]);
    out.body.push_back(set.body[p]);
    out.volume.push_back(set.volume[p]);
    out.mass.push_back(set.mass[p]);
    out.failed.push_back(set.failed[p]);
    out.spacing.push_back(set.spacing[p]);
  }
  return out;
}

// The exact r_theta of the union of the intact particles' footprints (squares of edge h): the
// least ray parameter at which the ray from (x0, y0) enters a footprint (slab method). The raster
// is checked against it.
inline double footprint_union_distance(const ParticleSet& set, double x0, double y0, double theta) {
  const double c = std::cos(theta), s = std::sin(theta);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < set.size(); ++p) {
    if (!set.intact(p)) continue;
    const double a = set.spacing[p] / 2;
    double t0 = 0, t1 = std::numeric_limits<double>::infinity();
    const double o[2] = {x0, y0},
                 d[2] = {std::abs(c) < 1e-12 ? 0.0 : c, std::abs(s) < 1e-12 ? 0.0 : s};
    bool miss = false;
    for (int k = 0; k < 2; ++k) {
      const double lo = set.position[3 * p + k] - a, hi = set.position[3 * p + k] + a;
      if (d[k] == 0) {
        if (o[k] < lo || o[k] > hi) miss = true;
        continue;
      }
      double ta = (lo - o[k]) / d[k], tb = (hi - o[k]) / d[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (!miss && t0 < t1) best = std::min(best, t0);
  }
  return best;
}

}  // namespace hvi::analysis::test
