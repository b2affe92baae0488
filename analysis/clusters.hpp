#pragma once
// The part of a facesheet still attached to it. Intact pieces torn off (a plug, fragments in the
// debris cloud, a spall scab) would, projected in the top view, cover the hole they came from; the
// sheet is the largest cluster (with its mirror images) of its intact particles, two particles
// linked when their centres are closer than link_factor x the larger of their point spacings. In an
// undeformed lattice the nearest neighbours are 1 h apart and a layer of failed particles between
// intact ones puts them 2 h apart: a link factor of 1.75 keeps material stretched by up to 75%
// joined and separates pieces divided by failed material.
#include <span>
#include <vector>

#include "analysis/particle_set.hpp"

namespace hvi::analysis {

// The largest cluster of `particles` (indices into `set`) and every other cluster at least half
// its size, in their order: a half or quarter model mirrored across its symmetry planes splits a
// sheet torn open to its edges into equal mirror images, all of them the sheet. `fallback_spacing`
// serves particles with no spacing of their own.
std::vector<std::size_t> attached_clusters(const ParticleSet& set,
                                           std::span<const std::size_t> particles,
                                           double link_factor, double fallback_spacing);

}  // namespace hvi::analysis
