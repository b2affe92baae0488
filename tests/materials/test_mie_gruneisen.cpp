// Mie-Grüneisen EOS (paper eqs. 4-5, standard form): pressure at given density and energy
// against the equations written out by hand, continuity of the Hugoniot branches, and the sound
// speed.
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "materials/equation_of_state.hpp"
#include "materials/mie_gruneisen.hpp"
#include "mpm/materials/library.hpp"

namespace hvi::materials {
namespace {

MieGruneisen al6061() {
  return *mpm::find_library_material("Al6061")->parameters.eos_as<MieGruneisen>();
}

TEST(MieGruneisen, PressureEqualsEquationsFourAndFive) {
  const MieGruneisen mg = al6061();  // rho0 2770, c0 5350, s 1.34, Gamma0 2.0
  const double rho0 = 2770, c0 = 5350, s = 1.34, g0 = 2.0;
  // Compression: rho = 1.2 rho0, e = 1e5 J/kg.
  {
    const double mu = 0.2, e = 1e5;
    const double pH = rho0 * c0 * c0 * mu * (1 + mu) / std::pow(1 - (s - 1) * mu, 2);
    const double gamma = g0 / (1 + mu);
    const double expected = pH * (1 - gamma * mu / 2) + g0 * rho0 * e;
    EXPECT_NEAR(mg.pressure(1.2 * rho0, e), expected, 1e-12 * expected);
    EXPECT_NEAR(expected, 1.8809e10, 1e6);  // 18.8 GPa computed by hand (calculator), 5 digits
  }
  // Tension: rho = 0.95 rho0, e = 1e5 J/kg: the linear branch plus a thermal pressure with
  // constant Gamma0 (no (1 - Gamma mu / 2) factor, and Gamma rho = Gamma0 rho in expansion).
  {
    const double mu = 0.95 - 1, e = 1e5;
    const double expected = rho0 * c0 * c0 * mu + g0 * 0.95 * rho0 * e;
    EXPECT_NEAR(mg.pressure(0.95 * rho0, e), expected, 1e-12 * std::fabs(expected));
  }
  // Far expanded debris keeps a bounded pressure and sound speed.
  EXPECT_GT(mg.pressure(rho0 / 80, 5e5), -rho0 * c0 * c0);
  EXPECT_NEAR(mg.bulk_sound_speed_squared(rho0 / 80, mg.pressure(rho0 / 80, 0.0)), 0.1 * c0 * c0,
              1e-9 * c0 * c0);
  // The energy coefficient dp/de is continuous at rho0 and bounded by Gamma0 rho0 in expansion.
  EXPECT_DOUBLE_EQ(mg.energy_coefficient(rho0), g0 * rho0);
  EXPECT_DOUBLE_EQ(mg.energy_coefficient(rho0 / 250), g0 * rho0 / 250);
  // Reference state: no pressure.
  EXPECT_EQ(mg.pressure(rho0, 0.0), 0.0);
}

TEST(MieGruneisen, HugoniotBranchesJoinWithTheBulkModulus) {
  const MieGruneisen mg = al6061();
  const double K0 = 2770.0 * 5350 * 5350;
  for (double mu : {-1e-9, 1e-9}) EXPECT_NEAR(mg.hugoniot_pressure(mu) / mu, K0, 1e-8 * K0);
  EXPECT_NEAR(mg.hugoniot_slope(0.0), K0, 1e-12 * K0);
  // The slope is the derivative of the pressure (central difference, O(h^2) error ~ 1e-8).
  for (double mu : {0.05, 0.3, 0.6}) {
    const double h = 1e-5;
    const double fd = (mg.hugoniot_pressure(mu + h) - mg.hugoniot_pressure(mu - h)) / (2 * h);
    EXPECT_NEAR(mg.hugoniot_slope(mu), fd, 1e-7 * fd) << mu;
  }
  // On the Hugoniot, with the Hugoniot energy e_H = p_H mu / (2 rho0 (1 + mu)), the EOS gives p_H:
  // the paper's (1 - Gamma mu / 2) factor is exactly what removes Gamma rho e_H.
  for (double mu : {0.1, 0.4}) {
    const double pH = mg.hugoniot_pressure(mu);
    const double eH = pH * mu / (2 * 2770.0 * (1 + mu));
    EXPECT_NEAR(mg.pressure(2770.0 * (1 + mu), eH), pH, 1e-12 * pH);
  }
}

TEST(MieGruneisen, SoundSpeedAtReferenceIsC0) {
  const MieGruneisen mg = al6061();
  EXPECT_NEAR(std::sqrt(mg.bulk_sound_speed_squared(2770.0, 0.0)), 5350.0, 1e-9 * 5350.0);
  // Compression stiffens the material.
  EXPECT_GT(mg.bulk_sound_speed_squared(1.2 * 2770.0, mg.pressure(1.2 * 2770.0, 0.0)),
            5350.0 * 5350.0);
}

// Every registered equation of state gives back the parameters it was built from, in the order
// of its parameter table, and answers through the registry as it does itself.
TEST(EquationOfState, EveryLawIsBuiltFromItsParameterTable) {
  for_each_equation_of_state([](auto type) {
    using Law = typename decltype(type)::type;
    std::array<double, Law::parameters.size()> values{};
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 1.5 + i;
    const Law law = Law::from(2700.0, values);
    EXPECT_EQ(law.values(), values) << Law::name;
    const EquationOfState eos = law;
    EXPECT_STREQ(name_of(eos), Law::name);
    EXPECT_EQ(reference_sound_speed(eos), law.reference_sound_speed());
    EXPECT_EQ(bulk_sound_speed_squared(eos, 3000.0, 1e9),
              law.bulk_sound_speed_squared(law.at(3000.0), 1e9));
  });
}

}  // namespace
}  // namespace hvi::materials
