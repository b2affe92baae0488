#pragma once
// Hole sizes as the paper measures them (Section 4.2, Fig. 13). With r_theta the distance from the
// impact point to the hole boundary along the direction theta (from +x towards +y; hole.hpp), the
// paper's D_theta is 2 r_theta.
//
// Front facesheet, eq. (8): two chords through the impact point,
//   D_h = r_0 + r_180,   D_v = r_90 + r_270,   D_f = (D_h + D_v) / 2.
//
// Rear facesheet, eqs. (9)-(10): the honeycomb has a 60 deg cyclic symmetry, so
//   D_h = (D_0 + 2 D_60 + 2 D_120 + D_180) / 6,   D_v = (D_30 + D_90 + D_150) / 3.
// These are averages over the six directions at multiples of 60 deg from the horizontal (resp.
// the vertical) of a hole mirror-symmetric about the horizontal line (the paper's half model):
// that symmetry gives r_300 = r_60, r_240 = r_120 and r_330 = r_30, r_270 = r_90, r_210 = r_150, so
//   (1/6) sum_{k=0..5} 2 r_{60k}      = (2r_0 + 2(2r_60) + 2(2r_120) + 2r_180) / 6
//                                     = (D_0 + 2 D_60 + 2 D_120 + D_180) / 6,
//   (1/6) sum_{k=0..5} 2 r_{90+60k}   = (2(2r_30) + 2(2r_90) + 2(2r_150)) / 6
//                                     = (D_30 + D_90 + D_150) / 3.
// The code takes the full-plane averages (the left-hand sides), which hold without the symmetry.
// D_r = (D_h + D_v) / 2.
//
// Eccentricity e = D_h / D_v (eq. 11); taper t = (D_r - D_f) / S (eq. 12).
// All directions may be turned by `rotation`: the paper measured its model at 60 and 150 deg
// (Section 3, Fig. 5(a)) because its cell pattern was turned 30 deg from the experiment's (the
// two-chord rule with rotation 60 deg gives exactly D_60 and D_150).
#include <array>
#include <string>

#include "analysis/hole.hpp"

namespace hvi::analysis {

enum class DiameterRule {
  two_chords,      // eq. (8), the front facesheet
  six_directions,  // eqs. (9)-(10), the rear facesheet
};
std::string to_string(DiameterRule rule);

struct HoleGeometry {
  bool perforated = false;
  bool open = false;  // the hole reaches the edge of the sheet: the sizes below are lower bounds
  DiameterRule rule = DiameterRule::two_chords;
  double rotation = 0;             // rad
  std::array<double, 12> r{};      // r_theta at theta_k = rotation + k * 30 deg, m
  double D_h = 0, D_v = 0;         // m
  double D = 0;                    // (D_h + D_v) / 2, m
  double eccentricity = 0;         // D_h / D_v
  double area = 0;                 // hole area in the top view, m^2
  double equivalent_diameter = 0;  // of the circle of the same area, m
  double resolution = 0;           // raster pixel edge, m

  static double angle(int k, double rotation);  // theta_k, rad
  double D_theta(int k) const { return 2 * r[k]; }
};

// Everything above for the hole at (x0, y0); zeros (perforated = false) if NP.
HoleGeometry measure_hole(const Raster& raster, const Hole& hole, double x0, double y0,
                          DiameterRule rule, double rotation);

// Eq. (12): the taper of the channel through a core of height S.
inline double channel_taper(double rear_diameter, double front_diameter, double core_height) {
  return (rear_diameter - front_diameter) / core_height;
}

}  // namespace hvi::analysis
