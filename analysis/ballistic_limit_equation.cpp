#include "analysis/ballistic_limit_equation.hpp"

#include <cmath>
#include <numbers>

namespace hvi::analysis {

namespace {

// The equation's units.
constexpr double cm = 1e-2, g_cm3 = 1e3, km_s = 1e3, ksi = 6.894757293168361e6;
constexpr double K3S = 1.4, K3D = 0.4, V_LV = 3.0, V_HV = 7.0;  // aluminium facesheets

struct Inputs {
  double t_b, t_w, S, sigma, rho_b, rho_p, cos_delta;  // cm, ksi, g/cm^3; cos^delta(theta)
};

double ballistic(const Inputs& in, double v) {
  const double wall = in.t_w / K3S * std::sqrt(in.sigma / 40) + in.t_b;
  return std::pow(wall / (0.6 * in.cos_delta * std::sqrt(in.rho_p) * std::cbrt(v * v)), 18.0 / 19);
}

double hypervelocity(const Inputs& in, double v) {
  return 1.155 * std::cbrt(in.S) * std::cbrt(in.t_w * in.t_w) * std::cbrt(in.sigma / 70) /
         (std::cbrt(K3D * K3D) * std::cbrt(in.rho_p) * std::pow(in.rho_b, 1.0 / 9) *
          std::cbrt(v * v) * in.cos_delta);
}

}  // namespace

CriticalDiameter srl_critical_diameter(const SandwichPanel& panel, double projectile_density,
                                       double speed, double obliquity) {
  const double deg = obliquity * 180 / std::numbers::pi;
  const double delta = deg > 45 && deg < 65 ? 5.0 / 4 : 4.0 / 3;
  const double c = std::cos(obliquity);
  const Inputs in{panel.front_thickness / cm,  panel.rear_thickness / cm,
                  panel.spacing / cm,          panel.rear_yield / ksi,
                  panel.front_density / g_cm3, projectile_density / g_cm3,
                  std::pow(c, delta)};
  const double v = speed / km_s, low = V_LV / c, high = V_HV / c;
  CriticalDiameter out;
  if (v <= low) {
    out = {ballistic(in, v), BleRegime::ballistic};
  } else if (v >= high) {
    out = {hypervelocity(in, v), BleRegime::hypervelocity};
  } else {
    const double a = ballistic(in, low), b = hypervelocity(in, high);
    out = {a + (b - a) * (v - low) / (high - low), BleRegime::shatter};
  }
  out.diameter *= cm;
  return out;
}

const char* to_string(BleRegime regime) {
  switch (regime) {
    case BleRegime::ballistic:
      return "ballistic";
    case BleRegime::shatter:
      return "shatter";
    case BleRegime::hypervelocity:
      return "hypervelocity";
  }
  return "";
}

}  // namespace hvi::analysis
