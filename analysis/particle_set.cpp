#include "analysis/particle_set.hpp"

#include <algorithm>

namespace hvi::analysis {

namespace {

template <class T>
void append_field(std::vector<T>& out, std::span<const T> in, std::size_t p, int components) {
  if (in.empty()) return;
  for (int c = 0; c < components; ++c) out.push_back(in[components * p + c]);
}

// The images of particles index(0), ..., index(n - 1), every field reserved to its size.
template <class Index>
ParticleData mirror_points(const ParticleSet& set, const MirrorPlanes& planes,
                           std::int64_t id_stride, std::size_t n, Index index) {
  ParticleData out;
  const std::size_t copies = (planes.x ? 2 : 1) * (planes.y ? 2 : 1);
  auto reserve = [&](auto& field, const auto& from, std::size_t components) {
    if (!from.empty()) field.reserve(components * n * copies);
  };
  reserve(out.position, set.position, 3);
  reserve(out.id, set.id, 1);
  reserve(out.body, set.body, 1);
  reserve(out.mass, set.mass, 1);
  reserve(out.volume, set.volume, 1);
  reserve(out.failed, set.failed, 1);
  reserve(out.spacing, set.spacing, 1);
  reserve(out.half_width, set.half_width, 3);
  reserve(out.velocity, set.velocity, 3);
  std::int64_t image = 0;
  for (int mx = 0; mx < (planes.x ? 2 : 1); ++mx)
    for (int my = 0; my < (planes.y ? 2 : 1); ++my, ++image)
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t p = index(i);
        Vec3 x = set.x(p);
        if (mx) x[0] = 2 * *planes.x - x[0];
        if (my) x[1] = 2 * *planes.y - x[1];
        out.position.insert(out.position.end(), x.begin(), x.end());
        out.id.push_back(set.id[p] + image * id_stride);
        append_field(out.body, set.body, p, 1);
        append_field(out.mass, set.mass, p, 1);
        append_field(out.volume, set.volume, p, 1);
        append_field(out.failed, set.failed, p, 1);
        append_field(out.spacing, set.spacing, p, 1);
        append_field(out.half_width, set.half_width, p, 3);
        if (!set.velocity.empty()) {
          const double* v = &set.velocity[3 * p];
          out.velocity.insert(out.velocity.end(), {mx ? -v[0] : v[0], my ? -v[1] : v[1], v[2]});
        }
      }
  return out;
}

}  // namespace

ParticleData mirrored(const ParticleSet& set, const MirrorPlanes& planes, std::int64_t id_stride) {
  return mirror_points(set, planes, id_stride, set.size(), [](std::size_t i) { return i; });
}

ParticleData mirrored(const ParticleSet& set, const MirrorPlanes& planes, std::int64_t id_stride,
                      std::span<const std::size_t> particles) {
  return mirror_points(set, planes, id_stride, particles.size(),
                       [&](std::size_t i) { return particles[i]; });
}

ParticleData copy_of(const ParticleSet& set) {
  return mirrored(set, {}, 0);
}

double point_spacing(const ParticleSet& set, std::size_t p, double fallback) {
  if (!set.spacing.empty()) return set.spacing[p];
  if (!set.half_width.empty())
    return 2 *
           std::max({set.half_width[3 * p], set.half_width[3 * p + 1], set.half_width[3 * p + 2]});
  return fallback;
}

std::vector<std::size_t> particles_of(const ParticleSet& set, std::int64_t body, bool intact_only) {
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < set.size(); ++p)
    if (set.body[p] == body && (!intact_only || set.intact(p))) out.push_back(p);
  return out;
}

}  // namespace hvi::analysis
