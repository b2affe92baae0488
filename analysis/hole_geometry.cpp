#include "analysis/hole_geometry.hpp"

#include <cmath>
#include <numbers>

namespace hvi::analysis {

std::string to_string(DiameterRule rule) {
  return rule == DiameterRule::two_chords ? "two-chords" : "six-directions";
}

double HoleGeometry::angle(int k, double rotation) {
  return rotation + k * std::numbers::pi / 6;
}

HoleGeometry measure_hole(const Raster& raster, const Hole& hole, double x0, double y0,
                          DiameterRule rule, double rotation) {
  HoleGeometry g;
  g.rule = rule;
  g.rotation = rotation;
  g.resolution = raster.cell;
  g.perforated = hole.perforated;
  g.open = hole.open;
  if (!hole.perforated) return g;
  for (int k = 0; k < 12; ++k) {
    bool border = false;
    g.r[k] = distance_to_boundary(raster, hole, x0, y0, HoleGeometry::angle(k, rotation), &border);
    g.open = g.open || border;
  }
  // k indexes multiples of 30 deg: 0 -> 0, 3 -> 90, 6 -> 180, 9 -> 270 deg.
  if (rule == DiameterRule::two_chords) {
    g.D_h = g.r[0] + g.r[6];  // eq. (8)
    g.D_v = g.r[3] + g.r[9];
  } else {
    double h = 0, v = 0;  // eqs. (9)-(10), full-plane form
    for (int k = 0; k < 6; ++k) {
      h += 2 * g.r[2 * k];             // 0, 60, ..., 300 deg
      v += 2 * g.r[(3 + 2 * k) % 12];  // 90, 150, ..., 30 deg
    }
    g.D_h = h / 6;
    g.D_v = v / 6;
  }
  g.D = (g.D_h + g.D_v) / 2;
  g.eccentricity = g.D_v > 0 ? g.D_h / g.D_v : 0.0;  // eq. (11)
  g.area = hole.area;
  g.equivalent_diameter = std::sqrt(4 * g.area / std::numbers::pi);
  return g;
}

}  // namespace hvi::analysis
