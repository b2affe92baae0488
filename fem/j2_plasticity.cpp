#include "fem/j2_plasticity.hpp"

#include <cmath>

namespace hvi::fem {

J2Update j2_return(const Sym& trial, const J2State& old, double mu, const mpm::JohnsonCookStrength& hardening) {
  J2Update r{trial, old, 0.0};
  const double p = (trial[0] + trial[1] + trial[2]) / 3.0;
  Sym s = trial;
  for (int i = 0; i < 3; ++i) s[i] -= p;
  const double ss = s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
  const double q_trial = std::sqrt(1.5 * ss);
  const double dgamma = mpm::radial_return(hardening, q_trial, mu, old.alpha, 1.0, 1.0);
  if (dgamma <= 0.0) return r;
  const double scale = 1.0 - 3.0 * mu * dgamma / q_trial;
  for (int i = 0; i < 6; ++i) {
    r.state.plastic_strain[i] += 1.5 * dgamma * s[i] / q_trial;
    r.stress[i] = scale * s[i] + (i < 3 ? p : 0.0);
  }
  r.state.alpha += dgamma;
  r.plastic_work = dgamma * scale * q_trial;
  return r;
}

}  // namespace hvi::fem
