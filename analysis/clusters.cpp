#include "analysis/clusters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace hvi::analysis {

namespace {

struct UnionFind {
  std::vector<std::size_t> parent, size;
  explicit UnionFind(std::size_t n) : parent(n), size(n, 1) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  std::size_t find(std::size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size[a] < size[b]) std::swap(a, b);
    parent[b] = a;
    size[a] += size[b];
  }
};

// 21 bits per axis, offset so that negative cells pack too.
std::int64_t pack(std::int64_t i, std::int64_t j, std::int64_t k) {
  constexpr std::int64_t offset = 1 << 20, mask = (1 << 21) - 1;
  return ((i + offset) & mask) | (((j + offset) & mask) << 21) | (((k + offset) & mask) << 42);
}

}  // namespace

std::vector<std::size_t> attached_clusters(const ParticleSet& set,
                                           std::span<const std::size_t> particles,
                                           double link_factor, double fallback_spacing) {
  const std::size_t n = particles.size();
  if (n == 0) return {};
  std::vector<double> link(n);
  double finest = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < n; ++a) {
    link[a] = link_factor * point_spacing(set, particles[a], fallback_spacing);
    if (!(link[a] > 0)) throw std::invalid_argument("clusters: a particle has no point spacing");
    finest = std::min(finest, link[a]);
  }
  // Hash cells of the finest link length; a particle looks as many cells out as its own link.
  const double cell = finest;
  std::vector<std::array<std::int64_t, 3>> c(n);
  std::unordered_map<std::int64_t, std::vector<std::size_t>> cells;
  cells.reserve(n);
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3 x = set.x(particles[a]);
    for (int d = 0; d < 3; ++d) c[a][d] = static_cast<std::int64_t>(std::floor(x[d] / cell));
    cells[pack(c[a][0], c[a][1], c[a][2])].push_back(a);
  }
  UnionFind sets(n);
  for (std::size_t a = 0; a < n; ++a) {
    const Vec3 x = set.x(particles[a]);
    const std::int64_t reach = static_cast<std::int64_t>(std::ceil(link[a] / cell));
    for (std::int64_t dk = -reach; dk <= reach; ++dk)
      for (std::int64_t dj = -reach; dj <= reach; ++dj)
        for (std::int64_t di = -reach; di <= reach; ++di) {
          const auto it = cells.find(pack(c[a][0] + di, c[a][1] + dj, c[a][2] + dk));
          if (it == cells.end()) continue;
          for (const std::size_t b : it->second) {
            // Each pair once, from the side of the longer link (whose reach surely covers it).
            if (!(link[a] > link[b] || (link[a] == link[b] && a < b))) continue;
            const Vec3 y = set.x(particles[b]);
            const double l = std::max(link[a], link[b]);
            const double r2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) +
                              (x[2] - y[2]) * (x[2] - y[2]);
            if (r2 < l * l) sets.join(a, b);
          }
        }
  }
  std::size_t largest = 0;
  for (std::size_t a = 0; a < n; ++a) largest = std::max(largest, sets.size[sets.find(a)]);
  std::vector<std::size_t> out;
  for (std::size_t a = 0; a < n; ++a)
    if (2 * sets.size[sets.find(a)] >= largest) out.push_back(particles[a]);
  return out;
}

}  // namespace hvi::analysis
