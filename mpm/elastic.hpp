#pragma once
// Isotropic linear elasticity in rate form with the Jaumann (co-rotational) stress rate, so that
// rigid rotations leave the stress unrotated relative to the material:
//   d(sigma)/dt = lambda tr(D) I + 2 mu D + W sigma - sigma W,
// D and W the symmetric and skew parts of the velocity gradient. Specific internal energy
// integrates the stress power with the mid-step stress and volume:
//   de = dt (sigma_n + sigma_n+1)/2 : D / rho_mid.
#include "mpm/material.hpp"

namespace hvi::mpm {

class LinearElastic : public Material {
 public:
  LinearElastic(std::string name, double density, double youngs_modulus, double poisson_ratio);

  double max_signal_speed(const Particles& particles, ParticleRange range) const override;
  StressUpdate update_stress(Particles& particles, ParticleRange range,
                             const StressContext& context) const override;
  double reference_density() const override { return density_; }

  double lame_lambda() const { return lambda_; }
  double shear_modulus() const { return mu_; }
  // Longitudinal (P-wave) speed at density rho: sqrt((lambda + 2 mu) / rho).
  double p_wave_speed(double rho) const;

 private:
  double density_, lambda_, mu_;
};

}  // namespace hvi::mpm
