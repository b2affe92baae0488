// Johnson-Cook damage (paper eqs. 2-3) under a prescribed strain path, max-principal-stress
// failure, Tuler-Butcher spall under a held stress, and what failed material keeps.
#include <cmath>

#include <gtest/gtest.h>

#include "materials/principal_stress.hpp"
#include "mpm/materials/hydro_material.hpp"
#include "mpm/materials/library.hpp"
#include "mpm/types.hpp"
#include "tests/mpm/materials/material_driver.hpp"

namespace hvi::mpm {
namespace {

using materials::max_principal;

// Uniaxial strain in tension at constant rate: with a constant triaxiality path the damage after
// each step must equal the sum of d eps_p / eps_f(sigma*) with the material's own sigma* and
// plastic strain increments (eq. 2), and the particle fails at D = 1.
TEST(JohnsonCookDamage, AccumulatesAsEquationTwoAndFails) {
  HydroModels models = find_library_material("Al5052")->parameters;
  models.eos.reset();
  const HydroMaterial material("core", models);
  test::MaterialPoint point(material);
  const JohnsonCookDamage& jd = *models.damage;
  const double rate = 1e4, dt = 1e-8;
  const double L[9] = {rate, 0, 0, 0, 0, 0, 0, 0, 0};
  double expected = 0.0;
  int failed_at = -1;
  for (int step = 0; step < 100000 && failed_at < 0; ++step) {
    const double eps_before = point.field("plastic_strain");
    point.step(L, dt);
    const double d_eps = point.field("plastic_strain") - eps_before;
    if (point.field("failed") > 0) {
      failed_at = step;
      break;
    }
    if (d_eps > 0) {
      const double* s = point.stress();
      const double triax = trace_sym(s) / 3.0 / von_mises(s);
      expected += d_eps / jd.failure_strain(triax, d_eps / dt, 0.0);
    }
    ASSERT_NEAR(point.field("damage"), expected, 1e-12 + 1e-10 * expected) << step;
  }
  ASSERT_GE(failed_at, 0) << "never failed";
  EXPECT_NEAR(expected, 1.0, 0.02);  // it failed when the sum reached 1 (within one increment)
  // Failed material: no deviatoric stress and no tension.
  const double* s = point.stress();
  for (int c = 0; c < 6; ++c) EXPECT_EQ(s[c] > 0 ? s[c] : 0.0, 0.0);
  EXPECT_DOUBLE_EQ(s[sym::xy], 0.0);
  EXPECT_DOUBLE_EQ(s[sym::xx], s[sym::yy]);
}

// Max principal stress: uniaxial-strain tension until sigma_1 reaches sigma_max; then the particle
// has failed and carries nothing in tension, but pressure again in compression.
TEST(MaxPrincipalStress, FailsAtSigmaMaxAndKeepsOnlyCompression) {
  HydroModels models = find_library_material("Al2024-T81")->parameters;  // sigma_max 1500 MPa
  models.damage.reset();
  const HydroMaterial material("face", models);
  test::MaterialPoint point(material);
  const double rate = 1e4, dt = 1e-8;
  const double tension[9] = {rate, 0, 0, 0, 0, 0, 0, 0, 0};
  double last_intact = 0.0;
  int steps = 0;
  while (point.field("failed") == 0.0 && steps < 100000) {
    last_intact = max_principal(point.stress());
    point.step(tension, dt);
    ++steps;
  }
  ASSERT_GT(point.field("failed"), 0.0);
  EXPECT_LT(last_intact, 1500e6);
  EXPECT_GT(last_intact, 1500e6 * 0.98);  // one step's stress increment below the limit
  for (int c = 0; c < 6; ++c) EXPECT_EQ(point.stress()[c], 0.0);
  point.step(tension, dt);
  for (int c = 0; c < 6; ++c) EXPECT_EQ(point.stress()[c], 0.0);  // still nothing in tension
  const double compression[9] = {-rate, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int k = 0; k < 400; ++k) point.step(compression, dt);  // back past the reference density
  const double* s = point.stress();
  EXPECT_LT(s[sym::xx], 0.0);                // pressure again
  EXPECT_DOUBLE_EQ(s[sym::xx], s[sym::yy]);  // but no deviator
}

// Tuler-Butcher: pulled in uniaxial strain to sigma_1 above sigma_0 and held there (L = 0 keeps
// the stress), the point fails after tau / (sigma_1 / sigma_0 - 1)^lambda less what the pull
// accumulated, to within the step: the closed form of the impulse integral at constant stress.
// Below sigma_0 it never fails, however long it is held.
TEST(TulerButcher, FailsAfterTheClosedFormTimeUnderAHeldStress) {
  HydroModels models = find_library_material("Al2024-T81")->parameters;
  models.damage.reset();
  models.max_principal_stress.reset();
  models.johnson_cook.reset();  // elastic: a rate-dependent yield would relax the held stress
  models.heating.reset();
  const double sigma_0 = 1.0e9, lambda = 2.0, tau = 2e-8, rate = 1e6,
               dt = 1e-9;  // ~0.1 GPa per step
  models.tuler_butcher = TulerButcher{sigma_0, lambda, tau};
  const double tension[9] = {rate, 0, 0, 0, 0, 0, 0, 0, 0}, hold[9] = {};
  for (const double target : {0.9e9, 1.5e9, 2.0e9}) {
    SCOPED_TRACE(target);
    const HydroMaterial material("face", models);
    test::MaterialPoint point(material);
    // The pull: D_s follows the sum of dt (sigma_1 / sigma_0 - 1)^lambda / tau over its steps.
    double expected = 0.0;
    while (max_principal(point.stress()) < target) {
      point.step(tension, dt);
      expected +=
          dt * std::pow(std::max(max_principal(point.stress()) / sigma_0 - 1.0, 0.0), lambda) / tau;
      ASSERT_NEAR(point.field("spall_damage"), expected, 1e-12);
    }
    ASSERT_EQ(point.field("failed"), 0.0);
    const double sigma_1 = max_principal(point.stress());
    const double excess = sigma_1 / sigma_0 - 1.0;
    const int limit = 5000;  // 5 us, 60 times the longest closed-form time here
    int held = 0;
    while (point.field("failed") == 0.0 && held < limit) {
      point.step(hold, dt);
      ++held;
      if (held == 1) {
        ASSERT_DOUBLE_EQ(max_principal(point.stress()), sigma_1);  // the hold keeps it
      }
    }
    if (excess <= 0.0) {
      EXPECT_EQ(held, limit);
      EXPECT_EQ(point.field("spall_damage"), expected);
      continue;
    }
    const double t_closed_form = (1.0 - expected) * tau / std::pow(excess, lambda);
    EXPECT_NEAR(held * dt, t_closed_form, dt);
    EXPECT_EQ(point.field("spall_damage"), 1.0);
    for (int c = 0; c < 6; ++c)
      EXPECT_EQ(point.stress()[c] > 0 ? point.stress()[c] : 0.0, 0.0);  // no tension left
  }
}

}  // namespace
}  // namespace hvi::mpm
