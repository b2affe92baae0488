#include "fem/j2_plasticity.hpp"

#include <algorithm>
#include <cmath>

namespace hvi::fem {

double equivalent_strain_rate(const Sym& de, double dt) {
  const double mean = (de[0] + de[1] + de[2]) / 3.0;
  double dd = 0.0;
  for (int i = 0; i < 3; ++i) dd += (de[i] - mean) * (de[i] - mean);
  for (int i = 3; i < 6; ++i) dd += 2.0 * de[i] * de[i];
  return std::sqrt(2.0 / 3.0 * dd) / dt;
}

J2Update j2_return(const Sym& trial, const J2State& old, double mu,
                   const materials::JohnsonCookStrength& hardening, const StrainRate& rate) {
  J2Update r{trial, old, 0.0};
  const double p = (trial[0] + trial[1] + trial[2]) / 3.0;
  Sym s = trial;
  for (int i = 0; i < 3; ++i) s[i] -= p;
  const double ss =
      s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
  const double q_trial = std::sqrt(1.5 * ss);
  const double k = rate.dt > 0.0 ? hardening.rate_factor(rate.equivalent) : 1.0;
  const double dgamma = materials::radial_return(hardening, q_trial, mu, old.alpha, k, 1.0);
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

namespace {

// A torn point: `r`'s stress to K min(tr eps, 0) I, the strain it stood on to eps_p; with
// `tearing` the elastic energy released, 1/2 sigma_before : d eps_p, added to the step's work.
// tr eps = tr sigma / 3K + tr eps_p.
void tear(J2Update& r, double mu, double K, bool tearing) {
  auto& ep = r.state.plastic_strain;
  const double p = (r.stress[0] + r.stress[1] + r.stress[2]) / 3.0;
  const double kept = K * std::min(p / K + ep[0] + ep[1] + ep[2], 0.0);
  Sym d{};
  for (int i = 0; i < 6; ++i) d[i] = (r.stress[i] - (i < 3 ? p : 0.0)) / (2.0 * mu);
  for (int i = 0; i < 3; ++i) d[i] += (p - kept) / (3.0 * K);
  if (tearing) {
    double released = 0.0;
    for (int i = 0; i < 6; ++i) released += (i < 3 ? 1.0 : 2.0) * r.stress[i] * d[i];
    r.plastic_work += 0.5 * released;
  }
  for (int i = 0; i < 6; ++i) {
    ep[i] += d[i];
    r.stress[i] = i < 3 ? kept : 0.0;
  }
}

}  // namespace

J2Update j2_return(const Sym& trial, const J2State& old, double mu, double K,
                   const materials::JohnsonCookStrength& hardening,
                   const materials::JohnsonCookDamage& damage, const StrainRate& rate) {
  if (old.damage >= 1.0) {  // torn before this step
    J2Update r{trial, old, 0.0};
    tear(r, mu, K, false);
    return r;
  }
  J2Update r = j2_return(trial, old, mu, hardening, rate);
  const double dgamma = r.state.alpha - old.alpha;
  if (dgamma <= 0.0) return r;
  // Triaxiality at the returned stress, whose q is the yield stress sigma_y(alpha_n+1) > 0.
  const double p = (r.stress[0] + r.stress[1] + r.stress[2]) / 3.0;
  const double q = r.plastic_work / dgamma;
  const double plastic_rate = rate.dt > 0.0 ? dgamma / rate.dt : 0.0;
  r.state.damage += dgamma / damage.failure_strain(p / q, plastic_rate, 0.0);
  if (r.state.damage >= 1.0) tear(r, mu, K, true);
  return r;
}

}  // namespace hvi::fem
