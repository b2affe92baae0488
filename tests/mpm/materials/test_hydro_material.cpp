// The laws inside HydroMaterial, driven through a material point: the stress path of
// uniaxial-strain compression with Johnson-Cook strength (paper eq. 1) against its closed form,
// and the Mie-Grüneisen EOS (paper eqs. 4-5) solved together with the energy equation.
#include <cmath>

#include <gtest/gtest.h>

#include "mpm/materials/hydro_material.hpp"
#include "mpm/materials/library.hpp"
#include "mpm/types.hpp"
#include "tests/mpm/materials/material_driver.hpp"

namespace hvi::mpm {
namespace {

// Uniaxial strain at constant rate: L = diag(-rate, 0, 0). Elastic until the deviator reaches the
// yield surface, then sigma_xx - sigma_yy = -sigma_y(eps_p) with, in this path,
//   eps_p = 2/3 eps - sigma_y(eps_p) / (3 G)   (eps = the accumulated compressive strain),
// and the pressure of the bulk response p = K eps. So sigma_xx = -K eps - 2/3 sigma_y.
TEST(JohnsonCook, UniaxialStrainPathMatchesClosedForm) {
  HydroModels models = find_library_material("Al6061")->parameters;
  models.eos.reset();
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
  EXPECT_NEAR(
      point.field("plastic_strain"),
      2.0 / 3.0 * eps - std::fabs(point.stress()[sym::xx] - point.stress()[sym::yy]) / (3 * G),
      1e-9);
}

// In the material the energy equation and the EOS are solved together:
//   e1 = e0 - (p0 + p1)/2 dV/m,  p1 = p(rho1, e1).
// Check the returned pressure and energy satisfy both to round-off after one compressive step.
TEST(MieGruneisen, MaterialSolvesEnergyAndPressureTogether) {
  HydroModels models = find_library_material("Al6061")->parameters;
  models.johnson_cook.reset();
  models.damage.reset();
  models.shear_strength = false;  // hydrodynamic: only the EOS acts
  const HydroMaterial material("al", models);
  test::MaterialPoint point(material);
  const double rate = 1e6, dt = 1e-8;
  const double L[9] = {-rate, 0, 0, 0, -rate, 0, 0, 0, -rate};
  double p_prev = 0.0;
  for (int step = 0; step < 50; ++step) {
    const double V0 = point.particles.volume[0], e0 = point.particles.internal_energy[0];
    point.step(L, dt);
    const double V1 = point.particles.volume[0], e1 = point.particles.internal_energy[0];
    const double m = point.particles.mass[0];
    const double p1 = -trace_sym(point.stress()) / 3.0;
    EXPECT_NEAR(e1, e0 - 0.5 * (p_prev + p1) * (V1 - V0) / m, 1e-9 * std::fabs(e1) + 1e-12);
    EXPECT_NEAR(p1, models.eos_as<MieGruneisen>()->pressure(m / V1, e1), 1e-10 * p1);
    p_prev = p1;
  }
  EXPECT_GT(p_prev, 5e9);  // the path reached a few GPa
}

}  // namespace
}  // namespace hvi::mpm
