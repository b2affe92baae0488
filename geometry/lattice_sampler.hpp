#pragma once
// Lattice sampling of a solid into material points: points at the centres of a cubic lattice of
// spacing `spacing` anchored at `anchor` (the grid origin, so that each grid cell holds the same
// n x n x n points), kept where the solid contains them. Each point carries an equal share of the
// solid's exact volume, so the sampled mass equals density x exact volume to round-off.
// (The scene driver uses sample() in sampler.hpp, which adds refinement zones and thin walls.)
#include "geometry/point_set.hpp"
#include "geometry/primitives.hpp"

namespace hvi::geometry {

//
// With `clip`, only the points inside the clip box are kept, each with the volume share of the
// unclipped sampling: a clip along planes of symmetry of the solid and the lattice (a half or
// quarter model cut on grid planes through the solid's axis) keeps exactly that fraction of the
// exact volume.
PointSet sample_lattice(const Solid& solid, double spacing, const Point& anchor,
                        const Bounds* clip = nullptr);

}  // namespace hvi::geometry
