#pragma once
// The Schaefer-Ryan-Lambert (SRL) ballistic limit equation for honeycomb sandwich panels (Ryan,
// Schaefer, Destefanis, Lambert, Adv. Space Res. 41 (2008) 1152-1166; Schaefer, Ryan, Lambert,
// Putzar, Int. J. Impact Eng. 35 (2008) 1784-1791), as NASA's open pyBLOSSUM evaluates it. In the
// equation's units (cm, g/cm^3, km/s, ksi), with t_b and t_w the front ("bumper") and rear
// ("wall") facesheets, S the panel spacing, sigma the rear sheet's yield, theta the obliquity and
// delta = 4/3 (5/4 for 45 deg < theta < 65 deg):
//   ballistic, v <= V_LV:       d_c = [((t_w / K3S)(sigma/40)^(1/2) + t_b)
//                                      / (0.6 cos^delta(theta) rho_p^(1/2) v^(2/3))]^(18/19)
//   hypervelocity, v >= V_HV:   d_c = 1.155 S^(1/3) t_w^(2/3) (sigma/70)^(1/3)
//                                      / (K3D^(2/3) rho_p^(1/3) rho_b^(1/9) v^(2/3)
//                                      cos^delta(theta))
//   shatter, in between:        linear in v from d_c(V_LV) to d_c(V_HV),
// with, for aluminium facesheets, K3S = 1.4, K3D = 0.4, V_LV = 3 km/s / cos(theta), V_HV =
// 7 km/s / cos(theta). The honeycomb enters only through K3S and K3D (its channelling: K3D = 0.16
// would be Christiansen's Whipple shield). A sphere of diameter d perforates the rear sheet when
// d >= d_c. Arguments and result in SI.
namespace hvi::analysis {

struct SandwichPanel {
  double front_thickness = 0;  // t_b, m
  double rear_thickness = 0;   // t_w, m
  double spacing = 0;          // S, m
  double rear_yield = 0;       // sigma, Pa
  double front_density = 0;    // rho_b, kg/m^3
};

enum class BleRegime { ballistic, shatter, hypervelocity };

struct CriticalDiameter {
  double diameter = 0;  // d_c, m
  BleRegime regime = BleRegime::ballistic;
};

// speed in m/s, obliquity in rad (0: normal incidence).
CriticalDiameter srl_critical_diameter(const SandwichPanel& panel, double projectile_density,
                                       double speed, double obliquity = 0);

const char* to_string(BleRegime regime);

}  // namespace hvi::analysis
