#pragma once
// Tuler-Butcher spall (Tuler and Butcher 1968): a time-dependent form of the max-principal-stress
// criterion. Tension above a threshold sigma_0 fails the material only once its impulse,
//   integral of max(sigma_1 - sigma_0, 0)^lambda dt,
// reaches a constant K. With K written sigma_0^lambda tau the scene gives a time tau, so the
// damage
//   D_s = (1 / tau) integral of max(sigma_1 / sigma_0 - 1, 0)^lambda dt
// fails the material at D_s = 1: a stress held at sigma_1 fails it after tau / (sigma_1 / sigma_0 -
// 1)^lambda, and a pulse shorter than that does not. As tau goes to 0 it is the instantaneous
// criterion at sigma_0; a literature K converts as tau = K / sigma_0^lambda.
#include <cmath>

namespace hvi::materials {

struct TulerButcher {
  double threshold = 0;  // sigma_0, Pa
  double exponent = 2;   // lambda
  double time = 0;       // tau = K / sigma_0^lambda, s

  // dD_s / dt at largest principal stress sigma_1.
  double damage_rate(double sigma_1) const {
    const double excess = sigma_1 / threshold - 1.0;
    return excess > 0.0 ? std::pow(excess, exponent) / time : 0.0;
  }
};

}  // namespace hvi::materials
