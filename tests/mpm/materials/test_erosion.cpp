// Erosion by compression: a point erodes in the step its volume ratio falls below r_min, not one
// step sooner or later; until then it is the same material to the bit; afterwards it carries no
// stress, does no work (its energy and volume stay), and its signal speed is its speed alone.
// The step it erodes in books only the work the grid has paid.
#include <cmath>

#include <gtest/gtest.h>

#include "mpm/materials/hydro_material.hpp"
#include "mpm/materials/library.hpp"
#include "tests/mpm/materials/material_driver.hpp"

namespace hvi::mpm {
namespace {

TEST(CompressionErosion, ErodesInTheStepTheVolumeRatioCrossesTheLimit) {
  const HydroModels plain = find_library_material("Al5052")->parameters;
  HydroModels eroding = plain;
  eroding.erosion = CompressionErosion{0.5};
  const HydroMaterial with("core", eroding), without("core", plain);
  test::MaterialPoint a(with), b(without);

  // Isotropic compression L = -k I: each step multiplies the volume by det(I + dt L) = (1 - k
  // dt)^3, so the ratio first falls below 0.5 at step n* = ceil(ln 0.5 / (3 ln(1 - k dt))) = 231.
  const double k = 1e6, dt = 1e-9;
  const double L[9] = {-k, 0, 0, 0, -k, 0, 0, 0, -k};
  const int expected = static_cast<int>(std::ceil(std::log(0.5) / (3.0 * std::log(1.0 - k * dt))));
  ASSERT_EQ(expected, 231);
  int eroded_at = -1;
  for (int n = 1; n <= 400 && eroded_at < 0; ++n) {
    a.step(L, dt);
    b.step(L, dt);
    if (a.field("failed") == failure_state::eroded) {
      eroded_at = n;
      break;
    }
    // Not yet eroded: bit for bit the material without erosion.
    ASSERT_EQ(a.field("failed"), failure_state::intact) << n;
    for (int c = 0; c < 6; ++c) ASSERT_EQ(a.stress()[c], b.stress()[c]) << n;
    ASSERT_EQ(a.particles.internal_energy[0], b.particles.internal_energy[0]) << n;
  }
  ASSERT_EQ(eroded_at, expected);
  // The energy of the eroding step leaves out the half of the work the zeroed stress would have
  // been paid in the next step: e = e_twin + p_twin dV / (2 m) (no deviator under isotropic
  // compression, no viscosity in the library material).
  const double m = a.particles.mass[0];
  const double dV = a.particles.volume[0] * (1.0 - 1.0 / std::pow(1.0 - k * dt, 3));
  const double p_twin = -b.stress()[0];
  EXPECT_NEAR(a.particles.internal_energy[0],
              b.particles.internal_energy[0] + 0.5 * p_twin * dV / m,
              1e-12 * b.particles.internal_energy[0]);
  EXPECT_LT(a.particles.internal_energy[0], b.particles.internal_energy[0]);
  const double ratio = a.particles.volume[0] / a.particles.volume0[0];
  EXPECT_LT(ratio, 0.5);
  EXPECT_GT(ratio, 0.5 * std::pow(1.0 - k * dt, 3));  // one step's compression below the limit
  for (int c = 0; c < 6; ++c) EXPECT_EQ(a.stress()[c], 0.0);
  // The twin at the same state carries 0.24 TPa (Mie-Grüneisen on this isentrope-like path; the
  // Hugoniot itself reaches 0.35 TPa at V/V0 = 0.5).
  EXPECT_GT(-b.stress()[0], 200e9);

  // Compressed on, the eroded point does no work: volume, energy and stress stay as they were.
  const double V = a.particles.volume[0], e = a.particles.internal_energy[0];
  for (int n = 0; n < 200; ++n) {
    const StressUpdate r = a.step(L, dt);
    ASSERT_EQ(r.bad_particle, -1);
    // It is at rest: no sound speed is left in its signal speed.
    ASSERT_EQ(r.max_signal_speed, 0.0);
  }
  EXPECT_EQ(a.particles.volume[0], V);
  EXPECT_EQ(a.particles.internal_energy[0], e);
  for (int c = 0; c < 6; ++c) EXPECT_EQ(a.stress()[c], 0.0);
  // Its signal speed is its speed: moving at 3 km/s it limits the step like any point at 3 km/s.
  a.particles.velocity[2] = -3000.0;
  EXPECT_EQ(with.max_signal_speed(a.particles, a.range), 3000.0);
}

// Tension does not erode, nor does compression short of the limit.
TEST(CompressionErosion, ExpansionAndModerateCompressionDoNotErode) {
  HydroModels models = find_library_material("Al5052")->parameters;
  models.damage.reset();  // no failure either: the point stays intact throughout
  models.erosion = CompressionErosion{0.5};
  const HydroMaterial material("core", models);
  test::MaterialPoint point(material);
  const double k = 1e6, dt = 1e-9;
  const double expand[9] = {k, 0, 0, 0, k, 0, 0, 0, k};
  for (int n = 0; n < 300; ++n) point.step(expand, dt);  // V/V0 = 2.46
  EXPECT_EQ(point.field("failed"), failure_state::intact);
  const double compress[9] = {-k, 0, 0, 0, -k, 0, 0, 0, -k};
  for (int n = 0; n < 500; ++n) point.step(compress, dt);  // back to V/V0 = 0.55
  EXPECT_GT(point.particles.volume[0] / point.particles.volume0[0], 0.5);
  EXPECT_EQ(point.field("failed"), failure_state::intact);
}

}  // namespace
}  // namespace hvi::mpm
