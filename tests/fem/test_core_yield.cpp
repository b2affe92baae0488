// The far field's yielding core (fem/core_yield.hpp) against closed forms: its caps from the
// walls' yield stress, and a block of core strained homogeneously through the matrix-free force,
// out of plane (uniaxial strain along z) and in transverse shear, loaded past yield and reversed.
// Each cap is elastic-perfectly plastic, so every stress, plastic strain and the plastic work are
// exact piecewise-linear functions of the strain: tolerances are round-off (1e-9 relative). A
// failing core tears where its walls' Johnson-Cook damage reaches 1: its failure strains, and the
// same blocks loaded past them, against the closed forms (the step the damage crosses 1 in is known
// in closed form, so these too hold to round-off).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "block.hpp"
#include "fem/core_yield.hpp"
#include "fem/far_field.hpp"

namespace hvi::fem {
namespace {

using test::L;

// The study panel's core (Table 3): Al5052 walls (Table 4: E, nu, density, Johnson-Cook A),
// D_hc = 3.0 mm, t_hc = 0.05 mm.
constexpr double Es = 73e9, nus = 0.33, rhos = 2680, sigma_ys = 265e6, D = 3.0e-3, t = 0.05e-3;

TEST(CoreYield, CapsAreTheWallsYieldThroughTheModuli) {
  const double solidity = honeycomb_core_solidity(D, t);
  const CoreYield single = honeycomb_core_yield(honeycomb_core(Es, nus, D, t), Es, nus, sigma_ys);
  // Flatwise: every wall yields along z at once, sigma_ys times the walls' area fraction.
  EXPECT_NEAR(single.normal, sigma_ys * solidity, 1e-12 * single.normal);
  // Transverse shear of single walls: G13 = G_s t / D, so Y13 = (sigma_ys / sqrt 3) t / D.
  EXPECT_NEAR(single.shear_xz, sigma_ys / std::sqrt(3.0) * t / D, 1e-12 * single.shear_xz);
  EXPECT_NEAR(single.shear_yz, single.shear_xz, 1e-12 * single.shear_xz);
  // Double walls: along the ribbon (yz) 19/12 of the single-wall value, as G23.
  const CoreYield doubled =
      honeycomb_core_yield(honeycomb_core(Es, nus, D, t, true), Es, nus, sigma_ys);
  EXPECT_NEAR(doubled.shear_yz, 19.0 / 12.0 * single.shear_xz, 1e-12 * single.shear_xz);
  EXPECT_NEAR(doubled.shear_xz, single.shear_xz, 1e-12 * single.shear_xz);
  EXPECT_NEAR(doubled.normal, sigma_ys * honeycomb_core_solidity(D, t, true),
              1e-12 * doubled.normal);
}

// Table 4's Al5052 damage: D1 = D2 = 0.13, D3 = -1.50.
materials::JohnsonCookDamage al5052_damage() {
  materials::JohnsonCookDamage d;
  d.D1 = 0.13, d.D2 = 0.13, d.D3 = -1.50, d.D4 = 0.011;
  return d;
}

CoreYield failing_caps(const Orthotropic& core) {
  CoreYield caps = honeycomb_core_yield(core, Es, nus, sigma_ys);
  caps.failure = honeycomb_core_failure(al5052_damage());
  return caps;
}

LayeredMesh core_block(int degree, bool yielding, bool failing = false) {
  const Orthotropic core = honeycomb_core(Es, nus, D, t);
  LayeredMesh m;
  m.lower = {0, 0};
  m.x_steps = {0.5 * L, 0.5 * L};
  m.y_steps = {0.5 * L, 0.5 * L};
  std::optional<CoreYield> caps;
  if (yielding) caps = failing ? failing_caps(core) : honeycomb_core_yield(core, Es, nus, sigma_ys);
  m.layers = {{"core", 0, L, 2, core, rhos * honeycomb_core_solidity(D, t), std::nullopt, caps,
               std::nullopt}};
  m.degree = degree;
  return m;
}

// Column `axis` of the homogeneous stress, read from the forces on the face X_axis = L.
std::array<double, 3> traction(FarField& f, int axis) {
  std::vector<double> force(3 * f.node_count());
  f.internal_force(force);
  auto s = test::face_force(force, f, axis);
  for (double& v : s) v /= -(L * L);
  return s;
}

// Uniaxial strain e along z: sigma_zz = C33 (e - e_p) clamped to +-Y3, e_p moving only at a cap;
// sigma_xx = C13 (e - e_p). Loaded to 3 e_y (e_y = Y3 / C33), then back to 0: reverse yield sets
// in at e = e_max - 2 e_y = e_y and leaves e_p = e_y at the end. Plastic work: Y3 (2 e_y + e_y) V.
TEST(CoreYield, UniaxialStrainOutOfPlaneLoadAndReverse) {
  const Orthotropic core = honeycomb_core(Es, nus, D, t);
  const auto C = stiffness(core);
  const CoreYield caps = honeycomb_core_yield(core, Es, nus, sigma_ys);
  const double ey = caps.normal / C[2], V = L * L * L;
  for (const int degree : {1, 2}) {
    FarField f(core_block(degree, true));
    ASSERT_TRUE(f.plastic());
    double ep = 0;  // the closed form's plastic strain
    auto check = [&](double e) {
      test::deform(f, {{{0, 0, 0}, {0, 0, 0}, {0, 0, e}}});
      const double trial = C[2] * (e - ep);
      if (std::abs(trial) > caps.normal) ep = e - std::copysign(caps.normal, trial) / C[2];
      const auto sz = traction(f, 2), sx = traction(f, 0);
      EXPECT_NEAR(sz[2], C[2] * (e - ep), 1e-9 * caps.normal) << "degree " << degree << ", e " << e;
      EXPECT_NEAR(sx[0], C[4] * (e - ep), 1e-9 * caps.normal) << "degree " << degree << ", e " << e;
      EXPECT_NEAR(sz[0], 0.0, 1e-9 * caps.normal);
    };
    const int n = 30;
    for (int k = 1; k <= n; ++k) check(3 * ey * k / n);
    EXPECT_NEAR(ep, 2 * ey, 1e-12 * ey);
    EXPECT_NEAR(f.max_core_plastic_strain(), 2 * ey, 1e-9 * ey);
    for (int k = n - 1; k >= 0; --k) check(3 * ey * k / n);
    EXPECT_NEAR(ep, ey, 1e-9 * ey);
    EXPECT_NEAR(f.max_core_plastic_strain(), 3 * ey, 1e-9 * ey);
    EXPECT_NEAR(f.plastic_work(), 3 * caps.normal * ey * V, 1e-9 * caps.normal * ey * V);
    EXPECT_EQ(f.max_equivalent_plastic_strain(), 0.0);  // no J2 layer
    // The stored energy is the residual elastic strain's: -e_p at zero strain, 1/2 C33 e_y^2 V.
    EXPECT_NEAR(f.strain_energy(), 0.5 * C[2] * ey * ey * V, 1e-9 * C[2] * ey * ey * V);
  }
}

// Transverse shear u_x = gamma z (and u_y = gamma z): sigma_xz = G13 (gamma - gamma_p) capped at
// Y13, sigma_yz likewise at Y23; loaded to 3 gamma_y and held there.
TEST(CoreYield, TransverseShearCapsAtTheWallsShearYield) {
  const Orthotropic core = honeycomb_core(Es, nus, D, t);
  const CoreYield caps = honeycomb_core_yield(core, Es, nus, sigma_ys);
  const double gy = caps.shear_xz / core.G13, V = L * L * L;
  FarField f(core_block(2, true));
  for (const double g : {0.5 * gy, gy, 2 * gy, 3 * gy}) {
    test::deform(f, {{{0, 0, g}, {0, 0, g}, {0, 0, 0}}});
    const auto sz = traction(f, 2);
    const double expected = std::min(core.G13 * g, caps.shear_xz);
    EXPECT_NEAR(sz[0], expected, 1e-9 * caps.shear_xz) << "gamma " << g;
    EXPECT_NEAR(sz[1], std::min(core.G23 * g, caps.shear_yz), 1e-9 * caps.shear_yz)
        << "gamma " << g;
    EXPECT_NEAR(sz[2], 0.0, 1e-9 * caps.shear_xz);
  }
  // gamma_p = 2 gamma_y in each of the two shears; work Y (2 gamma_y) V each.
  EXPECT_NEAR(f.max_core_plastic_strain(), 4 * gy, 1e-9 * gy);
  EXPECT_NEAR(f.plastic_work(), 2 * caps.shear_xz * 2 * gy * V, 1e-9 * caps.shear_xz * gy * V);
}

// eps_f = D1 + D2 exp(D3 triaxiality) at the reference rate and room temperature (D4 drops out):
// the walls of a core pulled along z are in uniaxial tension (1/3), pushed in compression (-1/3),
// sheared in pure shear (0).
TEST(CoreFailure, StrainsAreTheWallsJohnsonCookDamageByMode) {
  const CoreFailure f = honeycomb_core_failure(al5052_damage());
  EXPECT_NEAR(f.tension, 0.13 + 0.13 * std::exp(-0.5), 1e-15);
  EXPECT_NEAR(f.compression, 0.13 + 0.13 * std::exp(0.5), 1e-15);
  EXPECT_NEAR(f.shear, 0.26, 1e-15);
}

// Uniaxial strain along z in steps of de: sigma_zz = C33 e to e_y, Y3 on the plateau while the
// damage e_p / eps_f(1/3) < 1, then 0 from the step it reaches 1 in, k_f = the first k with
// k de - e_y >= eps_f, and on through unloading into compression (torn walls carry nothing out of
// plane; sigma_xx = C13 (e - e_p) with them). At the tear all the work put in, the area under the
// curve Y3 (e_kf - e_y / 2) V, has been dissipated and nothing is stored; after it no more work is
// taken, and the accumulated plastic strain stays at e_kf - e_y.
TEST(CoreFailure, UniaxialStrainTearsAtTheWallsTensileFailureStrain) {
  const Orthotropic core = honeycomb_core(Es, nus, D, t);
  const auto C = stiffness(core);
  const CoreYield caps = failing_caps(core);
  const double ey = caps.normal / C[2], ef = caps.failure->tension, V = L * L * L;
  const double de = (ey + ef) / 20.5;  // the damage reaches 1 in step 21, not at a step's end
  const int kf = 21;
  ASSERT_LT(20 * de - ey, ef);
  ASSERT_GE(kf * de - ey, ef);
  for (const int degree : {1, 2}) {
    FarField f(core_block(degree, true, true));
    double work_at_tear = 0;
    for (int k = 1; k <= 30; ++k) {
      const double e = k * de;
      test::deform(f, {{{0, 0, 0}, {0, 0, 0}, {0, 0, e}}});
      const double szz = e <= ey ? C[2] * e : k < kf ? caps.normal : 0.0;
      const auto sz = traction(f, 2), sx = traction(f, 0);
      EXPECT_NEAR(sz[2], szz, 1e-9 * caps.normal) << "degree " << degree << ", step " << k;
      EXPECT_NEAR(sx[0], C[4] / C[2] * szz, 1e-9 * caps.normal)
          << "degree " << degree << ", step " << k;
      if (k == kf) {
        work_at_tear = f.plastic_work();
        EXPECT_NEAR(f.plastic_work(), caps.normal * (e - 0.5 * ey) * V,
                    1e-9 * caps.normal * ef * V);
        EXPECT_NEAR(f.strain_energy(), 0.0, 1e-12 * caps.normal * ef * V);
        EXPECT_NEAR(f.core_failed_volume(), V, 1e-12 * V);
        // Every cell of the 2 x 2 x 2 block is torn: its in-plane centres, at L/4 and 3L/4.
        const std::vector<double> centres = f.damaged_cell_centres(1.0);
        ASSERT_EQ(centres.size(), 16u);
        for (const double c : centres)
          EXPECT_TRUE(std::abs(c - 0.25 * L) < 1e-12 * L || std::abs(c - 0.75 * L) < 1e-12 * L)
              << c;
      }
      if (k < kf) {
        EXPECT_EQ(f.core_failed_volume(), 0.0) << "step " << k;
        EXPECT_TRUE(f.damaged_cell_centres(1.0).empty()) << "step " << k;
      }
    }
    for (int k = 29; k >= -10; --k) {  // back through zero and 10 steps into compression
      test::deform(f, {{{0, 0, 0}, {0, 0, 0}, {0, 0, k * de}}});
      const auto sz = traction(f, 2);
      EXPECT_NEAR(sz[2], 0.0, 1e-9 * caps.normal) << "degree " << degree << ", step " << k;
      EXPECT_NEAR(traction(f, 0)[0], 0.0, 1e-9 * caps.normal)
          << "degree " << degree << ", step " << k;
    }
    EXPECT_NEAR(f.strain_energy(), 0.0, 1e-12 * caps.normal * ef * V);
    // Torn walls take no more work: the point exerts no force, whatever the strain does.
    EXPECT_EQ(f.plastic_work(), work_at_tear);
    // The accumulated strain is the walls' plastic strain to the tear, not what the torn core took
    // after.
    EXPECT_NEAR(f.max_core_plastic_strain(), kf * de - ey, 1e-9 * ef);
  }
}

// Transverse shear u_x = gamma z in steps of dg: sigma_xz = G13 gamma to gamma_y, Y13 while the
// damage gamma_p / (sqrt(3) eps_f(0)) < 1, then 0; sigma_yz stays 0 throughout. Work to the tear:
// Y13 (gamma_kf - gamma_y / 2) V.
TEST(CoreFailure, TransverseShearTearsAtTheWallsShearFailureStrain) {
  const Orthotropic core = honeycomb_core(Es, nus, D, t);
  const CoreYield caps = failing_caps(core);
  const double gy = caps.shear_xz / core.G13, gf = std::sqrt(3.0) * caps.failure->shear,
               V = L * L * L;
  const double dg = (gy + gf) / 12.5;
  const int kf = 13;
  FarField f(core_block(2, true, true));
  for (int k = 1; k <= 16; ++k) {
    const double g = k * dg;
    test::deform(f, {{{0, 0, g}, {0, 0, 0}, {0, 0, 0}}});
    const double sxz = g <= gy ? core.G13 * g : k < kf ? caps.shear_xz : 0.0;
    const auto sz = traction(f, 2);
    EXPECT_NEAR(sz[0], sxz, 1e-9 * caps.shear_xz) << "step " << k;
    EXPECT_NEAR(sz[1], 0.0, 1e-9 * caps.shear_xz) << "step " << k;
    if (k == kf) {
      EXPECT_NEAR(f.plastic_work(), caps.shear_xz * (g - 0.5 * gy) * V,
                  1e-9 * caps.shear_xz * gf * V);
      EXPECT_NEAR(f.strain_energy(), 0.0, 1e-12 * caps.shear_xz * gf * V);
    }
  }
  // Torn: the other shear carries nothing either.
  test::deform(f, {{{0, 0, 16 * dg}, {0, 0, dg}, {0, 0, 0}}});
  EXPECT_NEAR(traction(f, 2)[1], 0.0, 1e-9 * caps.shear_xz);
}

// The far field alone in motion, a core block fixed at z = 0 and thrown into shear and stretch
// (v_x = 400 m/s z / L, v_z = 100 m/s z / L), run by central differences at half the stable step:
// the energy, kinetic (of the mean of the half-step velocities) + stored + plastic work, is
// conserved through yield and through the tear of a quarter of the block. The bound is what the
// yielding core meets in the same run (the integrator's error while the block first yields,
// 3.3e-3), met by both; work booked for a torn point's elastic predictor (1/2 C d eps^2 a step, a
// force it never exerts) would add some 2.8 E0 in these 1,500 steps.
TEST(CoreFailure, EnergyIsConservedThroughTheTearInMotion) {
  for (const bool failing : {false, true}) {
    LayeredMesh m = core_block(2, true, failing);
    m.x_steps = {0.25 * L, 0.25 * L, 0.25 * L, 0.25 * L};
    m.layers[0].elements = 8;
    FarField f(m);
    test::throw_block(f, 400.0, 100.0);
    const double dt = 0.5 * f.stable_time_step(), E0 = f.kinetic_energy();
    std::vector<double> before(3 * f.node_count()), mean(3 * f.node_count());
    double worst = 0.0;
    for (int k = 0; k < 1500; ++k) {
      std::copy(f.velocity().begin(), f.velocity().end(), before.begin());
      f.step(dt);
      for (std::size_t i = 0; i < mean.size(); ++i) mean[i] = 0.5 * (before[i] + f.velocity()[i]);
      const double E = f.kinetic_energy(mean) + f.strain_energy() + f.plastic_work();
      worst = std::max(worst, std::abs(E / E0 - 1.0));
    }
    EXPECT_LT(worst, 3.5e-3) << (failing ? "failing" : "yielding");
    EXPECT_GT(f.plastic_work(), 0.25 * E0);  // the block yielded well past its elastic energy
    if (failing) {
      EXPECT_GT(f.core_failed_volume(), 0.1 * L * L * L);  // and tore
    }
  }
}

// An elastic core keeps no state; a layer may not name both models.
TEST(CoreYield, OnlyWhenNamedAndNotWithJ2) {
  EXPECT_FALSE(FarField(core_block(1, false)).plastic());
  EXPECT_EQ(FarField(core_block(1, true)).core_failed_volume(),
            0.0);  // a yielding core keeps no damage
  EXPECT_TRUE(FarField(core_block(1, true)).damaged_cell_centres(0.0).empty());
  LayeredMesh both = core_block(1, true);
  both.layers[0].elasticity = isotropic(test::E, test::nu);
  both.layers[0].plasticity = test::al6061();
  EXPECT_THROW(FarField{both}, std::invalid_argument);
}

}  // namespace
}  // namespace hvi::fem
