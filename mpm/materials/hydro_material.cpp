#include "mpm/materials/hydro_material.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "mpm/materials/principal_stress.hpp"
#include "mpm/phase_timer.hpp"
#include "mpm/types.hpp"

namespace hvi::mpm {

namespace {

// Field names shared by every hydro material of a scene.
constexpr const char* eos_pressure = "eos_pressure";    // pressure without viscosity, Pa
constexpr const char* plastic_strain = "plastic_strain";
constexpr const char* plastic_strain_rate = "plastic_strain_rate";
constexpr const char* plastic_work = "plastic_work";    // J/kg
constexpr const char* viscous_work = "viscous_work";    // J/kg
constexpr const char* temperature = "temperature";      // K
constexpr const char* damage = "damage";
constexpr const char* spall_damage = "spall_damage";    // Tuler-Butcher D_s
constexpr const char* failed = "failed";                // failure_state: 0 intact, 1 failed, 2 eroded

// Volume at the start of the step, from the end-of-step volume and det(I + dt L).
double volume_before(const Particles& P, std::size_t p, double dt) {
  const double* L = &P.velocity_gradient[9 * p];
  const double a = 1 + dt * L[0], b = dt * L[1], c = dt * L[2];
  const double d = dt * L[3], e = 1 + dt * L[4], f = dt * L[5];
  const double g = dt * L[6], h = dt * L[7], i = 1 + dt * L[8];
  return P.volume[p] / (a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g));
}

// Leaves a failed particle with its compressive mean stress only.
void strip_to_compression(double* s, double& pressure) {
  const double p = std::max(-trace_sym(s) / 3.0, 0.0);
  for (int c = 0; c < 6; ++c) s[c] = 0.0;
  s[sym::xx] = s[sym::yy] = s[sym::zz] = -p;
  pressure = std::max(pressure, 0.0);
}

struct Span {
  std::int64_t begin, end;
  explicit Span(ParticleRange r) : begin(static_cast<std::int64_t>(r.begin)), end(static_cast<std::int64_t>(r.end)) {}
};

// Fails every intact point of r for which fails(p, sigma) is true: it keeps compression only.
template <class Criterion>
void fail_intact_points(Particles& P, ParticleRange r, Criterion fails) {
  double* fl = P.field(failed).data();
  double* pe = P.field(eos_pressure).data();
  const Span s(r);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = s.begin; p < s.end; ++p) {
    if (fl[p] > 0.0) continue;
    double* sigma = &P.stress[6 * p];
    if (fails(p, sigma)) {
      fl[p] = failure_state::failed;
      strip_to_compression(sigma, pe[p]);
    }
  }
}

}  // namespace

HydroMaterial::HydroMaterial(std::string name, HydroModels models)
    : Material(std::move(name)),
      models_(std::move(models)),
      G_(models_.youngs_modulus / (2.0 * (1.0 + models_.poisson_ratio))),
      K_(models_.youngs_modulus / (3.0 * (1.0 - 2.0 * models_.poisson_ratio))) {}

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
  if (models_.tuler_butcher) P.add_field(spall_damage, FieldKind::scalar, "1");
  if (can_fail()) P.add_field(failed, FieldKind::scalar, "1");
}

void HydroMaterial::initialise(Particles& P, ParticleRange r) const {
  if (!models_.heating) return;
  auto& T = P.field(temperature);
  for (std::size_t p = r.begin; p < r.end; ++p) T[p] = models_.initial_temperature;
}

double HydroMaterial::sound_speed(double rho_current, double p, bool is_failed) const {
  // Failed material carries no tension: expanded below its reference density it has no stiffness
  // until it is compressed back, and then its wave speed is the reference one. Its volume grows
  // without bound as it sprays apart, and K / rho at the current density would shrink the time
  // step for nothing (a particle expanded 3,800-fold alone cut it 30-fold in the demo at 0.2 mm).
  const double rho = is_failed ? std::max(rho_current, models_.density) : rho_current;
  const double bulk2 = models_.mie_gruneisen ? models_.mie_gruneisen->bulk_sound_speed_squared(rho, p) : K_ / rho;
  const bool shear = models_.shear_strength && !is_failed;
  return std::sqrt(bulk2 + (shear ? 4.0 * G_ / (3.0 * rho) : 0.0));
}

double HydroMaterial::signal_speed(const Particles& P, std::size_t p, const double* pe, const double* fl) const {
  if (fl && fl[p] == failure_state::eroded) return speed(P, p);
  return sound_speed(P.mass[p] / P.volume[p], pe[p], fl && fl[p] > 0.0) + speed(P, p);
}

double HydroMaterial::max_signal_speed(const Particles& P, ParticleRange r) const {
  const double* pe = P.field(eos_pressure).data();
  const double* fl = can_fail() ? P.field(failed).data() : nullptr;
  double result = 0.0;
  const Span s(r);
#pragma omp parallel for reduction(max : result) schedule(static)
  for (std::int64_t p = s.begin; p < s.end; ++p) result = std::max(result, signal_speed(P, p, pe, fl));
  return result;
}

StressUpdate HydroMaterial::update_stress(Particles& P, ParticleRange r, const StressContext& ctx) const {
  PhaseTimer dummy;
  PhaseTimer& timer = ctx.timer ? *ctx.timer : dummy;
  {
    auto t = timer.scope(models_.johnson_cook     ? "strength: johnson-cook"
                         : models_.shear_strength ? "strength: elastic"
                                                  : "strength: none");
    update_deviatoric(P, r, ctx.dt);
  }
  {
    auto t = timer.scope(std::string(models_.mie_gruneisen ? "eos: mie-gruneisen" : "eos: elastic bulk") +
                         (models_.viscosity ? " + viscosity" : ""));
    update_pressure(P, r, ctx.dt);
  }
  if (models_.heating) {
    auto t = timer.scope("heating: adiabatic");
    update_temperature(P, r);
  }
  if (models_.damage) {
    auto t = timer.scope("damage: johnson-cook");
    accumulate_damage(P, r, ctx.dt);
  }
  if (models_.max_principal_stress) {
    auto t = timer.scope("failure: max-principal-stress");
    check_principal_stress(P, r);
  }
  if (models_.tuler_butcher) {
    auto t = timer.scope("failure: tuler-butcher");
    accumulate_spall(P, r, ctx.dt);
  }
  if (models_.erosion) {
    auto t = timer.scope("erosion: compression");
    erode_crushed(P, r, ctx.dt);
  }
  StressUpdate result;
  std::int64_t bad = INT64_MAX;
  result.max_signal_speed = signal_speed_and_check(P, r, bad);
  if (bad != INT64_MAX) {
    result.bad_particle = bad;
    result.problem = "non-positive volume, or non-finite stress or internal energy";
  }
  return result;
}

// Deviatoric stress: Jaumann-rate elastic trial, then (Johnson-Cook) radial return. Adds the
// deviatoric work to the internal energy and, for Johnson-Cook, the plastic work.
void HydroMaterial::update_deviatoric(Particles& P, ParticleRange r, double dt) const {
  const JohnsonCookStrength* jc = models_.johnson_cook ? &*models_.johnson_cook : nullptr;
  double* eps = jc ? P.field(plastic_strain).data() : nullptr;
  double* eps_rate = jc ? P.field(plastic_strain_rate).data() : nullptr;
  double* wp = jc ? P.field(plastic_work).data() : nullptr;
  const double* T = models_.heating ? P.field(temperature).data() : nullptr;
  const double* fl = can_fail() ? P.field(failed).data() : nullptr;
  const double* pe = P.field(eos_pressure).data();
  const double G = G_, T0 = models_.initial_temperature;
  const Span s(r);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = s.begin; p < s.end; ++p) {
    if (fl && fl[p] == failure_state::eroded) continue;  // no stress, volume frozen
    double D[6], W[9], spin[6];
    split_velocity_gradient(&P.velocity_gradient[9 * p], D, W);
    const double trD = D[sym::xx] + D[sym::yy] + D[sym::zz];
    D[sym::xx] -= trD / 3.0;
    D[sym::yy] -= trD / 3.0;
    D[sym::zz] -= trD / 3.0;  // D is now the deviator D'

    double* sigma = &P.stress[6 * p];
    const double mean = trace_sym(sigma) / 3.0;
    double s_old[6], s_new[6];
    for (int c = 0; c < 6; ++c) s_old[c] = sigma[c];
    s_old[sym::xx] -= mean;
    s_old[sym::yy] -= mean;
    s_old[sym::zz] -= mean;

    const VolumeChange V = advance_volume(P, p, dt);
    const double rho_mid = 2.0 * P.mass[p] / (V.before + V.after);

    if ((fl && fl[p] > 0.0) || !models_.shear_strength) {
      for (int c = 0; c < 6; ++c) s_new[c] = 0.0;
      if (eps_rate) eps_rate[p] = 0.0;
    } else {
      jaumann_spin_term(W, s_old, spin);
      for (int c = 0; c < 6; ++c) s_new[c] = s_old[c] + dt * (2.0 * G * D[c] + spin[c]);
      if (jc) {
        const double q_trial = von_mises(s_new);
        const double rate = std::sqrt(2.0 / 3.0 * contract_sym(D, D));
        const double temp = T ? T[p] : T0;
        const double d_eps = radial_return(*jc, q_trial, G, eps[p], jc->rate_factor(rate), jc->thermal_factor(temp));
        if (d_eps > 0.0) {
          const double q = q_trial - 3.0 * G * d_eps;  // the yield stress reached
          const double scale = q / q_trial;
          for (int c = 0; c < 6; ++c) s_new[c] *= scale;
          eps[p] += d_eps;
          wp[p] += q * d_eps / rho_mid;
        }
        eps_rate[p] = d_eps / dt;
      }
    }
    double s_mid[6];
    for (int c = 0; c < 6; ++c) s_mid[c] = 0.5 * (s_old[c] + s_new[c]);
    P.internal_energy[p] += dt * contract_sym(s_mid, D) / rho_mid;
    // Mean stress of the previous step's pressure for now; update_pressure replaces it.
    for (int c = 0; c < 6; ++c) sigma[c] = s_new[c];
    sigma[sym::xx] -= pe[p];
    sigma[sym::yy] -= pe[p];
    sigma[sym::zz] -= pe[p];
  }
}

// Pressure from the bulk response or the Mie-Grüneisen EOS, with the volumetric and viscous
// work in the internal energy: e_n+1 = e_n - ((p_n + p_n+1) / 2 + q) dV / m, solved in closed
// form for the Mie-Grüneisen pressure, which is linear in e.
void HydroMaterial::update_pressure(Particles& P, ParticleRange r, double dt) const {
  const MieGruneisen* mg = models_.mie_gruneisen ? &*models_.mie_gruneisen : nullptr;
  const ArtificialViscosity* av = models_.viscosity ? &*models_.viscosity : nullptr;
  double* pe = P.field(eos_pressure).data();
  double* wq = av ? P.field(viscous_work).data() : nullptr;
  const double* fl = can_fail() ? P.field(failed).data() : nullptr;
  const double K = K_;
  const Span s(r);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = s.begin; p < s.end; ++p) {
    if (fl && fl[p] == failure_state::eroded) continue;
    const double* L = &P.velocity_gradient[9 * p];
    const double trD = L[0] + L[4] + L[8];
    const double m = P.mass[p], V = P.volume[p];
    const double dV = V - volume_before(P, p, dt);
    const double rho = m / V;
    const bool is_failed = fl && fl[p] > 0.0;
    const double p_old = pe[p];

    double q = 0.0;
    if (av && trD < 0.0) {
      const double c = sound_speed(rho, p_old, is_failed);
      q = rho * av->length * (av->linear * c * -trD + av->quadratic * av->length * trD * trD);
      wq[p] += -q * dV / m;
    }
    double& e = P.internal_energy[p];
    double p_new;
    if (mg) {
      const double e_star = e - (0.5 * p_old + q) * dV / m;
      const double B = mg->energy_coefficient(rho);  // at the end-of-step density
      p_new = (mg->cold_part(rho) + B * e_star) / (1.0 + 0.5 * B * dV / m);
      if (is_failed) p_new = std::max(p_new, 0.0);
      e = e_star - 0.5 * p_new * dV / m;
    } else {
      p_new = p_old - K * trD * dt;
      if (is_failed) p_new = std::max(p_new, 0.0);
      e -= (0.5 * (p_old + p_new) + q) * dV / m;
    }
    pe[p] = p_new;
    double* sigma = &P.stress[6 * p];
    const double shift = p_old - p_new - q;
    sigma[sym::xx] += shift;
    sigma[sym::yy] += shift;
    sigma[sym::zz] += shift;
  }
}

// Adiabatic heating: T = T0 + chi w_p / c_v.
void HydroMaterial::update_temperature(Particles& P, ParticleRange r) const {
  double* T = P.field(temperature).data();
  const double* wp = models_.johnson_cook ? P.field(plastic_work).data() : nullptr;
  const double factor = models_.heating->taylor_quinney / models_.heating->specific_heat;
  const double T0 = models_.initial_temperature;
  const Span s(r);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = s.begin; p < s.end; ++p) T[p] = T0 + (wp ? factor * wp[p] : 0.0);
}

// D += d eps_p / eps_f(sigma*, epsdot_p*, T*); failure at D = 1.
void HydroMaterial::accumulate_damage(Particles& P, ParticleRange r, double dt) const {
  const JohnsonCookDamage& jd = *models_.damage;
  const JohnsonCookStrength* jc = models_.johnson_cook ? &*models_.johnson_cook : nullptr;
  if (!jc) return;  // without plastic flow there is no damage to accumulate
  double* D = P.field(damage).data();
  const double* rate = P.field(plastic_strain_rate).data();
  const double* T = models_.heating ? P.field(temperature).data() : nullptr;
  const double T0 = models_.initial_temperature;
  fail_intact_points(P, r, [&](std::int64_t p, const double* sigma) {
    if (rate[p] <= 0.0) return false;
    const double eq = von_mises(sigma);
    const double triaxiality = eq > 0.0 ? trace_sym(sigma) / 3.0 / eq : 0.0;
    const double eps_f = jd.failure_strain(triaxiality, rate[p], jc->homologous_temperature(T ? T[p] : T0));
    D[p] = std::min(D[p] + rate[p] * dt / eps_f, 1.0);
    return D[p] >= 1.0;
  });
}

// Spall: failure when the largest principal stress reaches sigma_max.
void HydroMaterial::check_principal_stress(Particles& P, ParticleRange r) const {
  const double limit = *models_.max_principal_stress;
  fail_intact_points(P, r, [&](std::int64_t, const double* sigma) { return max_principal(sigma) >= limit; });
}

// Time-dependent spall: D_s += dt max(sigma_1 / sigma_0 - 1, 0)^lambda / tau; failure at D_s = 1.
void HydroMaterial::accumulate_spall(Particles& P, ParticleRange r, double dt) const {
  const TulerButcher& tb = *models_.tuler_butcher;
  double* Ds = P.field(spall_damage).data();
  fail_intact_points(P, r, [&](std::int64_t p, const double* sigma) {
    Ds[p] = std::min(Ds[p] + dt * tb.damage_rate(max_principal(sigma)), 1.0);
    return Ds[p] >= 1.0;
  });
}

// Erosion: a point crushed below V / V0 = r_min loses its stress for good. Its mass and momentum
// stay on the grid (momentum is untouched) and its internal energy stays in the balance, less the
// work this step booked in advance: the update adds (p_n + p_n+1) / 2 dV + q dV and s_mid : D dt,
// of which the grid pays the p_n+1, q and s_n+1 parts only in the next step, through the stress
// that erosion now zeroes. Left in, that unpaid work appeared as energy: +4.6% instead of +1.3% in
// the thin-wall hard case with r_min = 0.8 (474 points eroded).
void HydroMaterial::erode_crushed(Particles& P, ParticleRange r, double dt) const {
  const double r_min = models_.erosion->min_volume_ratio;
  double* fl = P.field(failed).data();
  double* pe = P.field(eos_pressure).data();
  double* eps_rate = models_.johnson_cook ? P.field(plastic_strain_rate).data() : nullptr;
  double* wq = models_.viscosity ? P.field(viscous_work).data() : nullptr;
  const Span s(r);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = s.begin; p < s.end; ++p) {
    if (fl[p] == failure_state::eroded || !(P.volume[p] < r_min * P.volume0[p])) continue;
    double* sigma = &P.stress[6 * p];
    const double m = P.mass[p], V = P.volume[p], V_before = volume_before(P, p, dt);
    const double dV = V - V_before, rho_mid = 2.0 * m / (V + V_before);
    const double mean = trace_sym(sigma) / 3.0;
    const double q = -mean - pe[p];  // the viscous part of the mean stress
    // s : D' = s : D, the deviator s being traceless.
    double D[6], W[9], dev[6];
    split_velocity_gradient(&P.velocity_gradient[9 * p], D, W);
    for (int c = 0; c < 6; ++c) dev[c] = sigma[c];
    for (const int c : {sym::xx, sym::yy, sym::zz}) dev[c] -= mean;
    P.internal_energy[p] += (0.5 * pe[p] + q) * dV / m - 0.5 * dt * contract_sym(dev, D) / rho_mid;
    if (wq) wq[p] += q * dV / m;
    fl[p] = failure_state::eroded;
    for (int c = 0; c < 6; ++c) sigma[c] = 0.0;
    pe[p] = 0.0;
    if (eps_rate) eps_rate[p] = 0.0;
  }
}

double HydroMaterial::signal_speed_and_check(Particles& P, ParticleRange r, std::int64_t& bad) const {
  const double* pe = P.field(eos_pressure).data();
  const double* fl = can_fail() ? P.field(failed).data() : nullptr;
  double result = 0.0;
  std::int64_t first_bad = INT64_MAX;
  const Span s(r);
#pragma omp parallel for reduction(max : result) reduction(min : first_bad) schedule(static)
  for (std::int64_t p = s.begin; p < s.end; ++p) {
    const double* sigma = &P.stress[6 * p];
    const double V = P.volume[p];
    if (!(V > 0.0) || !std::isfinite(sigma[0] + sigma[1] + sigma[2] + sigma[3] + sigma[4] + sigma[5] +
                                     P.internal_energy[p])) {
      first_bad = std::min(first_bad, p);
      continue;
    }
    result = std::max(result, signal_speed(P, p, pe, fl));
  }
  bad = first_bad;
  return result;
}

double HydroMaterial::dissipated_energy(const Particles& P, ParticleRange r) const {
  const double* wp = models_.johnson_cook ? P.field(plastic_work).data() : nullptr;
  const double* wq = models_.viscosity ? P.field(viscous_work).data() : nullptr;
  if (!wp && !wq) return 0.0;
  double sum = 0.0;  // serial: the same sum for any thread count
  for (std::size_t p = r.begin; p < r.end; ++p) sum += P.mass[p] * ((wp ? wp[p] : 0.0) + (wq ? wq[p] : 0.0));
  return sum;
}

}  // namespace hvi::mpm
