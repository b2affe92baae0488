#pragma once
// J2 (von Mises) plasticity of the far field's facesheets at a quadrature point. The strain (the
// small strain, or with finite kinematics the Green-Lagrange strain, whose work conjugate S then
// takes sigma's place) splits additively, eps = eps_e + eps_p; sigma = lambda tr(eps_e) I + 2 mu
// eps_e; the yield stress follows the Johnson-Cook hardening curve of the facesheet's material at
// room temperature (the paper's eq. 1 with its thermal factor 1):
//   sigma_y(alpha) = (A + B alpha^n) k,   k = 1 + C ln(max(epsdot / epsdot_0, 1)),
// with the rate factor k frozen over the step as the material points freeze it
// (materials/johnson_cook.hpp). k = 1 (the reference rate) unless the far field is asked for
// the rate (far_field.strain_rate = "johnson-cook"): the far field is the panel away from the
// impact, where heating is small, but a panel ringing over tens of microseconds strains its
// sheets at 1e2-1e4 /s, where k is 1.07-1.14 for the paper's C = 0.015.
//
// Backward-Euler radial return (the closest point on the von Mises cylinder), with the safeguarded
// Newton solve of materials/johnson_cook.hpp:
//   sigma_trial = C (eps - eps_p,n),  s_trial = dev sigma_trial,  q_trial = sqrt(3/2 s:s)
//   q_trial - 3 mu dgamma = sigma_y(alpha_n + dgamma) k          (dgamma = 0 inside the surface)
//   eps_p,n+1 = eps_p,n + 3/2 dgamma s_trial / q_trial,  alpha_n+1 = alpha_n + dgamma
//   sigma = p_trial I + (1 - 3 mu dgamma / q_trial) s_trial
// The plastic work of the step per unit volume is sigma_n+1 : d eps_p = dgamma q_n+1.
//
// Failing facesheets (far_field.plasticity = "failing") add the Johnson-Cook damage of their
// material, the paper's eqs. (2)-(3) with the thermal factor at 1 (as the hardening) and the rate
// factor (1 + D4 ln epsdot_p*) of the step's plastic strain rate dgamma / dt, as the points take it
// (1 at the reference rate):
//   D += dgamma / eps_f(eta),  eps_f(eta) = (D1 + D2 exp(D3 eta)) (1 + D4 ln epsdot_p*),  eta = p /
//   q_n+1
// at the returned stress. Where D reaches 1 the point is torn and keeps, as the MPM's failed
// points do (mpm/materials/hydro_material.hpp), only the pressure of its volume when compressed
// below the reference one:
//   sigma -> p_kept I,  p_kept = K min(tr eps, 0),  d eps_p = s / (2 mu) + (p - p_kept) / (3 K) I,
// the strain the dropped stress stood on moved into eps_p (so a torn point pulled open and pushed
// back carries pressure again only past its reference volume, as an MPM point's EOS does). The
// elastic energy the drop releases, 1/2 (sigma_before + sigma_after) : d eps_p (exact for a linear
// solid, and sigma_after : d eps_p = p_kept (p - p_kept) / K = 0), is booked as plastic work in the
// step of the tear. In later steps the same drop books nothing: the deviatoric and tensile parts
// of a torn point's trial stress come from the strain increment of the elastic predictor, which
// never held energy. A torn point's alpha stays what it had taken at the tear.
#include <array>

#include "materials/johnson_cook.hpp"
#include "materials/johnson_cook_damage.hpp"

namespace hvi::fem {

// Symmetric tensors in Voigt order xx, yy, zz, yz, xz, xy, tensor (not engineering) shears.
using Sym = std::array<double, 6>;

struct J2State {
  Sym plastic_strain{};
  double alpha = 0.0;   // equivalent plastic strain, sqrt(2/3 eps_p : eps_p) for radial flow
  double damage = 0.0;  // D of failing facesheets (>= 1: torn); 0 otherwise
};

struct J2Update {
  Sym stress{};
  J2State state;
  double plastic_work = 0.0;  // J/m^3 over the step
};

// How fast the point strains over the step: its equivalent deviatoric strain rate
// sqrt(2/3 e':e') / dt (e the strain increment), the rate the material points' yield stress takes,
// and dt. dt = 0: the reference rate (k = 1, and the damage's rate factor 1).
struct StrainRate {
  double equivalent = 0.0;  // 1/s
  double dt = 0.0;          // s
};

// `trial_stress`: C (eps - eps_p,n) of the isotropic material with shear modulus mu.
J2Update j2_return(const Sym& trial_stress, const J2State& old, double mu,
                   const materials::JohnsonCookStrength& hardening, const StrainRate& rate = {});

// The same for failing facesheets, with bulk modulus K and Johnson-Cook damage `damage`.
J2Update j2_return(const Sym& trial_stress, const J2State& old, double mu, double K,
                   const materials::JohnsonCookStrength& hardening,
                   const materials::JohnsonCookDamage& damage, const StrainRate& rate = {});

// The equivalent deviatoric strain rate of a strain increment `de` (Voigt, tensor shears) over dt
// (> 0): sqrt(2/3 de':de') / dt.
double equivalent_strain_rate(const Sym& de, double dt);

}  // namespace hvi::fem
