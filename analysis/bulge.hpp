#pragma once
// The bulge of a rear facesheet that was not perforated (paper Section 3: "a bulge can be found on
// the back surface of the rear facesheet"): the largest displacement along the impact direction d,
//   bulge = max_p (x_p(t) - x_p(0)) . d,
// over the sheet's particles at time t (normally its intact attached ones), each matched by id to
// its position in the initial snapshot.
#include <cstdint>
#include <span>

#include "analysis/particle_set.hpp"

namespace hvi::analysis {

struct Bulge {
  double displacement = 0;    // m, along the impact direction
  std::int64_t id = -1;       // the particle that moved most
  Vec3 position{};            // its position at t, m
  std::size_t unmatched = 0;  // particles with no id in the initial set (left out)
};

// `direction` need not be normalised.
Bulge rear_bulge(const ParticleSet& initial, const ParticleSet& current,
                 std::span<const std::size_t> particles, Vec3 direction);

}  // namespace hvi::analysis
