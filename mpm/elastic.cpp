#include "mpm/elastic.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mpm/phase_timer.hpp"
#include "mpm/types.hpp"

namespace hvi::mpm {

LinearElastic::LinearElastic(std::string name, double density, double youngs_modulus,
                             double poisson_ratio)
    : Material(std::move(name)),
      density_(density),
      lambda_(youngs_modulus * poisson_ratio /
              ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio))),
      mu_(youngs_modulus / (2.0 * (1.0 + poisson_ratio))) {}

double LinearElastic::p_wave_speed(double rho) const {
  return std::sqrt((lambda_ + 2.0 * mu_) / rho);
}

double LinearElastic::max_signal_speed(const Particles& particles, ParticleRange range) const {
  double result = 0.0;
  const auto begin = static_cast<std::int64_t>(range.begin),
             end = static_cast<std::int64_t>(range.end);
#pragma omp parallel for reduction(max : result) schedule(static)
  for (std::int64_t p = begin; p < end; ++p) {
    const double rho = particles.mass[p] / particles.volume[p];
    result = std::max(result, p_wave_speed(rho) + speed(particles, p));
  }
  return result;
}

StressUpdate LinearElastic::update_stress(Particles& particles, ParticleRange range,
                                          const StressContext& context) const {
  PhaseTimer dummy;
  auto t = (context.timer ? *context.timer : dummy).scope("stress: linear elastic");
  const double dt = context.dt;
  double max_signal = 0.0;
  std::int64_t bad = INT64_MAX;
  const auto begin = static_cast<std::int64_t>(range.begin),
             end = static_cast<std::int64_t>(range.end);
#pragma omp parallel for reduction(max : max_signal) reduction(min : bad) schedule(static)
  for (std::int64_t p = begin; p < end; ++p) {
    const double* L = &particles.velocity_gradient[9 * p];
    double D[6], W[9], spin[6];
    split_velocity_gradient(L, D, W);
    double* s = &particles.stress[6 * p];
    jaumann_spin_term(W, s, spin);

    const double trD = D[sym::xx] + D[sym::yy] + D[sym::zz];
    double s_new[6];
    for (int c = 0; c < 6; ++c) s_new[c] = s[c] + dt * (2.0 * mu_ * D[c] + spin[c]);
    s_new[sym::xx] += dt * lambda_ * trD;
    s_new[sym::yy] += dt * lambda_ * trD;
    s_new[sym::zz] += dt * lambda_ * trD;

    const VolumeChange V = advance_volume(particles, p, dt);
    const double rho_mid = 2.0 * particles.mass[p] / (V.before + V.after);

    double s_mid[6];
    for (int c = 0; c < 6; ++c) s_mid[c] = 0.5 * (s[c] + s_new[c]);
    particles.internal_energy[p] += dt * contract_sym(s_mid, D) / rho_mid;
    for (int c = 0; c < 6; ++c) s[c] = s_new[c];

    if (!(V.after > 0.0) ||
        !std::isfinite(s_new[0] + s_new[1] + s_new[2] + s_new[3] + s_new[4] + s_new[5]))
      bad = std::min(bad, p);
    const double rho = particles.mass[p] / V.after;
    max_signal = std::max(max_signal, p_wave_speed(rho) + speed(particles, p));
  }
  return StressUpdate::of(max_signal, bad, "non-positive volume or non-finite stress");
}

}  // namespace hvi::mpm
