#include "mpm/materials/hydro_material.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "materials/principal_stress.hpp"
#include "mpm/exact_sum.hpp"
#include "mpm/phase_timer.hpp"
#include "mpm/types.hpp"

namespace hvi::mpm {

namespace {

// Field names shared by every hydro material of a scene.
constexpr const char* eos_pressure = "eos_pressure";  // pressure without viscosity, Pa
constexpr const char* plastic_strain = "plastic_strain";
constexpr const char* plastic_strain_rate = "plastic_strain_rate";
constexpr const char* plastic_work = "plastic_work";  // J/kg
constexpr const char* viscous_work = "viscous_work";  // J/kg
constexpr const char* temperature = "temperature";    // K
constexpr const char* damage = "damage";
constexpr const char* spall_damage = "spall_damage";    // Tuler-Butcher D_s
constexpr const char* fracture_work = "fracture_work";  // g / G_f since damage initiated
constexpr const char* failure_scale = "failure_scale";  // the point's Weibull factor k
constexpr const char* failed = "failed";  // failure_state: 0 intact, 1 failed, 2 eroded

// Leaves a failed particle with its compressive mean stress only.
void strip_to_compression(double* s, double& pressure) {
  const double p = std::max(-trace_sym(s) / 3.0, 0.0);
  for (int c = 0; c < 6; ++c) s[c] = 0.0;
  s[sym::xx] = s[sym::yy] = s[sym::zz] = -p;
  pressure = std::max(pressure, 0.0);
}

struct Span {
  std::int64_t begin, end;
  explicit Span(ParticleRange r)
      : begin(static_cast<std::int64_t>(r.begin)), end(static_cast<std::int64_t>(r.end)) {}
};

// Points per chunk of the stress update's parallel loop: a yielding point costs several times an
// elastic one, and a static split left one thread the projectile's (1.3 times on 2 threads).
constexpr int chunk = 4096;

// Fails point p if it is intact and fails(sigma) is true: it keeps compression only.
template <class Criterion>
void fail_if(std::int64_t p, double* fl, double* pe, double* sigma, Criterion fails) {
  if (fl[p] > 0.0 || !fails(sigma)) return;
  fl[p] = failure_state::failed;
  strip_to_compression(sigma, pe[p]);
}

}  // namespace

HydroMaterial::HydroMaterial(std::string name, HydroModels models)
    : Material(std::move(name)),
      models_(std::move(models)),
      G_(models_.youngs_modulus / (2.0 * (1.0 + models_.poisson_ratio))),
      K_(models_.youngs_modulus / (3.0 * (1.0 - 2.0 * models_.poisson_ratio))),
      tension_modulus_(models_.eos ? models_.density * materials::bulk_sound_speed_squared(
                                                           *models_.eos, models_.density, 0.0)
                                   : K_),
      phase_name_(phase_name()) {}

void HydroMaterial::declare_fields(Particles& P) const {
  P.add_field(eos_pressure, FieldKind::scalar, "Pa", 0.0, false);
  if (models_.johnson_cook) {
    P.add_field(plastic_strain, FieldKind::scalar, "1");
    P.add_field(plastic_strain_rate, FieldKind::scalar, "1/s");
    P.add_field(plastic_work, FieldKind::scalar, "J/kg");
  }
  if (models_.viscosity) P.add_field(viscous_work, FieldKind::scalar, "J/kg");
  if (models_.heating) P.add_field(temperature, FieldKind::scalar, "K");
  if (models_.damage) P.add_field(damage, FieldKind::scalar, "1");
  if (models_.fracture_energy) P.add_field(fracture_work, FieldKind::scalar, "1");
  if (models_.scatter) P.add_field(failure_scale, FieldKind::scalar, "1");
  if (models_.tuler_butcher) P.add_field(spall_damage, FieldKind::scalar, "1");
  if (can_fail()) P.add_field(failed, FieldKind::scalar, "1");
}

void HydroMaterial::initialise(Particles& P, ParticleRange r) const {
  if (models_.heating) {
    auto& T = P.field(temperature);
    for (std::size_t p = r.begin; p < r.end; ++p) T[p] = models_.initial_temperature;
  }
  if (models_.scatter) {
    auto& k = P.field(failure_scale);
    for (std::size_t p = r.begin; p < r.end; ++p) k[p] = models_.scatter->factor(P.id[p]);
  }
}

double HydroMaterial::sound_speed(double rho_current, double p, bool is_failed) const {
  // Failed material carries no tension: expanded below its reference density it has no stiffness
  // until it is compressed back, and then its wave speed is the reference one. Its volume grows
  // without bound as it sprays apart, and K / rho at the current density would shrink the time
  // step for nothing (a particle expanded 3,800-fold alone cut it 30-fold in the demo at 0.2 mm).
  const double rho = is_failed ? std::max(rho_current, models_.density) : rho_current;
  const double bulk2 =
      models_.eos ? materials::bulk_sound_speed_squared(*models_.eos, rho, p) : K_ / rho;
  return wave_speed(bulk2, rho, is_failed);
}

double HydroMaterial::wave_speed(double bulk2, double rho, bool is_failed) const {
  const bool shear = models_.shear_strength && !is_failed;
  return std::sqrt(bulk2 + (shear ? 4.0 * G_ / (3.0 * rho) : 0.0));
}

double HydroMaterial::signal_speed(const Particles& P, std::size_t p, const double* pe,
                                   const double* fl) const {
  if (fl && fl[p] == failure_state::eroded) return speed(P, p);
  return sound_speed(P.mass[p] / P.volume[p], pe[p], fl && fl[p] > 0.0) + speed(P, p);
}

double HydroMaterial::max_signal_speed(const Particles& P, ParticleRange r) const {
  const double* pe = P.field(eos_pressure).data();
  const double* fl = can_fail() ? P.field(failed).data() : nullptr;
  double result = 0.0;
  const Span s(r);
#pragma omp parallel for reduction(max : result) schedule(static)
  for (std::int64_t p = s.begin; p < s.end; ++p)
    result = std::max(result, signal_speed(P, p, pe, fl));
  return result;
}

// The state fields of the models a material names (nullptr for the others).
struct HydroMaterial::State {
  double* pe;        // eos_pressure
  double* eps;       // plastic_strain
  double* eps_rate;  // plastic_strain_rate
  double* wp;        // plastic_work
  double* wq;        // viscous_work
  double* T;         // temperature
  double* D;         // damage
  double* Ds;        // spall_damage
  double* spent;     // fracture_work
  double* k;         // failure_scale
  double* fl;        // failed
};

HydroMaterial::State HydroMaterial::state(Particles& P) const {
  const auto get = [&](bool named, const char* name) {
    return named ? P.field(name).data() : nullptr;
  };
  const bool jc = models_.johnson_cook.has_value();
  return {P.field(eos_pressure).data(),
          get(jc, plastic_strain),
          get(jc, plastic_strain_rate),
          get(jc, plastic_work),
          get(models_.viscosity.has_value(), viscous_work),
          get(models_.heating.has_value(), temperature),
          get(models_.damage.has_value(), damage),
          get(models_.tuler_butcher.has_value(), spall_damage),
          get(models_.fracture_energy.has_value(), fracture_work),
          get(models_.scatter.has_value(), failure_scale),
          get(can_fail(), failed)};
}

// One phase for the whole update, named after the models it runs, for example
// "strength: johnson-cook | eos: mie-gruneisen + viscosity | damage: johnson-cook".
std::string HydroMaterial::phase_name() const {
  std::string name = models_.johnson_cook     ? "strength: johnson-cook"
                     : models_.shear_strength ? "strength: elastic"
                                              : "strength: none";
  name += std::string(" | eos: ") +
          (models_.eos ? materials::name_of(*models_.eos) : "elastic bulk") +
          (models_.viscosity ? " + viscosity" : "");
  if (models_.heating) name += " | heating: adiabatic";
  if (models_.damage) name += " | damage: johnson-cook";
  if (models_.fracture_energy) name += " + fracture-energy";
  if (models_.scatter) name += " | scatter: weibull";
  if (models_.max_principal_stress) name += " | failure: max-principal-stress";
  if (models_.tuler_butcher) name += " | failure: tuler-butcher";
  if (models_.erosion) name += " | erosion: compression";
  return name;
}

// Every model a scene names, point by point in one pass over the group: each model reads only
// the point's own state, so this is the same, to the bit, as a pass per model.
StressUpdate HydroMaterial::update_stress(Particles& P, ParticleRange r,
                                          const StressContext& ctx) const {
  PhaseTimer dummy;
  auto t = (ctx.timer ? *ctx.timer : dummy).scope(phase_name_);
  const State st = state(P);
  const double dt = ctx.dt;
  double signal = 0.0;
  std::int64_t first_bad = INT64_MAX;
  const Span s(r);
#pragma omp parallel for schedule(dynamic, chunk) reduction(max : signal) reduction(min : first_bad)
  for (std::int64_t p = s.begin; p < s.end; ++p) {
    EosState eos{};
    const bool eroded = st.fl && st.fl[p] == failure_state::eroded;  // no stress, volume frozen
    if (!eroded) {
      const VolumeChange V = advance_volume(P, static_cast<std::size_t>(p), dt);
      update_deviatoric(P, p, st, dt, V);
      update_pressure(P, p, st, dt, V, eos);
      if (st.T) update_temperature(P, p, st);
      if (models_.damage) accumulate_damage(P, p, st, dt);
      if (models_.max_principal_stress) check_principal_stress(P, p, st);
      if (models_.tuler_butcher) accumulate_spall(P, p, st, dt);
      if (models_.erosion) erode_crushed(P, p, st, dt, V);
    }
    const double* sigma = &P.stress[6 * p];
    if (!(P.volume[p] > 0.0) || !std::isfinite(sigma[0] + sigma[1] + sigma[2] + sigma[3] +
                                               sigma[4] + sigma[5] + P.internal_energy[p])) {
      first_bad = std::min(first_bad, p);
      continue;
    }
    // The signal speed at the end of the step: an intact point's EOS state is the one the pressure
    // update used (the same density).
    const bool intact = !st.fl || st.fl[p] == failure_state::intact;
    const double c =
        !eroded && intact && models_.eos
            ? wave_speed(materials::bulk_sound_speed_squared(*models_.eos, eos, st.pe[p]), eos.rho,
                         false) +
                  speed(P, static_cast<std::size_t>(p))
            : signal_speed(P, static_cast<std::size_t>(p), st.pe, st.fl);
    signal = std::max(signal, c);
  }
  return StressUpdate::of(signal, first_bad,
                          "non-positive volume, or non-finite stress or internal energy");
}

// Deviatoric stress: Jaumann-rate elastic trial, then (Johnson-Cook) radial return. Adds the
// deviatoric work to the internal energy and, for Johnson-Cook, the plastic work.
void HydroMaterial::update_deviatoric(Particles& P, std::int64_t p, const State& st, double dt,
                                      const VolumeChange& V) const {
  const JohnsonCookStrength* jc = models_.johnson_cook ? &*models_.johnson_cook : nullptr;
  const double G = G_;
  double D[6], W[9], spin[6];
  split_velocity_gradient(&P.velocity_gradient[9 * p], D, W);
  constexpr double third = 1.0 / 3.0;
  const double trD = D[sym::xx] + D[sym::yy] + D[sym::zz];
  D[sym::xx] -= trD * third;
  D[sym::yy] -= trD * third;
  D[sym::zz] -= trD * third;  // D is now the deviator D'

  double* sigma = &P.stress[6 * p];
  const double mean = trace_sym(sigma) * third;
  double s_old[6], s_new[6];
  for (int c = 0; c < 6; ++c) s_old[c] = sigma[c];
  s_old[sym::xx] -= mean;
  s_old[sym::yy] -= mean;
  s_old[sym::zz] -= mean;

  const double inv_rho_mid = (V.before + V.after) / (2.0 * P.mass[p]);  // 1 / the mid-step density

  if ((st.fl && st.fl[p] > 0.0) || !models_.shear_strength) {
    for (int c = 0; c < 6; ++c) s_new[c] = 0.0;
    if (st.eps_rate) st.eps_rate[p] = 0.0;
  } else {
    jaumann_spin_term(W, s_old, spin);
    for (int c = 0; c < 6; ++c) s_new[c] = s_old[c] + dt * (2.0 * G * D[c] + spin[c]);
    if (jc) {
      const double q_trial = von_mises(s_new);
      const double rate = std::sqrt(2.0 / 3.0 * contract_sym(D, D));
      const double temp = st.T ? st.T[p] : models_.initial_temperature;
      // A softening point's flow stress is (1 - omega) of the intact one.
      const double intact = st.spent ? FractureEnergy::intact(st.spent[p]) : 1.0;
      const double d_eps = materials::radial_return(
          *jc, q_trial, G, st.eps[p], jc->rate_factor(rate), jc->thermal_factor(temp) * intact);
      if (d_eps > 0.0) {
        const double q = q_trial - 3.0 * G * d_eps;  // the yield stress reached
        const double scale = q / q_trial;
        for (int c = 0; c < 6; ++c) s_new[c] *= scale;
        st.eps[p] += d_eps;
        st.wp[p] += q * d_eps * inv_rho_mid;
        soften(st, p, q * d_eps * inv_rho_mid);
      }
      st.eps_rate[p] = d_eps / dt;
    }
  }
  double s_mid[6];
  for (int c = 0; c < 6; ++c) s_mid[c] = 0.5 * (s_old[c] + s_new[c]);
  P.internal_energy[p] += dt * contract_sym(s_mid, D) * inv_rho_mid;
  // Mean stress of the previous step's pressure for now; update_pressure replaces it.
  for (int c = 0; c < 6; ++c) sigma[c] = s_new[c];
  sigma[sym::xx] -= st.pe[p];
  sigma[sym::yy] -= st.pe[p];
  sigma[sym::zz] -= st.pe[p];
}

// Pressure from the bulk response or the equation of state, with the volumetric and viscous
// work in the internal energy: e_n+1 = e_n - ((p_n + p_n+1) / 2 + q) dV / m, solved in closed
// form for p = cold + B e (every registered EOS is linear in e at a fixed density).
void HydroMaterial::update_pressure(Particles& P, std::int64_t p, const State& st, double dt,
                                    const VolumeChange& volume, EosState& eos) const {
  const EquationOfState* law = models_.eos ? &*models_.eos : nullptr;
  const ArtificialViscosity* av = models_.viscosity ? &*models_.viscosity : nullptr;
  const double* L = &P.velocity_gradient[9 * p];
  const double trD = L[0] + L[4] + L[8];
  const double m = P.mass[p], V = volume.after;
  const double dV_m = (V - volume.before) / m;  // dV / m
  const double rho = m / V;
  const bool is_failed = st.fl && st.fl[p] > 0.0;
  const double p_old = st.pe[p];
  if (law) eos = materials::state_at(*law, rho);  // at the end-of-step density

  double q = 0.0;
  if (av && trD < 0.0) {
    const double c =
        is_failed || !law
            ? sound_speed(rho, p_old, is_failed)
            : wave_speed(materials::bulk_sound_speed_squared(*law, eos, p_old), rho, false);
    q = rho * av->length * (av->linear * c * -trD + av->quadratic * av->length * trD * trD);
    st.wq[p] += -q * dV_m;
  }
  double& e = P.internal_energy[p];
  double p_new;
  // A softening point keeps (1 - omega) of its equation of state's tension (the scene reader
  // refuses a fracture energy without an equation of state).
  const double intact = st.spent ? FractureEnergy::intact(st.spent[p]) : 1.0;
  if (law) {
    const double e_star = e - (0.5 * p_old + q) * dV_m;
    p_new = (eos.cold + eos.B * e_star) / (1.0 + 0.5 * eos.B * dV_m);
    if (is_failed) p_new = std::max(p_new, 0.0);
    if (p_new < 0.0) p_new *= intact;
    e = e_star - 0.5 * p_new * dV_m;
  } else {
    p_new = p_old - K_ * trD * dt;
    if (is_failed) p_new = std::max(p_new, 0.0);
    e -= (0.5 * (p_old + p_new) + q) * dV_m;
  }
  // Once damage has initiated, an opening is a crack's: the net work of the tension on it (the
  // closing gives back what the opening took), with the plastic work, is what the crack
  // dissipates.
  if (st.spent) soften(st, p, -std::min(0.5 * (p_old + p_new), 0.0) * dV_m);
  st.pe[p] = p_new;
  double* sigma = &P.stress[6 * p];
  const double shift = p_old - p_new - q;
  sigma[sym::xx] += shift;
  sigma[sym::yy] += shift;
  sigma[sym::zz] += shift;
}

// Adiabatic heating: T = T0 + chi w_p / c_v.
void HydroMaterial::update_temperature(Particles&, std::int64_t p, const State& st) const {
  const double factor = models_.heating->taylor_quinney / models_.heating->specific_heat;
  st.T[p] = models_.initial_temperature + (st.wp ? factor * st.wp[p] : 0.0);
}

// With a fracture energy, g / G_f += rho_0 L dw / G_f for the energy dw (J/kg) a point that has
// initiated (D = 1) dissipates: its plastic work, and what its opening releases.
void HydroMaterial::soften(const State& st, std::int64_t p, double work) const {
  if (!st.spent || st.D[p] < 1.0) return;
  const double share = models_.fracture_energy->share(models_.density, work);
  st.spent[p] = std::clamp(st.spent[p] + share, 0.0, 1.0);
}

// D += d eps_p / (k eps_f(sigma*, epsdot_p*, T*)), k the point's scatter factor (1 without);
// failure at D = 1, or with a fracture energy once the point has spent G_f (omega = 1).
void HydroMaterial::accumulate_damage(Particles& P, std::int64_t p, const State& st,
                                      double dt) const {
  const JohnsonCookStrength* jc = models_.johnson_cook ? &*models_.johnson_cook : nullptr;
  if (!jc) return;  // without plastic flow there is no damage to accumulate
  const JohnsonCookDamage& jd = *models_.damage;
  const double rate = st.eps_rate[p];
  fail_if(p, st.fl, st.pe, &P.stress[6 * p], [&](const double* sigma) {
    if (st.spent && st.D[p] >= 1.0) return st.spent[p] >= 1.0;
    if (rate <= 0.0) return false;
    const double eq = von_mises(sigma);
    const double triaxiality = eq > 0.0 ? trace_sym(sigma) / 3.0 / eq : 0.0;
    const double T = st.T ? st.T[p] : models_.initial_temperature;
    const double eps_f = jd.failure_strain(triaxiality, rate, jc->homologous_temperature(T)) *
                         (st.k ? st.k[p] : 1.0);
    st.D[p] = std::min(st.D[p] + rate * dt / eps_f, 1.0);
    return !st.spent && st.D[p] >= 1.0;  // softening starts here
  });
}

// Spall: failure when the largest principal stress reaches k sigma_max.
void HydroMaterial::check_principal_stress(Particles& P, std::int64_t p, const State& st) const {
  const double limit = *models_.max_principal_stress * (st.k ? st.k[p] : 1.0);
  fail_if(p, st.fl, st.pe, &P.stress[6 * p],
          [&](const double* sigma) { return materials::principal_reaches(sigma, limit); });
}

// Time-dependent spall: D_s += dt max(sigma_1 / sigma_0 - 1, 0)^lambda / tau; failure at D_s = 1.
void HydroMaterial::accumulate_spall(Particles& P, std::int64_t p, const State& st,
                                     double dt) const {
  const TulerButcher& tb = *models_.tuler_butcher;
  fail_if(p, st.fl, st.pe, &P.stress[6 * p], [&](const double* sigma) {
    // Below the threshold the rate is 0 and D_s stays as it is.
    if (materials::principal_reaches(sigma, tb.threshold))
      st.Ds[p] = std::min(st.Ds[p] + dt * tb.damage_rate(materials::max_principal(sigma)), 1.0);
    return st.Ds[p] >= 1.0;
  });
}

// Erosion: a point crushed below V / V0 = r_min loses its stress for good. Its mass and momentum
// stay on the grid (momentum is untouched) and its internal energy stays in the balance, less the
// work this step booked in advance: the update adds (p_n + p_n+1) / 2 dV + q dV and s_mid : D dt,
// of which the grid pays the p_n+1, q and s_n+1 parts only in the next step, through the stress
// that erosion now zeroes. Left in, that unpaid work appeared as energy: +4.6% instead of +1.3% in
// the thin-wall hard case with r_min = 0.8 (474 points eroded).
void HydroMaterial::erode_crushed(Particles& P, std::int64_t p, const State& st, double dt,
                                  const VolumeChange& volume) const {
  const double r_min = models_.erosion->min_volume_ratio;
  if (st.fl[p] == failure_state::eroded || !(P.volume[p] < r_min * P.volume0[p])) return;
  double* sigma = &P.stress[6 * p];
  const double m = P.mass[p], V = volume.after, V_before = volume.before;
  const double dV = V - V_before, rho_mid = 2.0 * m / (V + V_before);
  const double mean = trace_sym(sigma) / 3.0;
  const double q = -mean - st.pe[p];  // the viscous part of the mean stress
  // s : D' = s : D, the deviator s being traceless.
  double D[6], W[9], dev[6];
  split_velocity_gradient(&P.velocity_gradient[9 * p], D, W);
  for (int c = 0; c < 6; ++c) dev[c] = sigma[c];
  for (const int c : {sym::xx, sym::yy, sym::zz}) dev[c] -= mean;
  P.internal_energy[p] += (0.5 * st.pe[p] + q) * dV / m - 0.5 * dt * contract_sym(dev, D) / rho_mid;
  if (st.wq) st.wq[p] += q * dV / m;
  st.fl[p] = failure_state::eroded;
  for (int c = 0; c < 6; ++c) sigma[c] = 0.0;
  st.pe[p] = 0.0;
  if (st.eps_rate) st.eps_rate[p] = 0.0;
}

void HydroMaterial::add_dissipated_energy(const Particles& P, ParticleRange r,
                                          ExactSum& sum) const {
  const double* wp = models_.johnson_cook ? P.field(plastic_work).data() : nullptr;
  const double* wq = models_.viscosity ? P.field(viscous_work).data() : nullptr;
  if (!wp && !wq) return;
  for (std::size_t p = r.begin; p < r.end; ++p)
    sum += P.mass[p] * ((wp ? wp[p] : 0.0) + (wq ? wq[p] : 0.0));
}

}  // namespace hvi::mpm
