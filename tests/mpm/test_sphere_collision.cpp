// Verification: two identical elastic spheres in head-on collision (the Sulsky et al. 1995 disk
// test in 3D). MPM resolves the contact through the shared grid, with no contact algorithm: the
// spheres must meet, convert their kinetic energy to strain energy and bounce apart, with total
// momentum conserved to round-off and total energy to a bound measured below.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "mpm_test_helpers.hpp"

namespace hvi::mpm::test {
namespace {

struct CollisionResult {
  double min_kinetic = 0.0;        // min KE / KE0 over the run
  double final_kinetic = 0.0;      // KE / KE0 at the end
  double max_energy_error = 0.0;   // max |KE + IE - E0| / E0 (raw)
  double max_centred_error = 0.0;  // the same with KE centred on the stress time (see below)
  double final_centred_error = 0.0;
  double max_momentum_error = 0.0;                   // max |P(t) - P(0)| / (m v0), any component
  double left_velocity = 0.0, right_velocity = 0.0;  // mean x velocity per sphere at the end
  double final_gap = 0.0;  // min x of the right sphere - max x of the left, m
  int steps = 0;
};

// Aluminium-like spheres (E = 70 GPa, nu = 0.3, rho = 2700: P-wave speed 6.0 km/s) of radius 5
// cells (1 mm cells, 2 particles per cell per direction: 8448 particles), surfaces 2 cells apart,
// moving at +-300 m/s (v0 / c = 0.05). No boundary conditions; the domain is large enough that
// nothing leaves. Runs 400 steps: contact from step ~12 to ~110, then free flight apart.
CollisionResult collide(ShapeFunction shape) {
  // One thread: 8448 particles take 0.6-2 s on an idle machine (half that on 2 threads), but
  // 25-45 s with 2 threads while a parallel build runs (measured). Threaded runs are
  // test_determinism.cpp's.
  const Threads threads(1);
  const double h = 1e-3, R = 5 * h, v0 = 300.0;
  SolverSettings settings;
  settings.shape = shape;
  Solver solver(grid({-24 * h, -8 * h, -8 * h}, h, {48, 16, 16}), settings,
                one_material(std::make_unique<LinearElastic>("aluminium", 2700.0, 70e9, 0.3)),
                {"left", "right"}, {});
  add_body(solver, geometry::Sphere({-(R + h), 0, 0}, R), 2, 0, 0, uniform({v0, 0, 0}));
  add_body(solver, geometry::Sphere({R + h, 0, 0}, R), 2, 1, 0, uniform({-v0, 0, 0}));
  solver.initialise();

  const EnergyReport e0 = solver.energy();
  const double E0 = e0.kinetic, m = 0.5 * e0.mass;
  CollisionResult r;
  r.min_kinetic = 1.0;
  double k_prev = e0.kinetic, i_prev = e0.internal;
  for (r.steps = 0; r.steps < 400; ++r.steps) {
    solver.step();
    const EnergyReport e = solver.energy();
    r.min_kinetic = std::min(r.min_kinetic, e.kinetic / E0);
    r.max_energy_error = std::max(r.max_energy_error, std::fabs(e.kinetic + e.internal - E0) / E0);
    // The particle velocities after a step are, as in leapfrog, half a step ahead of the stresses
    // (positions and strains advance with them), so KE + IE carries an O(dt) stagger error
    // |dKE/dt| dt/2 during contact. The mean of two consecutive kinetic energies is centred on
    // the stress time of the earlier step and removes it (see test_elastic_bar.cpp).
    r.final_centred_error = (0.5 * (k_prev + e.kinetic) + i_prev - E0) / E0;
    r.max_centred_error = std::max(r.max_centred_error, std::fabs(r.final_centred_error));
    k_prev = e.kinetic;
    i_prev = e.internal;
    const Vec3 p = total_momentum(solver);
    for (int d = 0; d < 3; ++d)
      r.max_momentum_error =
          std::max(r.max_momentum_error, std::fabs(p[d] - e0.momentum[d]) / (m * v0));
  }
  r.final_kinetic = k_prev / E0;

  const Particles& P = solver.particles();
  double mv[2] = {0, 0}, mass[2] = {0, 0}, left_max = -1e9, right_min = 1e9;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const auto b = P.body[p];
    mv[b] += P.mass[p] * P.velocity[3 * p];
    mass[b] += P.mass[p];
    if (b == 0)
      left_max = std::max(left_max, P.position[3 * p]);
    else
      right_min = std::min(right_min, P.position[3 * p]);
  }
  r.left_velocity = mv[0] / mass[0] / v0;
  r.right_velocity = mv[1] / mass[1] / v0;
  r.final_gap = right_min - left_max;
  std::printf(
      "[spheres %s] min KE %.4f, final KE %.4f, max |dE| raw %.3e centred %.3e, final centred "
      "%+.3e, max |dP|/(m v0) %.3e, sphere velocities %+.4f %+.4f v0, gap %.2f cells\n",
      shape == ShapeFunction::linear ? "linear" : "gimp", r.min_kinetic, r.final_kinetic,
      r.max_energy_error, r.max_centred_error, r.final_centred_error, r.max_momentum_error,
      r.left_velocity, r.right_velocity, r.final_gap / h);
  return r;
}

void check_common(const CollisionResult& r) {
  // Momentum: the grid forces sum to zero and the FLIP update adds sum_I m_I dv_I = dt sum_I f_I
  // to the particles, so only round-off accumulates: ~1e-14 measured after 400 steps; 1e-10 is
  // the required bound (still 4 orders above round-off, far below any real leak).
  EXPECT_LT(r.max_momentum_error, 1e-10);
  // They interacted: nearly all kinetic energy is stored as strain at maximum compression
  // (measured min KE 1.4% linear, 0.7% GIMP), then most of it comes back (measured 96.8% linear,
  // 97.7% GIMP).
  EXPECT_LT(r.min_kinetic, 0.1);
  EXPECT_GT(r.final_kinetic, 0.9);
  // And bounced apart: each sphere moves back at nearly v0 (elastic rebound; measured 0.968 v0
  // linear, 0.980 v0 GIMP), with a clear gap between them at the end (measured 15 cells).
  EXPECT_LT(r.left_velocity, -0.9);
  EXPECT_GT(r.right_velocity, 0.9);
  EXPECT_GT(r.final_gap, 5e-3);
}

// Energy bounds. Total energy is not an invariant of the discrete scheme here: the grid's single
// velocity field resolves the contact like a sticking impact at the shared nodes (the velocity
// averaging there dissipates), and particles crossing cells with stress add noise (mostly for
// linear shape functions). Measured (400 steps): raw max |dE|/E0 = 2.07% linear, 2.19% GIMP, of
// which the O(dt) stagger is ~1.5%; centred max 0.70% linear, 0.95% GIMP. Bounds: 3% raw and 1.5%
// centred, ~1.5x the measured values, so a change that doubles the energy error fails.
// The bounds hold for this run length. Over longer runs, linear shape functions with pure FLIP let
// the energy grow after separation (the grid-crossing / ringing noise of FLIP): with radius 10
// cells, +0.1% at 350 steps, +1.1% at 650, +2.1% at 750, growing; GIMP stays within -0.4%.
TEST(SphereCollision, LinearMusl) {
  const CollisionResult r = collide(ShapeFunction::linear);
  check_common(r);
  EXPECT_LT(r.max_energy_error, 0.03);
  EXPECT_LT(r.max_centred_error, 0.015);
}

TEST(SphereCollision, GimpMusl) {
  const CollisionResult r = collide(ShapeFunction::gimp);
  check_common(r);
  EXPECT_LT(r.max_energy_error, 0.03);
  EXPECT_LT(r.max_centred_error, 0.015);
}

}  // namespace
}  // namespace hvi::mpm::test
