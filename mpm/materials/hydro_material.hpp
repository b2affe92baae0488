#pragma once
// A hydrocode metal: isotropic elasticity plus the models a scene names, each optional and each
// its own phase of the stress update (paper Sec. 2.2):
//   strength   none (hydrodynamic: no deviatoric stress), elastic (no yield), or Johnson-Cook
//              (eq. 1) with radial return
//   pressure   hypoelastic bulk response, or the Mie-Grüneisen EOS (eqs. 4-5) coupled to the
//              specific internal energy
//   viscosity  artificial bulk viscosity q (linear + quadratic) in compression
//   heating    adiabatic: T = T0 + chi w_p / c_v from the plastic work w_p
//   damage     Johnson-Cook (eqs. 2-3); a particle fails when D reaches 1
//   failure    max principal stress: a particle fails when sigma_1 reaches sigma_max
// Failed material keeps only compressive pressure: no deviatoric stress, no tension.
// A model that is not named declares no field and runs no loop.
#include <optional>

#include "mpm/material.hpp"
#include "mpm/materials/johnson_cook.hpp"
#include "mpm/materials/johnson_cook_damage.hpp"
#include "mpm/materials/mie_gruneisen.hpp"

namespace hvi::mpm {

struct AdiabaticHeating {
  double specific_heat = 0;      // c_v, J/(kg K)
  double taylor_quinney = 0.9;   // fraction chi of plastic work turned into heat
};

// q = rho l (linear c |tr D| + quadratic l (tr D)^2) for tr D < 0, l the grid cell size.
struct ArtificialViscosity {
  double linear = 0.2, quadratic = 1.0;  // AUTODYN's defaults; they hold the plate-impact
                                          // shock to 3-5 cells with <20% overshoot
  double length = 0;                      // m
};

struct HydroModels {
  double density = 0, youngs_modulus = 0, poisson_ratio = 0;
  double initial_temperature = 293.0;  // K
  bool shear_strength = true;  // false: hydrodynamic, the deviatoric stress stays zero
  std::optional<JohnsonCookStrength> johnson_cook;
  std::optional<MieGruneisen> mie_gruneisen;
  std::optional<ArtificialViscosity> viscosity;
  std::optional<AdiabaticHeating> heating;
  std::optional<JohnsonCookDamage> damage;
  std::optional<double> max_principal_stress;  // sigma_max, Pa
};

class HydroMaterial : public Material {
 public:
  HydroMaterial(std::string name, HydroModels models);

  void declare_fields(Particles& particles) const override;
  void initialise(Particles& particles, ParticleRange range) const override;
  double max_signal_speed(const Particles& particles, ParticleRange range) const override;
  StressUpdate update_stress(Particles& particles, ParticleRange range,
                             const StressContext& context) const override;
  double dissipated_energy(const Particles& particles, ParticleRange range) const override;
  double reference_density() const override { return models_.density; }

  const HydroModels& models() const { return models_; }
  double shear_modulus() const { return G_; }
  double bulk_modulus() const { return K_; }
  // Sound speed (bulk and, for intact material, shear) at density rho and pressure p.
  double sound_speed(double rho, double p, bool failed) const;

 private:
  void update_deviatoric(Particles& P, ParticleRange r, double dt) const;
  void update_pressure(Particles& P, ParticleRange r, double dt) const;
  void update_temperature(Particles& P, ParticleRange r) const;
  void accumulate_damage(Particles& P, ParticleRange r, double dt) const;
  void check_principal_stress(Particles& P, ParticleRange r) const;
  double signal_speed_and_check(Particles& P, ParticleRange r, std::int64_t& bad) const;
  bool can_fail() const { return models_.damage || models_.max_principal_stress; }

  HydroModels models_;
  double G_, K_;
};

}  // namespace hvi::mpm
