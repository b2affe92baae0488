#pragma once
// Johnson-Cook strength, the paper's eq. (1):
//   sigma_y = (A + B eps_p^n) (1 + C ln(epsdot*)) (1 - T*^m),
//   epsdot* = max(epsdot / epsdot_0, 1)             (rates below the reference do not soften)
//   T* = clamp((T - T_room) / (T_melt - T_room), 0, 1).
// The deviatoric stress is returned radially to the von Mises surface (radial_return).
#include <algorithm>
#include <cmath>

namespace hvi::materials {

struct JohnsonCookStrength {
  double A = 0, B = 0, n = 1, C = 0, m = 1;               // Pa, Pa, -, -, -
  double melt_temperature = 0, room_temperature = 293.0;  // K
  double reference_strain_rate = 1.0;                     // 1/s

  double homologous_temperature(double T) const {
    return std::clamp((T - room_temperature) / (melt_temperature - room_temperature), 0.0, 1.0);
  }
  // Below the reference rate ln(1) = 0, and at room temperature 0^m = 0 (m > 0): both factors are
  // then exactly 1, as most points of a run are, without a logarithm or a power.
  double rate_factor(double strain_rate) const {
    const double ratio = strain_rate / reference_strain_rate;
    return ratio > 1.0 ? 1.0 + C * std::log(ratio) : 1.0;
  }
  double thermal_factor(double T) const {
    const double t = homologous_temperature(T);
    return t > 0.0 || !(m > 0.0) ? 1.0 - std::pow(t, m) : 1.0;
  }
  double hardening(double eps_p) const { return A + B * (eps_p > 0.0 ? std::pow(eps_p, n) : 0.0); }
  double yield_stress(double eps_p, double strain_rate, double T) const {
    return hardening(eps_p) * rate_factor(strain_rate) * thermal_factor(T);
  }
};

// Radial return for J2 plasticity with Johnson-Cook hardening. Given the trial von Mises stress
// q_trial (of an elastic trial deviator), the shear modulus G, the plastic strain eps_p and the
// rate and thermal factors frozen over the step, finds the plastic strain increment d with
//   q_trial - 3 G d = (A + B (eps_p + d)^n) * rate * thermal
// by safeguarded Newton iteration (the residual is monotone in d), started from the linearised
// return d_0 = f(0) / (3 G + H'(eps_p)), which a step's small plastic increment leaves within a
// few ulps of the root, so two or three iterations converge. Returns 0 when q_trial is inside the
// surface. The deviator is then scaled by (q_trial - 3 G d) / q_trial.
inline double radial_return(const JohnsonCookStrength& jc, double q_trial, double G, double eps_p,
                            double rate, double thermal) {
  const double k = rate * thermal;
  // Elastic points, most of a run's, below A k <= (A + B eps_p^n) k (B >= 0): no power needed.
  if (jc.B >= 0.0 && k >= 0.0 && q_trial <= jc.A * k) return 0.0;
  // The yield stress at plastic strain e, and its slope dy/de (from e^n / e, one power).
  const auto yield = [&](double e, double& slope) {
    const double en = e > 0.0 ? std::pow(e, jc.n) : 0.0;
    slope = e > 0.0 ? jc.B * jc.n * (en / e) * k : 0.0;
    return (jc.A + jc.B * en) * k;
  };
  double slope;
  const double f0 = q_trial - yield(eps_p, slope);
  if (f0 <= 0.0) return 0.0;
  if (k <= 0.0) return q_trial / (3.0 * G);  // molten: no strength left
  // f(d) = q_trial - 3 G d - yield(eps_p + d) is decreasing; f(0) > 0, f(q_trial / 3G) <= 0.
  double lo = 0.0, hi = q_trial / (3.0 * G);
  double d = f0 / (3.0 * G + slope);
  if (!(d > lo && d < hi)) d = 0.5 * hi;
  for (int it = 0; it < 60; ++it) {
    const double f = q_trial - 3.0 * G * d - yield(eps_p + d, slope);
    if (f > 0.0)
      lo = d;
    else
      hi = d;
    double next = d + f / (3.0 * G + slope);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // keep Newton inside the bracket
    if (std::fabs(next - d) <= 1e-14 * (eps_p + next) + 1e-300) return next;
    d = next;
  }
  return d;
}

}  // namespace hvi::materials
