#pragma once
// Johnson-Cook damage, the paper's eqs. (2)-(3):
//   D = sum d eps_p / eps_f,
//   eps_f = [D1 + D2 exp(D3 sigma*)] [1 + D4 ln(epsdot*)] [1 + D5 T*],
// sigma* = sigma_m / sigma_eq the stress triaxiality, epsdot* = max(epsdot / epsdot_0, 1), T* the
// homologous temperature. (The paper prints D5 T; T* is the usual form, and D5 = 0 for every
// material of its tables but Al6061.) The material fails when D reaches 1.
#include <algorithm>
#include <cmath>

namespace hvi::materials {

struct JohnsonCookDamage {
  double D1 = 0, D2 = 0, D3 = 0, D4 = 0, D5 = 0;
  double reference_strain_rate = 1.0;
  // Failure strains below this are taken as this: with D1 < 0 (Al6061) the bracket turns negative
  // at high triaxiality, which means failure within a step.
  static constexpr double minimum_failure_strain = 1e-6;

  double failure_strain(double triaxiality, double strain_rate, double homologous_T) const {
    const double rate = std::max(strain_rate / reference_strain_rate, 1.0);
    const double eps_f = (D1 + D2 * std::exp(D3 * triaxiality)) * (1.0 + D4 * std::log(rate)) *
                         (1.0 + D5 * homologous_T);
    return std::max(eps_f, minimum_failure_strain);
  }
};

}  // namespace hvi::materials
