// Verification: axial vibration of a fixed-free elastic bar. With Poisson ratio 0 the bar is
// exactly one-dimensional (no lateral stress from axial strain), the wave speed is c = sqrt(E/rho)
// and the first mode, v(x, t) = v0 sin(pi x / 2L) cos(2 pi t / T), has period T = 4L/c.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "mpm_test_helpers.hpp"

namespace hvi::mpm::test {
namespace {

struct BarResult {
  double period = 0.0;        // measured first-mode period, s
  double exact_period = 0.0;  // 4L/c, s
  int crossings = 0;
  double max_dt = 0.0;  // s
  // Energy, relative to the initial (kinetic) energy E0:
  double raw_error = 0.0;      // max |KE + IE - E0|
  double centred_error = 0.0;  // max |KE_centred + IE - E0|, see below
  double drift = 0.0;          // mean of the centred error over the last period - over the first
};

// A bar of 25 cells (1 mm; or `cells`) along x, cross-section 1 x 1 cell, aluminium-like E and rho
// with nu = 0, fixed at the grid plane x = 0, free at x = L; 2 particles per cell per direction
// (200 particles); initial velocity of the first mode with v0 = 0.1 m/s (strain ~ v0/c = 2e-5:
// linear regime). Runs `periods` exact periods (200 steps each at CFL 0.5) and measures the period
// from the zero crossings of the total momentum, which for the first mode is proportional to cos(2
// pi t / T).
BarResult run_bar(ShapeFunction shape, UpdateScheme scheme, int periods, int cells = 25) {
  const Threads threads(1);  // 200-800 particles
  const double h = 1e-3, L = cells * h, rho = 2700.0, E = 70e9, v0 = 0.1;
  SolverSettings settings;
  settings.shape = shape;
  settings.scheme = scheme;
  settings.cfl = 0.5;  // the predicted period error below assumes it
  // Bar at y, z in [3h, 4h]: GIMP stencils (one node beyond the particle's cell) stay in the
  // domain.
  Solver solver(grid({0.0, 0.0, 0.0}, h, {cells + 7, 8, 8}), settings,
                one_material(std::make_unique<LinearElastic>("bar", rho, E, 0.0)), {"bar"},
                {GridBoundary{0, 0, true, BoundaryType::fixed}});
  add_body(solver, geometry::Box({0.0, 3 * h, 3 * h}, {L, 4 * h, 4 * h}), 2, 0, 0,
           [&](const double* x) {
             return Vec3{v0 * std::sin(std::numbers::pi * x[0] / (2 * L)), 0.0, 0.0};
           });
  solver.initialise();

  BarResult r;
  r.exact_period = 4 * L / std::sqrt(E / rho);
  const double E0 = solver.energy().kinetic;
  double t_prev = 0.0, p_prev = solver.energy().momentum[0];
  double k_prev = E0, i_prev = 0.0, t_stress = 0.0;
  std::vector<double> crossings;
  double first_sum = 0, last_sum = 0;
  int first_n = 0, last_n = 0;
  while (solver.time() < periods * r.exact_period) {
    r.max_dt = std::max(r.max_dt, solver.next_time_step());
    solver.step();
    const EnergyReport e = solver.energy();
    r.raw_error = std::max(r.raw_error, std::fabs(e.kinetic + e.internal - E0) / E0);
    // MUSL advances positions (hence strain and stress) with the new velocities, like leapfrog:
    // the velocities after a step are half a step ahead of the stresses, so KE + IE oscillates by
    // about (omega dt / 2) E0 even for an exactly energy-conserving scheme. The mean of the kinetic
    // energies after this step and the previous one is centred on the previous step's stress time.
    if (solver.step_count() > 1) {
      const double centred = (0.5 * (k_prev + e.kinetic) + i_prev - E0) / E0;
      r.centred_error = std::max(r.centred_error, std::fabs(centred));
      if (t_stress < r.exact_period) first_sum += centred, ++first_n;
      if (t_stress >= (periods - 1) * r.exact_period) last_sum += centred, ++last_n;
    }
    k_prev = e.kinetic;
    i_prev = e.internal;
    t_stress = solver.time();
    const double t = solver.time(), p = e.momentum[0];
    if ((p_prev > 0) != (p > 0)) crossings.push_back(t_prev + (t - t_prev) * p_prev / (p_prev - p));
    t_prev = t;
    p_prev = p;
  }
  r.crossings = static_cast<int>(crossings.size());
  // Zero crossings are half a period apart.
  if (crossings.size() >= 2)
    r.period =
        2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  if (first_n > 0 && last_n > 0) r.drift = last_sum / last_n - first_sum / first_n;
  return r;
}

void report(const char* name, const BarResult& r) {
  std::printf(
      "[bar %s] period %.6e s, exact %.6e s, error %+.4f %%, %d crossings; energy: raw %.3e "
      "(pi dt/T %.3e), centred %.3e ((omega dt)^2 %.3e), drift %+.2e\n",
      name, r.period, r.exact_period, 100 * (r.period / r.exact_period - 1), r.crossings,
      r.raw_error, std::numbers::pi * r.max_dt / r.exact_period, r.centred_error,
      std::pow(2 * std::numbers::pi * r.max_dt / r.exact_period, 2), r.drift);
}

// Required: within 1% of 4L/c. That is loose for the scheme (measured +0.049%) but catches any
// error in stiffness, mass or the boundary treatment, each of which moves T by O(1/25) = 4% or
// more.
constexpr double kPeriodTolerance = 0.01;

// The discrete period error predicted by a modified-wavenumber analysis for this set-up, with
// k = pi / 2L the first-mode wavenumber and h the cell:
//   lumped-mass stiffness operator on the nodes     omega factor 1 - (kh)^2 / 24
//   velocities live on the particles (FLIP): they   each a factor 0.75 cos(kh/4) + 0.25 cos(3kh/4)
//     reach the nodes by the mass-weighted            = 1 - 0.09375 (kh)^2 on a mode (particles at
//     projection and come back by interpolation       h/4 and 3h/4 of each cell); on omega^2 both,
//                                                     so omega factor 1 - 0.09375 (kh)^2
//   leapfrog-like time integration at CFL 0.5       omega factor 1 + (omega dt)^2 / 24
//                                                     = 1 + (kh)^2 / 96
// Together T_h / T - 1 = (kh)^2 / 8 (= 4.935e-4 at 25 cells), the same for MUSL, USL and USF.
double predicted_period_error(int cells) {
  const double kh = std::numbers::pi / (2.0 * cells);
  return kh * kh / 8.0;
}

void check_period(const BarResult& r) {
  ASSERT_GE(r.crossings, 5);  // 6 expected in 3 periods (at T/4, 3T/4, ...)
  EXPECT_NEAR(r.period / r.exact_period, 1.0, kPeriodTolerance);
  // Sharper: the error is the predicted (kh)^2 / 8 (measured 4.936e-4 MUSL, 4.935e-4 USL and USF,
  // vs 4.935e-4). 5% of it (2.5e-5 of T) leaves room for higher-order terms, O((kh)^4) ~ 1e-7,
  // and the interpolated zero crossings, and fails for any change of the scheme's dispersion.
  EXPECT_NEAR(r.period / r.exact_period - 1.0, predicted_period_error(25),
              0.05 * predicted_period_error(25));
}

// The stagger of KE against IE (see run_bar) makes the raw energy oscillate with amplitude
// omega dt / 2 = pi dt / T (= 1.57e-2 at 200 steps per period; measured 1.595e-2 for every scheme
// and shape, 1.5% above the first-order estimate). Bound: 1.05 pi dt / T.
void check_raw_energy(const BarResult& r) {
  EXPECT_LT(r.raw_error, 1.05 * std::numbers::pi * r.max_dt / r.exact_period);
}

// MUSL, linear shape functions (the required configuration), 3 periods.
TEST(ElasticBar, MuslLinear) {
  const BarResult r = run_bar(ShapeFunction::linear, UpdateScheme::musl, 3);
  report("musl linear", r);
  check_period(r);
  check_raw_energy(r);
  // With the stagger removed the remaining error is second order, ~(omega dt)^2 / 2 = 4.9e-4
  // (measured 4.93e-4; 1.23e-4 at half the time step, 2.0e-5 at a fifth). Bound: (omega dt)^2.
  EXPECT_LT(r.centred_error, std::pow(2 * std::numbers::pi * r.max_dt / r.exact_period, 2));
  // No secular drift: the period-averaged centred energy changes by -1.3e-6 E0 from the first to
  // the third period (measured; -3.4e-6 from the first to the tenth). A dissipative update (USL
  // here: -2.9e-4; PIC: -0.36) or a growing one would exceed the 1e-5 bound.
  EXPECT_LT(std::fabs(r.drift), 1e-5);
}

// The same bar with uGIMP: grid-aligned particles, so the same results to ~1e-6 (measured period
// +0.049%, centred 4.93e-4, drift -1.3e-6); same bounds.
TEST(ElasticBar, MuslGimp) {
  const BarResult r = run_bar(ShapeFunction::gimp, UpdateScheme::musl, 3);
  report("musl gimp", r);
  check_period(r);
  check_raw_energy(r);
  EXPECT_LT(r.centred_error, std::pow(2 * std::numbers::pi * r.max_dt / r.exact_period, 2));
  EXPECT_LT(std::fabs(r.drift), 1e-5);
}

// USL and USF reproduce the period too (measured +0.0493% each). Their velocity/stress staggering
// differs, so only the period and the raw oscillation bound are checked.
TEST(ElasticBar, UslAndUsfLinear) {
  for (const auto scheme : {UpdateScheme::usl, UpdateScheme::usf}) {
    const BarResult r = run_bar(ShapeFunction::linear, scheme, 3);
    report(scheme == UpdateScheme::usl ? "usl linear" : "usf linear", r);
    check_period(r);
    check_raw_energy(r);
  }
}

// Convergence: the period error is second order in h and follows (kh)^2 / 8 (see above).
// Measured: +4.936e-4, +1.234e-4, +3.085e-5 at 25, 50, 100 cells (predicted 4.935e-4, 1.234e-4,
// 3.084e-5). Each must be within 5% of the prediction, and each halving of h must divide the
// error by 4 +- 0.5 (a first-order error, e.g. in the boundary treatment, would give 2).
TEST(ElasticBar, PeriodConvergesAtSecondOrder) {
  double previous = 0.0;
  for (const int cells : {25, 50, 100}) {
    const BarResult r = run_bar(ShapeFunction::linear, UpdateScheme::musl, 3, cells);
    const double error = r.period / r.exact_period - 1.0;
    std::printf("[bar convergence] %d cells: period error %+.3e\n", cells, error);
    EXPECT_NEAR(error, predicted_period_error(cells), 0.05 * predicted_period_error(cells));
    if (previous > 0.0) {
      EXPECT_GT(previous / error, 3.5) << cells << " cells";
      EXPECT_LT(previous / error, 4.5) << cells << " cells";
    }
    previous = error;
  }
}

}  // namespace
}  // namespace hvi::mpm::test
