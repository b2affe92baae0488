#pragma once
// Sampling a solid into material points.
//
// Lattice: points at the centres of a cubic lattice of spacing h = cell size / particles per cell
// anchored at the grid origin (every grid cell holds n x n x n points), kept where the solid
// contains them.
//
// Refinement zones (the paper's Fig. 4): a coarse lattice cell whose centre lies in a zone of
// factor k is replaced by the k x k x k cells of the lattice of spacing h / k that subdivide it,
// each kept where the solid contains its centre. The grid stays the same; only the points get
// finer. A coarse cell is refined whole or not at all, so the fine and coarse points tile space
// with no gap or overlap at the zone boundary.
//
// Thin walls (the paper's point-type internal-structure model, Section 2.4, eq. (7)): a solid
// that lists walls (the honeycomb core) and whose walls are thinner than 2 h (or when asked) is
// sampled as one layer of points on each wall mid-surface, n_u = ceil(L / h) along the wall of
// length L and n_z = ceil(H / h) over its height H, evenly spaced (k times more of each in a
// refinement zone, decided per coarse wall cell as above). A point carries
// thickness x (L - trims) / n_u x H / n_z: the wall's true volume, the junction overlaps counted
// once (geometry/honeycomb.hpp).
//
// Mass: per body, the raw point volumes (lattice cell volumes, or the thin-wall volumes above)
// are scaled by V_exact / sum(raw), so the sampled volume, and mass = density x volume, equal the
// exact ones to round-off. The report gives both sums: their ratio is how well the points
// resolve the body.
#include <vector>

#include "geometry/point_set.hpp"
#include "geometry/solid.hpp"

namespace hvi::geometry {

struct RefinementZone {
  enum class Shape { box, cylinder };
  Shape shape = Shape::box;
  Bounds box{};  // box: [lower, upper)
  // cylinder: base centre, axis (0, 1, 2), radius, length along the axis
  Point base{};
  int axis = 2;
  double radius = 0.0, length = 0.0;
  int factor = 2;  // points per coarse spacing along each axis
  bool contains(const Point& x) const;
};

enum class ThinWallModel { automatic, lattice, point_type };

struct SamplingSettings {
  double spacing = 0.0;  // coarse lattice spacing h, m
  Point anchor{};        // lattice origin (the grid's lower corner)
  std::vector<RefinementZone> zones;
  ThinWallModel thin_walls = ThinWallModel::automatic;
};

struct SampleReport {
  double exact_volume = 0.0;    // the solid's exact volume, m^3
  double lattice_volume = 0.0;  // sum of the raw point volumes before scaling, m^3
  std::size_t points = 0;
  std::size_t refined_points = 0;  // of which from refinement zones
  bool point_type = false;         // walls sampled as single layers
};

// Throws std::invalid_argument if no point falls in the solid.
PointSet sample(const Solid& solid, const SamplingSettings& settings,
                SampleReport* report = nullptr);

}  // namespace hvi::geometry
