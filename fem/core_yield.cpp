#include "fem/core_yield.hpp"

#include <cmath>

namespace hvi::fem {

CoreYield honeycomb_core_yield(const Orthotropic& core, double wall_youngs_modulus,
                               double wall_poisson_ratio, double wall_yield_stress) {
  const double shear_modulus = wall_youngs_modulus / (2.0 * (1.0 + wall_poisson_ratio));
  const double shear_yield = wall_yield_stress / std::sqrt(3.0);
  return {core.E3 / wall_youngs_modulus * wall_yield_stress, core.G13 / shear_modulus * shear_yield,
          core.G23 / shear_modulus * shear_yield, std::nullopt};
}

CoreFailure honeycomb_core_failure(const materials::JohnsonCookDamage& walls) {
  // Reference rate (factor 1) and room temperature (T* = 0).
  return {walls.failure_strain(1.0 / 3.0, 0.0, 0.0), walls.failure_strain(-1.0 / 3.0, 0.0, 0.0),
          walls.failure_strain(0.0, 0.0, 0.0)};
}

namespace {

// sigma_zz of `r` moved to `target` by plastic strain along z, d eps_p,zz = (sigma_zz - target) /
// C33, which also moves sigma_xx and sigma_yy by C13 and C23 times it; returns d eps_p,zz.
double return_normal(CoreYieldUpdate& r, const std::array<double, 9>& C, double target) {
  const double d = (r.stress[2] - target) / C[2];
  r.stress[0] -= C[4] * d;
  r.stress[1] -= C[5] * d;
  r.stress[2] = target;
  r.plastic_strain[2] += d;
  return d;
}

// Shear `k` of `r` (Voigt 3 = yz, 4 = xz) moved to `target`: d gamma_p = (tau - target) / G in
// engineering strain, half of it in the tensor component; returns d gamma_p.
double return_shear(CoreYieldUpdate& r, int k, double modulus, double target) {
  const double dgamma = (r.stress[k] - target) / modulus;
  r.stress[k] = target;
  r.plastic_strain[k] += 0.5 * dgamma;
  return dgamma;
}

// Torn walls: sigma_zz, sigma_yz and sigma_xz of `r` to zero and the strain they stood on to the
// plastic strain. In the step of the tear the elastic energy that releases, 1/2 sigma : d eps_p
// (sigma the capped stress, zero after), is dissipated; in later steps nothing is: the torn point
// exerts no force, so the strain increment of its elastic predictor never held energy, and
// booking it would create energy (1/2 C d eps^2 a step). The accumulated strain keeps the walls'
// plastic strain up to the tear: what a torn core takes after is not the walls'.
void release(CoreYieldUpdate& r, const std::array<double, 9>& C, bool tearing) {
  const double book = tearing ? 0.5 : 0.0;
  const double szz = r.stress[2];
  r.plastic_work += book * szz * return_normal(r, C, 0.0);
  for (const auto& [k, modulus] : {std::pair{3, C[6]}, std::pair{4, C[7]}}) {
    const double tau = r.stress[k];
    r.plastic_work += book * tau * return_shear(r, k, modulus, 0.0);
  }
}

}  // namespace

CoreYieldUpdate core_yield_return(const Sym& trial_stress, const Sym& plastic_strain,
                                  double accumulated, double damage, const std::array<double, 9>& C,
                                  const CoreYield& caps) {
  CoreYieldUpdate r{trial_stress, plastic_strain, accumulated, damage, 0.0};
  if (caps.failure && damage >= 1.0) {  // torn before this step: carries nothing out of plane
    release(r, C, false);
    return r;
  }
  // sigma_zz (Voigt 2) against +-Y3; C = {C11, C22, C33, C12, C13, C23, C44, C55, C66}.
  const double szz = trial_stress[2];
  if (std::abs(szz) > caps.normal) {
    const double d = return_normal(r, C, std::copysign(caps.normal, szz));
    r.accumulated += std::abs(d);
    r.plastic_work += caps.normal * std::abs(d);
    if (caps.failure)
      r.damage += std::abs(d) / (d > 0 ? caps.failure->tension : caps.failure->compression);
  }
  // The shears: Voigt 3 = yz (C44 = G23), 4 = xz (C55 = G13).
  const struct {
    int k;
    double modulus, cap;
  } shears[2] = {{3, C[6], caps.shear_yz}, {4, C[7], caps.shear_xz}};
  for (const auto& s : shears) {
    const double tau = trial_stress[s.k];
    if (std::abs(tau) <= s.cap) continue;
    const double dgamma = return_shear(r, s.k, s.modulus, std::copysign(s.cap, tau));
    r.accumulated += std::abs(dgamma);
    r.plastic_work += s.cap * std::abs(dgamma);
    if (caps.failure) r.damage += std::abs(dgamma) / (std::sqrt(3.0) * caps.failure->shear);
  }
  if (caps.failure && r.damage >= 1.0) release(r, C, true);  // torn in this step
  return r;
}

}  // namespace hvi::fem
