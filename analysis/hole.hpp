#pragma once
// The hole of a perforated facesheet in its top view (top_view.hpp): the connected region of
// empty pixels (4-neighbour connectivity) that contains the impact point (x0, y0). If the impact
// point's pixel is material the sheet is not perforated (NP). Distances to the hole boundary are
// taken along rays by exact pixel traversal (Amanatides and Woo 1987): r_theta is where the ray
// from (x0, y0) leaves the last hole pixel it crosses.
#include <cstdint>
#include <vector>

#include "analysis/top_view.hpp"

namespace hvi::analysis {

struct Hole {
  bool perforated = false;  // the impact point's pixel is empty
  // The region reaches the raster's border: empty all the way to the sheet's edge, so the hole is
  // not closed within the modelled sheet and its sizes are lower bounds.
  bool open = false;
  std::vector<std::uint8_t> inside;  // nx * ny, 1 in the hole
  std::size_t pixels = 0;
  double area = 0;  // m^2
};

Hole find_hole(const Raster& raster, double x0, double y0);

// Distance (m) from (x0, y0) along the direction theta (rad, from +x towards +y) to the edge of
// the last hole pixel the ray crosses; 0 when (x0, y0) is not in the hole. `reached_border` (if
// given) is set when the ray leaves the raster without meeting material.
double distance_to_boundary(const Raster& raster, const Hole& hole, double x0, double y0,
                            double theta, bool* reached_border = nullptr);

}  // namespace hvi::analysis
