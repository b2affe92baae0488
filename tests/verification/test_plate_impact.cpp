// 1D plate impact (cases/verification/plate_impact.toml): Al6061 on Al6061 in uniaxial strain,
// hydrodynamic (no strength) with the Mie-Grüneisen EOS and bulk viscosity. Same materials on both
// sides, so by symmetry u_p = v / 2 and, on the linear Us-up Hugoniot (impedance matching),
//   Us = c0 + s u_p,   P = rho0 Us u_p       (rho0 2770 kg/m^3, c0 5350 m/s, s 1.34).
// The test measures the shocked pressure and particle velocity between the impact plane and the
// front, the shock speed from the front positions at 0.5 and 1 us, the front width (10-90% of
// the plateau) and the ringing behind it.
#include <algorithm>
#include <cmath>
#include <numeric>

#include <gtest/gtest.h>
#include <omp.h>

#include "mpm/types.hpp"
#include "tests/verification/scene_run.hpp"

namespace hvi {
namespace {

struct Profile {
  std::vector<double> x, p, v;  // sorted by x
};

Profile profile(const mpm::Particles& P) {
  std::vector<std::size_t> order(P.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](auto a, auto b) { return P.position[3 * a] < P.position[3 * b]; });
  Profile out;
  for (const auto i : order) {
    out.x.push_back(P.position[3 * i]);
    out.p.push_back(-mpm::trace_sym(&P.stress[6 * i]) / 3.0);
    out.v.push_back(P.velocity[3 * i]);
  }
  return out;
}

struct ShockState {
  double pressure, velocity, front, width_cells, scatter, overshoot;
};

// The plateau is the target between 0.3 mm behind its moved impact face and 0.4 mm before the
// expected front; the front is where the pressure falls through half the plateau.
ShockState measure(const Profile& f, double t, double up, double Us, double h) {
  double sum_p = 0, sum_v = 0, max_p = 0;
  int n = 0;
  for (std::size_t k = 0; k < f.x.size(); ++k)
    if (f.x[k] > 0.3e-3 + up * t && f.x[k] < Us * t - 0.4e-3) {
      sum_p += f.p[k];
      sum_v += f.v[k];
      max_p = std::max(max_p, f.p[k]);
      ++n;
    }
  const double P = sum_p / n;
  double var = 0;
  for (std::size_t k = 0; k < f.x.size(); ++k)
    if (f.x[k] > 0.3e-3 + up * t && f.x[k] < Us * t - 0.4e-3) var += (f.p[k] - P) * (f.p[k] - P);
  auto last_above = [&](double level) {
    std::size_t j = 0;
    for (std::size_t k = 0; k < f.x.size(); ++k)
      if (f.p[k] > level) j = k;
    return j;
  };
  const std::size_t j = last_above(0.5 * P);
  const double front = f.x[j] + (0.5 * P - f.p[j]) * (f.x[j + 1] - f.x[j]) / (f.p[j + 1] - f.p[j]);
  const double width = (f.x[last_above(0.1 * P)] - f.x[last_above(0.9 * P)]) / h;
  return {P, sum_v / n, front, width, std::sqrt(var / n) / P, max_p / P - 1};
}

void check_plate_impact(double v) {
  omp_set_num_threads(1);  // a small 1D problem: threads only add overhead
  const double rho0 = 2770, c0 = 5350, s = 1.34, h = 0.05e-3;
  const double up = v / 2, Us = c0 + s * up, P = rho0 * Us * up;
  test::SceneRun run("verification/plate_impact.toml",
                     {"body.flyer.velocity=[" + std::to_string(v) + ", 0, 0]"});
  run.run_to(0.5e-6);
  const ShockState a = measure(profile(run.particles()), 0.5e-6, up, Us, h);
  run.run_to(1.0e-6);
  const ShockState b = measure(profile(run.particles()), 1.0e-6, up, Us, h);
  const double Us_measured = (b.front - a.front) / 0.5e-6;
  std::printf(
      "v = %.0f m/s: P = %.4g GPa (impedance match %.4g, %+.2f%%), u_p = %.1f m/s, Us = %.1f m/s "
      "(%.1f, %+.2f%%), front width %.1f cells, scatter %.1f%%, overshoot %.1f%%\n",
      v, b.pressure / 1e9, P / 1e9, 100 * (b.pressure / P - 1), b.velocity, Us_measured, Us,
      100 * (Us_measured / Us - 1), b.width_cells, 100 * b.scatter, 100 * b.overshoot);
  // The bound: shocked pressure and shock speed within 3% of impedance matching.
  EXPECT_NEAR(b.pressure / P, 1.0, 0.03);
  EXPECT_NEAR(a.pressure / P, 1.0, 0.03);
  EXPECT_NEAR(Us_measured / Us, 1.0, 0.03);
  EXPECT_NEAR(b.velocity / up, 1.0, 0.01);  // momentum: u_p = v/2 by symmetry
  // "A few cells": measured 2.6-4.8 cells with the default viscosity; 6 allows for noise.
  EXPECT_LT(b.width_cells, 6.0);
  EXPECT_LT(a.width_cells, 6.0);
  // Ringing behind the front (measured: scatter 3-5%, largest overshoot 10-12%): bounded at
  // 8% scatter and 20% overshoot, well under the 30% and 10% that uGIMP without a linear
  // viscosity term shows.
  EXPECT_LT(b.scatter, 0.08);
  EXPECT_LT(b.overshoot, 0.20);
}

TEST(PlateImpact, Al6061At1kmPerSecondMatchesImpedanceMatching) {
  check_plate_impact(1000.0);
}
TEST(PlateImpact, Al6061At3kmPerSecondMatchesImpedanceMatching) {
  check_plate_impact(3000.0);
}

// The full material (Johnson-Cook strength on top of the EOS): the deviator adds 2/3 Y to the
// longitudinal stress and an elastic precursor runs ahead, so the plastic front is measured
// against the same Hugoniot: measured P -1.35% / Us +1.23% at 1 km/s, P 0.0% / Us +0.43% at
// 3 km/s. Bound: the 3%. (The front width here includes the precursor's ramp.)
TEST(PlateImpact, WithJohnsonCookStrengthStaysWithin3Percent) {
  omp_set_num_threads(1);
  for (const double v : {1000.0, 3000.0}) {
    const double up = v / 2, Us = 5350 + 1.34 * up, P = 2770 * Us * up;
    test::SceneRun run("verification/plate_impact.toml",
                       {"body.flyer.velocity=[" + std::to_string(v) + ", 0, 0]",
                        "material.Al6061.strength=johnson-cook"});
    run.run_to(0.5e-6);
    const ShockState a = measure(profile(run.particles()), 0.5e-6, up, Us, 0.05e-3);
    run.run_to(1.0e-6);
    const ShockState b = measure(profile(run.particles()), 1.0e-6, up, Us, 0.05e-3);
    EXPECT_NEAR(b.pressure / P, 1.0, 0.03) << v;
    EXPECT_NEAR((b.front - a.front) / 0.5e-6 / Us, 1.0, 0.03) << v;
  }
}

}  // namespace
}  // namespace hvi
