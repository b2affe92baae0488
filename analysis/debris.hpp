#pragma once
// The debris cloud behind the rear facesheet at one time (paper Section 4.1, Figs. 9-10): every
// particle, of any body, more than `threshold` (one point spacing) behind the back face,
//   s_p = (x_p - a) . d - back_face > threshold,
// with d the impact direction (unit), a a point of the impact axis and back_face the position of
// the rear face's back surface along d. Reported: the mass, how far the cloud reaches behind the
// back face (max s_p, particle centres) and across the axis (the largest distance of a particle
// centre from the impact axis), and its kinetic energy sum 1/2 m_p |v_p|^2 (when the set has
// velocities). Material that has left the grid is not in the snapshot and not
// counted.
#include <cstdint>
#include <span>
#include <vector>

#include "analysis/particle_set.hpp"

namespace hvi::analysis {

struct DebrisOptions {
  Vec3 axis_point{};         // a point of the impact axis, m
  Vec3 direction{0, 0, -1};  // impact direction (normalised inside)
  double back_face = 0;      // (x - axis_point) . d of the back surface, m
  double threshold = 0;      // how far behind it a particle must be, m
};

struct Debris {
  double mass = 0;  // kg
  std::size_t particles = 0;
  double axial_extent = 0;    // m behind the back face
  double radial_extent = 0;   // m from the impact axis
  double kinetic_energy = 0;  // J (0 without velocities)
};

// `excluded` (sorted or not) lists particles not to count: the rear facesheet's own attached
// material, whose bulge or petals are not debris.
Debris debris_cloud(const ParticleSet& set, const DebrisOptions& options,
                    std::span<const std::size_t> excluded = {});

}  // namespace hvi::analysis
