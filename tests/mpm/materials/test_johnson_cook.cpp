// Johnson-Cook strength (paper eq. 1): the yield stress against its closed form, the clamps of the
// rate and temperature terms, radial return onto the yield surface, and the stress path of
// uniaxial-strain compression against its closed form.
#include <cmath>

#include <gtest/gtest.h>

#include "mpm/materials/hydro_material.hpp"
#include "mpm/materials/library.hpp"
#include "mpm/types.hpp"
#include "tests/mpm/materials/material_driver.hpp"

namespace hvi::mpm {
namespace {

JohnsonCookStrength paper_al() { return *find_library_material("Al6061")->parameters.johnson_cook; }

TEST(JohnsonCook, YieldStressEqualsClosedForm) {
  const JohnsonCookStrength jc = paper_al();
  // eps_p = 0.1, rate 1000/s, T = 400 K, by hand from Table 4:
  // (265 + 426 * 0.1^0.34) * (1 + 0.015 ln 1000) * (1 - (400 - 293) / (775 - 293)) MPa
  const double expected = (265e6 + 426e6 * std::pow(0.1, 0.34)) * (1 + 0.015 * std::log(1000.0)) *
                          (1 - (400.0 - 293.0) / (775.0 - 293.0));
  // Same operations in a different order: agreement to a few ulps.
  EXPECT_NEAR(jc.yield_stress(0.1, 1000.0, 400.0), expected, 1e-13 * expected);
  EXPECT_NEAR(expected, 3.9473e8, 1e4);  // the value computed by hand (calculator), 5 digits
}

TEST(JohnsonCook, RateAndTemperatureTermsAreClamped) {
  const JohnsonCookStrength jc = paper_al();
  const double A = 265e6;
  EXPECT_DOUBLE_EQ(jc.yield_stress(0.0, 1e-3, 293.0), A);   // rate below the reference: no softening
  EXPECT_DOUBLE_EQ(jc.yield_stress(0.0, 1.0, 200.0), A);    // below room temperature: T* = 0
  EXPECT_DOUBLE_EQ(jc.yield_stress(0.5, 1e4, 900.0), 0.0);  // above melt: T* = 1
}

// Stress state after return: von Mises equals the yield stress at the updated plastic strain.
TEST(JohnsonCook, RadialReturnEndsOnTheYieldSurface) {
  const JohnsonCookStrength jc = paper_al();
  const double G = 75e9 / (2 * 1.33);
  for (double q_trial : {300e6, 1e9, 5e9}) {
    for (double eps_p : {0.0, 0.05, 1.0}) {
      const double rate = jc.rate_factor(1e4), thermal = jc.thermal_factor(350.0);
      const double d = radial_return(jc, q_trial, G, eps_p, rate, thermal);
      const double q = q_trial - 3 * G * d;
      if (q_trial <= jc.hardening(eps_p) * rate * thermal) {
        EXPECT_EQ(d, 0.0);
        continue;
      }
      // Newton converged to 1e-14 relative in d: the residual is round-off of q (1e-12 of q).
      EXPECT_NEAR(q, jc.hardening(eps_p + d) * rate * thermal, 1e-10 * q) << q_trial << " " << eps_p;
      EXPECT_GT(d, 0.0);
    }
  }
}

// Uniaxial strain at constant rate: L = diag(-rate, 0, 0). Elastic until the deviator reaches the
// yield surface, then sigma_xx - sigma_yy = -sigma_y(eps_p) with, in this path,
//   eps_p = 2/3 eps - sigma_y(eps_p) / (3 G)   (eps = the accumulated compressive strain),
// and the pressure of the bulk response p = K eps. So sigma_xx = -K eps - 2/3 sigma_y.
TEST(JohnsonCook, UniaxialStrainPathMatchesClosedForm) {
  HydroModels models = find_library_material("Al6061")->parameters;
  models.mie_gruneisen.reset();
  models.damage.reset();
  const HydroMaterial material("al", models);
  const double G = material.shear_modulus(), K = material.bulk_modulus();
  const JohnsonCookStrength& jc = *models.johnson_cook;
  test::MaterialPoint point(material);
  const double rate = 1e4, dt = 1e-8;
  const double L[9] = {-rate, 0, 0, 0, 0, 0, 0, 0, 0};
  const double rate_factor = jc.rate_factor(2.0 / 3.0 * rate);  // equivalent strain rate 2/3 |L_xx|
  double eps = 0.0, worst = 0.0;
  for (int step = 1; step <= 2000; ++step) {  // to 20% strain
    point.step(L, dt);
    eps += rate * dt;
    // Closed form: solve eps_p = 2/3 eps - sigma_y(eps_p)/(3G) by bisection (or elastic).
    double sigma_dev;  // sigma_xx - sigma_yy
    if (2.0 * G * eps <= jc.A * rate_factor) {
      sigma_dev = -2.0 * G * eps;
    } else {
      double lo = 0.0, hi = 2.0 / 3.0 * eps;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        (mid - (2.0 / 3.0 * eps - jc.hardening(mid) * rate_factor / (3 * G)) < 0 ? lo : hi) = mid;
      }
      sigma_dev = -jc.hardening(0.5 * (lo + hi)) * rate_factor;
    }
    const double expected_xx = -K * eps + 2.0 / 3.0 * sigma_dev;
    const double* s = point.stress();
    worst = std::max(worst, std::fabs(s[sym::xx] - expected_xx) / std::fabs(expected_xx));
    EXPECT_NEAR(s[sym::xx] - s[sym::yy], sigma_dev, 1e-6 * std::fabs(sigma_dev)) << "step " << step;
  }
  // The hypoelastic integration is exact for a constant L; what remains is the return's
  // round-off and the one step in which the path crosses the yield surface.
  EXPECT_LT(worst, 1e-6);
  EXPECT_NEAR(point.field("plastic_strain"),
              2.0 / 3.0 * eps - std::fabs(point.stress()[sym::xx] - point.stress()[sym::yy]) / (3 * G), 1e-9);
}

}  // namespace
}  // namespace hvi::mpm
