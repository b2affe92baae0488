// The energy ledger (mpm/energy_ledger.hpp): each body's energy phase by phase. Checked on the
// head-on collision of two elastic spheres (test_sphere_collision.cpp's), where the answers are
// known: the ledger's kinetic and internal columns add up to the solver's energy report; for an
// elastic solid the work its stresses do on the grid is the strain energy it stores (W = -dU), so
// what the ledger books as the stress update's and the transfer's errors are the time
// integration's, first order in the time step; the two mirror-image spheres book the same; and a
// body that flies out of the grid is booked as removed with the energy it carried. Bitwise for
// any thread count.
#include <cmath>

#include <gtest/gtest.h>

#include "mpm_test_helpers.hpp"

namespace hvi::mpm::test {
namespace {

using Row = std::array<double, ledger::columns>;

// Two aluminium-like spheres of radius 5 cells (1 mm cells, 2 points per cell), 2 cells apart,
// at +-300 m/s; GIMP, MUSL. They touch from about step 12 and part by about step 110.
std::unique_ptr<Solver> spheres(double v0 = 300.0, double cfl = 0.5) {
  const double h = 1e-3, R = 5 * h;
  SolverSettings settings;
  settings.cfl = cfl;
  settings.shape = ShapeFunction::gimp;
  settings.energy_ledger = true;
  auto solver = std::make_unique<Solver>(
      grid({-24 * h, -8 * h, -8 * h}, h, {48, 16, 16}), settings,
      one_material(std::make_unique<LinearElastic>("aluminium", 2700.0, 70e9, 0.3)),
      std::vector<std::string>{"left", "right"}, std::vector<GridBoundary>{});
  add_body(*solver, geometry::Sphere({-(R + h), 0, 0}, R), 2, 0, 0, uniform({v0, 0, 0}));
  add_body(*solver, geometry::Sphere({R + h, 0, 0}, R), 2, 1, 0, uniform({-v0, 0, 0}));
  solver->initialise();
  return solver;
}

double column_sum(const EnergyReport& e, int column) {
  double s = 0.0;
  for (const Row& r : e.ledger) s += r[column];
  return s;
}

TEST(EnergyLedger, ColumnsAddUpToTheEnergyReport) {
  const Threads threads(1);
  auto s = spheres();
  const EnergyReport e0 = s->energy();
  const double E0 = e0.total();
  for (int k = 0; k < 60; ++k) s->step();  // in contact: both columns large
  const EnergyReport e = s->energy();
  ASSERT_EQ(e.ledger.size(), 2u);
  // The kinetic energy changes only in the transfer, the internal energy (strain and
  // dissipated) only in the stress update.
  EXPECT_NEAR(column_sum(e, ledger::transfer_kinetic), e.kinetic - e0.kinetic, 1e-12 * E0);
  EXPECT_NEAR(column_sum(e, ledger::stress_internal),
              (e.internal + e.dissipated) - (e0.internal + e0.dissipated), 1e-12 * E0);
  EXPECT_GT(e0.kinetic - e.kinetic, 0.3 * E0);  // much of the energy is strain energy now
  EXPECT_EQ(column_sum(e, ledger::removed), 0.0);
  EXPECT_EQ(column_sum(e, ledger::failed_internal), 0.0);  // elastic: nothing fails
}

// Run to the same time (the spheres have met and parted), the ledger's two errors are the time
// integration's: the stress update books more internal energy than the stresses did work on the
// grid, FLIP's transfer gives the points less kinetic energy than the nodes gained, each by 8.6%
// of E0 at cfl 0.5 (measured), so that they nearly cancel (the balance is -0.9%). Both are first
// order in the time step: halving it halves them (measured ratios 1.99 and 1.98).
TEST(EnergyLedger, ItsErrorsAreFirstOrderInTheTimeStep) {
  const Threads threads(1);
  double stress[2], transfer[2];
  for (int k = 0; k < 2; ++k) {
    auto s = spheres(300.0, k == 0 ? 0.5 : 0.25);
    const double E0 = s->energy().total();
    while (s->time() < 16e-6) s->step();  // about 200 steps at cfl 0.5: met and parted
    const EnergyReport e = s->energy();
    const Row& left = e.ledger[0];
    stress[k] = (left[ledger::stress_internal] + left[ledger::force_work]) / E0;
    transfer[k] = (left[ledger::transfer_kinetic] - left[ledger::force_work]) / E0;
    // The mirror images book the same, to round-off.
    for (int c = 0; c < ledger::columns; ++c)
      EXPECT_NEAR(e.ledger[0][c], e.ledger[1][c], 1e-9 * E0) << ledger::name(c);
  }
  EXPECT_GT(stress[0], 0.05);
  EXPECT_LT(stress[0], 0.12);
  EXPECT_LT(transfer[0], -0.05);
  EXPECT_GT(transfer[0], -0.12);
  EXPECT_NEAR(stress[0] / stress[1], 2.0, 0.1);
  EXPECT_NEAR(transfer[0] / transfer[1], 2.0, 0.1);
}

TEST(EnergyLedger, BooksWhatLeavesTheGrid) {
  const Threads threads(1);
  const double h = 1e-3, v = 2000.0;
  SolverSettings settings;
  settings.energy_ledger = true;
  Solver s(grid({0, 0, 0}, h, {16, 8, 8}), settings,
           one_material(std::make_unique<LinearElastic>("aluminium", 2700.0, 70e9, 0.3)),
           {"leaving"}, {});
  add_body(s, geometry::Box({12 * h, 2 * h, 2 * h}, {14 * h, 4 * h, 4 * h}), 2, 0, 0,
           uniform({v, 0, 0}));
  s.initialise();
  const double K0 = s.energy().kinetic;
  while (s.particles().size() > 0 && s.step_count() < 200) s.step();
  const EnergyReport e = s.energy();
  ASSERT_EQ(s.particles().size(), 0u);
  // A free body in uniform motion: no stress, no work, nothing transferred; all of it removed.
  EXPECT_NEAR(e.ledger[0][ledger::removed], K0, 1e-12 * K0);
  EXPECT_NEAR(e.ledger[0][ledger::transfer_kinetic], 0.0, 1e-12 * K0);
  EXPECT_NEAR(e.ledger[0][ledger::force_work], 0.0, 1e-12 * K0);
}

TEST(EnergyLedger, SameBitsForAnyThreadCount) {
  std::vector<double> ledgers[2];
  for (int t = 0; t < 2; ++t) {
    const Threads threads(t + 1);
    auto s = spheres();
    for (int k = 0; k < 40; ++k) s->step();
    ledgers[t] = s->state().ledger;
  }
  EXPECT_TRUE(same_bytes(ledgers[0], ledgers[1]));
}

}  // namespace
}  // namespace hvi::mpm::test
