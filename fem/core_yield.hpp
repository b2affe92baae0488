#pragma once
// Yield of the far field's homogenised honeycomb core (far_field.core = "yielding"): the stresses
// the walls carry, the out-of-plane normal sigma_zz and the two transverse shears sigma_xz,
// sigma_yz, are each capped where the walls yield, elastic-perfectly plastic and uncoupled, as a
// honeycomb core's strengths are quoted (flatwise tension and compression, L and W shear) and as
// LS-DYNA's *MAT_HONEYCOMB treats the uncompacted core. The in-plane stresses, carried by wall
// bending at 1e-4 of the facesheets' stiffness, stay elastic.
//
// The caps follow from the same kinematics as the moduli (fem/orthotropic.hpp): the walls of a
// core strained along z carry sigma_s = E_s eps, so sigma_zz = (E3 / E_s) sigma_s; sheared in xz
// (yz) they carry tau_s = G_s gamma, so sigma_xz = (G13 / G_s) tau_s. With the walls' yield
// stress sigma_ys (their Johnson-Cook A) and von Mises' tau_ys = sigma_ys / sqrt(3):
//   sigma_zz in [-Y3, Y3],  Y3 = (E3 / E_s) sigma_ys = sigma_ys rho*/rho_s
//   |sigma_xz| <= Y13 = (G13 / G_s) sigma_ys / sqrt(3)       (= sigma_ys t / (sqrt(3) D), single
//   walls) |sigma_yz| <= Y23 = (G23 / G_s) sigma_ys / sqrt(3)
// The compressive cap is the walls' squash load, an upper bound: thin walls buckle and fold
// first (Wierzbicki 1983), so crushing starts lower in a real core; in tension and shear the walls
// yield as assumed.
//
// The return (per component, with sigma = C (eps - eps_p) and C orthotropic): a trial sigma_zz
// beyond its cap takes d eps_p,zz = (sigma_zz - cap) / C33, which also lowers sigma_xx and sigma_yy
// by C13 and C23 times it; a trial shear beyond its cap takes d gamma_p = (tau - cap) / C44 (or
// C55) in engineering strain, half of it in the tensor component. The work of the step per unit
// volume, cap |d eps_p| summed, is never negative.
//
// A failing core (far_field.core = "failing") adds the walls' Johnson-Cook damage, the paper's
// eqs. (2)-(3) with the rate and thermal factors at 1 (as the far field's hardening): each step's
// plastic strain of the walls over their failure strain at the triaxiality of its mode,
//   D += |d eps_p,zz| / eps_f(+-1/3) + (|d gamma_p,xz| + |d gamma_p,yz|) / (sqrt(3) eps_f(0)),
// for a wall strained along z is in uniaxial stress (triaxiality 1/3 in tension, -1/3 in
// compression) and a sheared wall in pure shear (0, its equivalent strain gamma / sqrt(3)). Where
// D reaches 1 the walls are torn: sigma_zz, sigma_xz and sigma_yz drop to zero then and stay
// there (the strain goes to eps_p), as the MPM's failed wall points carry no tension or shear.
// Crushed walls that compact again (densification, at strains near 1 - rho*/rho_s) are not
// modelled. The elastic energy the drop releases, 1/2 (sigma_before + sigma_after) : d eps_p
// exactly for a linear solid, is booked as work in the step of the tear, and nothing after (a torn
// point exerts no force), so the energy balance holds through failure.
#include <array>
#include <optional>

#include "fem/j2_plasticity.hpp"
#include "fem/orthotropic.hpp"
#include "materials/johnson_cook_damage.hpp"

namespace hvi::fem {

// The walls' failure strains eps_f = D1 + D2 exp(D3 triaxiality) in each mode.
struct CoreFailure {
  double tension = 0;      // triaxiality 1/3
  double compression = 0;  // -1/3
  double shear = 0;        // 0
};

CoreFailure honeycomb_core_failure(const materials::JohnsonCookDamage& walls);

struct CoreYield {
  double normal = 0;                   // Y3, Pa: |sigma_zz| at yield
  double shear_xz = 0;                 // Y13, Pa
  double shear_yz = 0;                 // Y23, Pa
  std::optional<CoreFailure> failure;  // a failing core; none: the caps hold at any strain
};

// The caps above from the core's moduli, its walls' E_s, nu_s and yield stress sigma_ys.
CoreYield honeycomb_core_yield(const Orthotropic& core, double wall_youngs_modulus,
                               double wall_poisson_ratio, double wall_yield_stress);

struct CoreYieldUpdate {
  Sym stress{};
  Sym plastic_strain{};  // tensor shears, as Sym
  double accumulated =
      0.0;              // sum of |d eps_p,zz| + |d gamma_p,xz| + |d gamma_p,yz| so far (to a tear)
  double damage = 0.0;  // D of a failing core (>= 1: failed); 0 otherwise
  double plastic_work = 0.0;  // J/m^3 over the step
};

// `trial_stress` = C (eps - eps_p,n); `C` the nine entries of fem::stiffness(); `damage` D at the
// start of the step (a failing core's; 0 otherwise).
CoreYieldUpdate core_yield_return(const Sym& trial_stress, const Sym& plastic_strain,
                                  double accumulated, double damage, const std::array<double, 9>& C,
                                  const CoreYield& caps);

}  // namespace hvi::fem
