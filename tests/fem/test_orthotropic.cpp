// The homogenised honeycomb core (Gibson & Ashby's closed forms) and orthotropic stiffness.
#include <gtest/gtest.h>

#include <cmath>

#include "fem/orthotropic.hpp"

namespace hvi::fem {
namespace {

TEST(Orthotropic, IsotropicStiffnessIsLame) {
  const double E = 70e9, nu = 0.3;
  const auto C = stiffness(isotropic(E, nu));
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(C[i] / (lambda + 2 * mu), 1.0, 1e-14);
  for (int i = 3; i < 6; ++i) EXPECT_NEAR(C[i] / lambda, 1.0, 1e-14);
  for (int i = 6; i < 9; ++i) EXPECT_NEAR(C[i] / mu, 1.0, 1e-14);
}

// The paper's study core: Al5052 walls (E 73 GPa, nu 0.33), D_hc 3 mm, t_hc 0.05 mm.
TEST(Orthotropic, HoneycombCoreClosedForms) {
  const double Es = 73e9, nus = 0.33, D = 3e-3, t = 0.05e-3;
  const auto c = honeycomb_core(Es, nus, D, t);
  const double solidity = (2 * t / D) * (1 - t / (2 * D));
  EXPECT_NEAR(honeycomb_core_solidity(D, t), 0.033055555555555555, 1e-15);
  EXPECT_DOUBLE_EQ(c.E3, Es * solidity);                  // 2.413 GPa
  EXPECT_DOUBLE_EQ(c.G13, Es / (2 * (1 + nus)) * t / D);  // 457.4 MPa
  EXPECT_DOUBLE_EQ(c.G23, c.G13);
  const double tl = t * std::sqrt(3.0) / D;  // t / l with l = D / sqrt(3)
  EXPECT_NEAR(c.E1 / (2.3094010767585 * Es * tl * tl * tl), 1.0, 1e-12);
  EXPECT_NEAR(c.G12 / (0.57735026918963 * Es * tl * tl * tl), 1.0, 1e-12);
  // In plane the core is ~3 orders softer than out of plane (wall bending vs stretching).
  EXPECT_LT(c.E1 / c.E3, 2e-3);
  // The compliance is symmetric: nu13 / E1 = nu31 / E3 with nu31 = nu_s.
  EXPECT_NEAR(c.nu13 / c.E1, nus / c.E3, 1e-24);
  const auto C = stiffness(c);
  // Under uniaxial strain C33 lies between the free walls' E3 and the walls held in plane strain,
  // E3 / (1 - nu_s^2): the lateral confinement of the cells.
  EXPECT_GT(C[2], c.E3);
  EXPECT_LT(C[2], c.E3 / (1 - nus * nus));
}

// Double walls (the ribbon walls 2t): the solidity is the plan area of the walls, which for
// t << D is 1 + 1/3 times the single walls' (one wall in three per cell doubled); the shear along
// the ribbon lies between Kelsey's bounds 3/2 and 5/3 G_s t/D; across it is unchanged.
TEST(Orthotropic, DoubleWalledCoreClosedForms) {
  const double Es = 73e9, nus = 0.33, D = 3e-3, t = 0.05e-3, Gs = Es / (2 * (1 + nus));
  // The plan area exactly: the hexagon (sqrt(3)/2) D^2 minus its interior shrunk by t on the two
  // ribbon sides and t/2 on the four others, a hexagon of half-widths r0 (across the ribbon
  // sides) and r1: a rectangle 2 r0 x 2 y0 plus two triangles, y0 = (2 r1 - r0) / sqrt(3),
  // y1 = 2 r1 / sqrt(3).
  const double r0 = D / 2 - t, r1 = D / 2 - t / 2, s3 = std::sqrt(3.0);
  const double y0 = (2 * r1 - r0) / s3, y1 = 2 * r1 / s3;
  const double plan = 1 - (4 * r0 * y0 + 2 * r0 * (y1 - y0)) / (s3 / 2 * D * D);
  EXPECT_NEAR(honeycomb_core_solidity(D, t, true), plan, 1e-15);
  const auto c = honeycomb_core(Es, nus, D, t, true), single = honeycomb_core(Es, nus, D, t);
  EXPECT_NEAR(c.E3 / (Es * plan), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(c.G13, single.G13);
  EXPECT_GT(c.G23, 1.5 * Gs * t / D);
  EXPECT_LT(c.G23, 5.0 / 3.0 * Gs * t / D);
  EXPECT_DOUBLE_EQ(c.E1, single.E1);
  EXPECT_NO_THROW(stiffness(c));
}

TEST(Orthotropic, RefusesConstantsThatAreNotPositiveDefinite) {
  Orthotropic bad = isotropic(70e9, 0.3);
  bad.nu12 = 1.2;
  EXPECT_THROW(stiffness(bad), std::invalid_argument);
  EXPECT_THROW(honeycomb_core(70e9, 0.3, 1e-3, 2e-3), std::invalid_argument);
}

}  // namespace
}  // namespace hvi::fem
