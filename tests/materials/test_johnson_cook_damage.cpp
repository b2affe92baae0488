// Johnson-Cook damage (paper eqs. 2-3): the failure strain of eq. (3) against its closed form, and
// its floor where the bracket turns negative.
#include <cmath>

#include <gtest/gtest.h>

#include "materials/johnson_cook_damage.hpp"
#include "mpm/materials/library.hpp"

namespace hvi::materials {
namespace {

TEST(JohnsonCookDamage, FailureStrainEqualsEquationThree) {
  const JohnsonCookDamage d = *mpm::find_library_material("Al6061")->parameters.damage;
  // sigma* = 1/3 (uniaxial tension), rate 100/s, T* = 0.2:
  const double expected =
      (-0.77 + 1.45 * std::exp(-0.47 / 3.0)) * (1 + 0.0 * std::log(100.0)) * (1 + 1.6 * 0.2);
  EXPECT_NEAR(d.failure_strain(1.0 / 3.0, 100.0, 0.2), expected, 1e-14);
  // High triaxiality makes the bracket negative: failure within a step.
  EXPECT_EQ(d.failure_strain(3.0, 1.0, 0.0), JohnsonCookDamage::minimum_failure_strain);
}

}  // namespace
}  // namespace hvi::materials
