#pragma once
// What the measurements read: plain per-particle arrays (a struct of arrays, as mpm::Particles and
// the snapshot files hold them), so that the same code runs on a live solver and on snapshots.
// Knows nothing of the solver, CGAL or deal.II.
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace hvi::analysis {

using Vec3 = std::array<double, 3>;

// A read-only view. Optional fields are empty spans.
struct ParticleSet {
  std::span<const double> position;    // 3 per particle, m
  std::span<const std::int64_t> id;    // stable particle id
  std::span<const std::int64_t> body;  // index into the scene's bodies
  std::span<const double> mass;        // kg (optional: the debris mass needs it)
  std::span<const double> volume;      // current volume, m^3 (optional)
  std::span<const double> failed;   // 0 intact, 1 failed (optional: no failure model, all intact)
  std::span<const double> spacing;  // point spacing, m (optional): the footprint edge
  std::span<const double> half_width;  // 3 per particle, m (optional): GIMP half-widths
  std::span<const double> velocity;  // 3 per particle, m/s (optional: the debris's kinetic energy)

  std::size_t size() const { return id.size(); }
  Vec3 x(std::size_t p) const {
    return {position[3 * p], position[3 * p + 1], position[3 * p + 2]};
  }
  bool intact(std::size_t p) const { return failed.empty() || failed[p] == 0.0; }
};

// Owning storage with the same fields (snapshots read from disk, mirrored copies, tests).
struct ParticleData {
  std::vector<double> position, mass, volume, failed, spacing, half_width, velocity;
  std::vector<std::int64_t> id, body;

  std::size_t size() const { return id.size(); }
  ParticleSet view() const {
    return {position, id, body, mass, volume, failed, spacing, half_width, velocity};
  }
};

// The symmetry planes of a half or quarter model: x = x_s and/or y = y_s.
struct MirrorPlanes {
  std::optional<double> x, y;
  bool any() const { return x || y; }
};

// The full model from a half or quarter model: every particle and its images across the planes
// (2 or 4 copies in all). Image k (k = 1, 2, 3) has id + k * id_stride, so two snapshots mirrored
// with the same stride (larger than every id) still match particle by particle. Mass and volume
// are copied: sums over the result are sums over the full model; velocities are mirrored with the
// positions. A particle lying exactly on a
// plane is copied too (lattice sampling puts none there: points sit half a spacing from a cut).
ParticleData mirrored(const ParticleSet& set, const MirrorPlanes& planes, std::int64_t id_stride);
// The same for the listed particles only (indices into the set), in the order listed: a
// measurement mirrors just the bodies it reads, not the whole model.
ParticleData mirrored(const ParticleSet& set, const MirrorPlanes& planes, std::int64_t id_stride,
                      std::span<const std::size_t> particles);

// A copy of the set (no mirroring).
ParticleData copy_of(const ParticleSet& set);

// The point spacing of particle p, m: its `spacing`, else twice its largest GIMP half-width, else
// `fallback`.
double point_spacing(const ParticleSet& set, std::size_t p, double fallback);

// Indices of the particles of `body`; with `intact_only`, only those not failed.
std::vector<std::size_t> particles_of(const ParticleSet& set, std::int64_t body, bool intact_only);

}  // namespace hvi::analysis
