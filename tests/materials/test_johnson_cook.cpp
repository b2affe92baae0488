// Johnson-Cook strength (paper eq. 1): the yield stress against its closed form, the clamps of the
// rate and temperature terms, and radial return onto the yield surface.
#include <cmath>

#include <gtest/gtest.h>

#include "materials/johnson_cook.hpp"
#include "mpm/materials/library.hpp"

namespace hvi::materials {
namespace {

JohnsonCookStrength paper_al() {
  return *mpm::find_library_material("Al6061")->parameters.johnson_cook;
}

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
  EXPECT_DOUBLE_EQ(jc.yield_stress(0.0, 1e-3, 293.0), A);  // rate below the reference: no softening
  EXPECT_DOUBLE_EQ(jc.yield_stress(0.0, 1.0, 200.0), A);   // below room temperature: T* = 0
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
      EXPECT_NEAR(q, jc.hardening(eps_p + d) * rate * thermal, 1e-10 * q)
          << q_trial << " " << eps_p;
      EXPECT_GT(d, 0.0);
    }
  }
}

}  // namespace
}  // namespace hvi::materials
