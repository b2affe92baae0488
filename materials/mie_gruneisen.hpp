#pragma once
// Mie-Grüneisen equation of state with a linear Us-up Hugoniot, the paper's eqs. (4)-(5) in the
// standard form (AUTODYN "shock", LS-DYNA *EOS_GRUNEISEN without the cubic terms):
//   mu = rho / rho0 - 1
//   p_H = rho0 c0^2 mu (1 + mu) / [1 - (s - 1) mu]^2   (mu >= 0; the paper prints c0 for c0^2)
//   p_H = rho0 c0^2 mu                                   (mu < 0, tension)
//   p   = p_H (1 - Gamma mu / 2) + Gamma rho e,   Gamma rho = Gamma0 rho0   (mu >= 0)
//   p   = p_H + Gamma0 rho e                                               (mu < 0)
// with e the current specific internal energy (J/kg). The paper's "gamma0 E0" is read as
// Gamma0 rho0 e: E0 the internal energy per unit reference volume, integrated per particle.
// In expansion the form changes in two ways, both because Gamma = Gamma0 rho0 / rho diverges as
// rho -> 0 (debris expanded hundreds of times in a honeycomb impact):
//  - the (1 - Gamma mu / 2) factor is left out, as LS-DYNA's *EOS_GRUNEISEN does (with it, 10 km/s
//    debris reached p = -80 rho0 c0^2 and a 440 km/s sound speed);
//  - Gamma stays Gamma0 (p = Gamma0 rho e, an ideal-gas-like thermal pressure), so that the
//    energy-pressure coupling dp/de = Gamma rho stays bounded by Gamma0 rho0; with Gamma0 rho0 the
//    implicit energy update of a particle expanded 250-fold lost positivity and drove e to 2e9
//    J/kg.
// Both are continuous with the compression branch at rho0.
#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "materials/model_parameter.hpp"

namespace hvi::materials {

// What an equation of state p = cold(rho) + B(rho) e needs of a density, computed once for the
// pressure update and the sound speeds of a point: mu = rho / rho0 - 1, B = dp/de at fixed
// density, and dp/dmu at fixed e (for Mie-Grüneisen, but for the expansion branch's e term).
struct EosState {
  double rho, mu, B, cold, dp_dmu;
};

struct MieGruneisen {
  static constexpr const char* name = "mie-gruneisen";
  static constexpr const char* table = "mie_gruneisen";
  static constexpr const char* doc = "Mie-Grüneisen EOS parameters (paper eqs. 4-5).";
  static constexpr const char* summary = "eqs. 4-5";
  static constexpr std::array<ModelParameter, 3> parameters{{
      {"c0", "m/s", ModelParameter::Bound::positive, "Bulk sound speed (Us-up intercept)"},
      {"s", "", ModelParameter::Bound::non_negative, "Us-up slope"},
      {"gamma0", "", ModelParameter::Bound::non_negative,
       "Grüneisen parameter at the reference density"},
  }};
  static MieGruneisen from(double rho0, std::span<const double, 3> v) {
    return {rho0, v[0], v[1], v[2]};
  }
  std::array<double, 3> values() const { return {c0, s, gamma0}; }
  double reference_sound_speed() const { return c0; }

  double reference_density = 0;  // rho0, kg/m^3
  double c0 = 0;                 // bulk sound speed, m/s
  double s = 0;                  // Us-up slope
  double gamma0 = 0;             // Grüneisen parameter at rho0

  // The compression branch is singular at mu = 1 / (s - 1); stay below it.
  double limited_mu(double mu) const { return s > 1.0 ? std::min(mu, 0.9 / (s - 1.0)) : mu; }

  double hugoniot_pressure(double mu) const {
    const double K0 = reference_density * c0 * c0;
    if (mu < 0.0) return K0 * mu;
    mu = limited_mu(mu);
    const double den = 1.0 - (s - 1.0) * mu;
    return K0 * mu * (1.0 + mu) / (den * den);
  }
  // d p_H / d mu
  double hugoniot_slope(double mu) const {
    const double K0 = reference_density * c0 * c0;
    if (mu < 0.0) return K0;
    mu = limited_mu(mu);
    const double den = 1.0 - (s - 1.0) * mu;
    return K0 * ((1.0 + 2.0 * mu) * den + 2.0 * (s - 1.0) * mu * (1.0 + mu)) / (den * den * den);
  }
  // Pressure = A(rho) + B(rho) e: the part independent of e, and B = dp/de at fixed density.
  double cold_part(double rho) const {
    const double mu = rho / reference_density - 1.0;
    if (mu < 0.0) return hugoniot_pressure(mu);
    const double gamma = gamma0 / (1.0 + mu);  // Gamma = Gamma0 rho0 / rho
    return hugoniot_pressure(mu) * (1.0 - 0.5 * gamma * mu);
  }
  double energy_coefficient(double rho) const { return gamma0 * std::min(rho, reference_density); }
  double pressure(double rho, double e) const {
    return cold_part(rho) + energy_coefficient(rho) * e;
  }

  EosState at(double rho) const {
    EosState a{rho, rho / reference_density - 1.0, energy_coefficient(rho), 0.0, 0.0};
    const double mu = a.mu, pH = hugoniot_pressure(mu), slope = hugoniot_slope(mu);
    if (mu < 0.0) {
      a.cold = pH;
      a.dp_dmu = slope;
    } else {
      const double gamma = gamma0 / (1.0 + mu);  // Gamma = Gamma0 rho0 / rho
      a.cold = pH * (1.0 - 0.5 * gamma * mu);
      a.dp_dmu = slope * (1.0 - 0.5 * gamma0 * mu / (1.0 + mu)) -
                 pH * 0.5 * gamma0 / ((1.0 + mu) * (1.0 + mu));
    }
    return a;
  }

  // Squared bulk sound speed c^2 = dp/drho|_e + p / rho^2 dp/de|_rho, floored at a tenth of c0^2
  // so that a state in tension keeps a meaningful time step.
  double bulk_sound_speed_squared(const EosState& a, double p) const {
    double dp_dmu_e = a.dp_dmu;
    if (a.mu < 0.0) {  // in expansion d(Gamma0 rho e)/dmu = Gamma0 rho0 e, with e recovered from p
      const double e = (p - a.cold) / a.B;
      dp_dmu_e += gamma0 * reference_density * std::max(e, 0.0);
    }
    const double c2 = dp_dmu_e / reference_density + p * a.B / (a.rho * a.rho);
    return std::max(c2, 0.1 * c0 * c0);
  }
  double bulk_sound_speed_squared(double rho, double p) const {
    return bulk_sound_speed_squared(at(rho), p);
  }
};

}  // namespace hvi::materials
