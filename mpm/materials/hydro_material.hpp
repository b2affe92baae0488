#pragma once
// A hydrocode metal: isotropic elasticity plus the models a scene names, each optional and each
// its own phase of the stress update (paper Sec. 2.2):
//   strength   none (hydrodynamic: no deviatoric stress), elastic (no yield), or Johnson-Cook
//              (eq. 1) with radial return
//   pressure   hypoelastic bulk response, or an equation of state (materials/equation_of_state.hpp:
//              the Mie-Grüneisen EOS, eqs. 4-5) coupled to the specific internal energy
//   viscosity  artificial bulk viscosity q (linear + quadratic) in compression
//   heating    adiabatic: T = T0 + chi w_p / c_v from the plastic work w_p
//   damage     Johnson-Cook (eqs. 2-3); a particle fails when D reaches 1, or with a
//              fracture energy softens from there and fails when it has dissipated G_f per
//              unit area of a one-cell band (materials/fracture_energy.hpp)
//   scatter    Weibull: each point's failure strain and spall strength times its own factor
//              of unit mean (materials/weibull_scatter.hpp)
//   failure    max principal stress: a particle fails when sigma_1 reaches sigma_max; or
//              Tuler-Butcher: when the impulse of sigma_1 above sigma_0 reaches K
//   erosion    compression: a particle crushed below V/V0 = r_min is eroded
// Failed material keeps only compressive pressure: no deviatoric stress, no tension. Eroded
// material keeps its mass, momentum and internal energy but no stress at all: it moves as a free
// point mass, its volume frozen (the hydrocode's "retain inertia of eroded nodes").
// A model that is not named declares no field and runs no code. The update is one pass over the
// material's points, each model in turn on each point, timed as one phase named after the models.
#include <optional>

#include "materials/equation_of_state.hpp"
#include "materials/fracture_energy.hpp"
#include "materials/johnson_cook.hpp"
#include "materials/johnson_cook_damage.hpp"
#include "materials/tuler_butcher.hpp"
#include "materials/weibull_scatter.hpp"
#include "mpm/material.hpp"

namespace hvi::mpm {

// The laws the models below are made of (materials/).
using materials::EosState;
using materials::EquationOfState;
using materials::FractureEnergy;
using materials::JohnsonCookDamage;
using materials::JohnsonCookStrength;
using materials::MieGruneisen;
using materials::TulerButcher;
using materials::WeibullScatter;

struct AdiabaticHeating {
  double specific_heat = 0;     // c_v, J/(kg K)
  double taylor_quinney = 0.9;  // fraction chi of plastic work turned into heat
};

// q = rho l (linear c |tr D| + quadratic l (tr D)^2) for tr D < 0, l the grid cell size.
struct ArtificialViscosity {
  double linear = 0.2, quadratic = 1.0;  // AUTODYN's defaults; they hold the plate-impact
                                         // shock to 3-5 cells with <20% overshoot
  double length = 0;                     // m
};

// Erosion by compression. A small point caught in a cell with fast, heavy material is squeezed by
// that material's velocity field however stiff it is: at 0.25 mm cells the study's 0.05 mm core
// walls and 1/24 mm front-sheet fragments driven into the core were crushed to V/V0 = 0.28-0.33,
// near the Mie-Grüneisen cap (V/V0 = 0.27), at 0.3-5 TPa, and their sound speed cut the time step
// 20-fold. No shock in the 1-7 km/s range compresses aluminium that far (a 7 km/s Al-on-Al
// impact: V/V0 = 0.65 on the Hugoniot; V/V0 = 0.5 needs about 16 km/s), so such a state is the
// grid's, not the metal's.
struct CompressionErosion {
  double min_volume_ratio = 0.5;  // r_min: erode when V / V0 < r_min
};

// Values of the "failed" particle field.
namespace failure_state {
constexpr double intact = 0.0, failed = 1.0, eroded = 2.0;
}

struct HydroModels {
  double density = 0, youngs_modulus = 0, poisson_ratio = 0;
  double initial_temperature = 293.0;  // K
  bool shear_strength = true;          // false: hydrodynamic, the deviatoric stress stays zero
  std::optional<JohnsonCookStrength> johnson_cook;
  std::optional<EquationOfState> eos;  // none: the elastic bulk response
  std::optional<ArtificialViscosity> viscosity;
  std::optional<AdiabaticHeating> heating;
  std::optional<JohnsonCookDamage> damage;
  std::optional<FractureEnergy> fracture_energy;  // after damage initiates; none: fail at D = 1
  std::optional<WeibullScatter> scatter;          // of the failure strain and spall strength
  std::optional<double> max_principal_stress;     // sigma_max, Pa
  std::optional<TulerButcher> tuler_butcher;
  std::optional<CompressionErosion> erosion;

  // The equation of state if it is a `Law`, else nullptr.
  template <class Law>
  const Law* eos_as() const {
    return eos ? std::get_if<Law>(&*eos) : nullptr;
  }
};

class HydroMaterial : public Material {
 public:
  HydroMaterial(std::string name, HydroModels models);

  void declare_fields(Particles& particles) const override;
  void initialise(Particles& particles, ParticleRange range) const override;
  double max_signal_speed(const Particles& particles, ParticleRange range) const override;
  StressUpdate update_stress(Particles& particles, ParticleRange range,
                             const StressContext& context) const override;
  void add_dissipated_energy(const Particles& particles, ParticleRange range,
                             ExactSum& sum) const override;
  double reference_density() const override { return models_.density; }

  const HydroModels& models() const { return models_; }
  double shear_modulus() const { return G_; }
  double bulk_modulus() const { return K_; }
  // Sound speed (bulk and, for intact material, shear) at density rho and pressure p.
  double sound_speed(double rho, double p, bool failed) const;
  // Fastest signal of particle p: |v| plus its sound speed (an eroded point carries no wave).
  double signal_speed(const Particles& P, std::size_t p, const double* pressure,
                      const double* failed_state) const;

 private:
  struct State;
  State state(Particles& P) const;
  std::string phase_name() const;
  // The models' work on point p over one step, in this order.
  void update_deviatoric(Particles& P, std::int64_t p, const State& st, double dt,
                         const VolumeChange& V) const;
  void update_pressure(Particles& P, std::int64_t p, const State& st, double dt,
                       const VolumeChange& V, EosState& eos) const;
  // sqrt(c_bulk^2 + 4 G / (3 rho)), without the shear wave where there is no strength.
  double wave_speed(double bulk2, double rho, bool failed) const;
  void update_temperature(Particles& P, std::int64_t p, const State& st) const;
  void soften(const State& st, std::int64_t p, double work) const;
  void accumulate_damage(Particles& P, std::int64_t p, const State& st, double dt) const;
  void check_principal_stress(Particles& P, std::int64_t p, const State& st) const;
  void accumulate_spall(Particles& P, std::int64_t p, const State& st, double dt) const;
  void erode_crushed(Particles& P, std::int64_t p, const State& st, double dt,
                     const VolumeChange& V) const;
  // The "failed" field exists when a model can fail or erode a particle.
  bool can_fail() const {
    return models_.damage || models_.max_principal_stress || models_.tuler_butcher ||
           models_.erosion;
  }

  HydroModels models_;
  double G_, K_;
  double tension_modulus_;  // the bulk modulus at the reference state: a tension's stored energy
  std::string phase_name_;  // its row in the timing table
};

}  // namespace hvi::mpm
