// Particles leaving the grid: blocks flying out through an upper and a lower domain face are
// removed, and the removed-material ledger and removal events account for exactly what left,
// while a block at rest elsewhere is untouched.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "mpm_test_helpers.hpp"

namespace hvi::mpm::test {
namespace {

// What the blocks about to leave carry, and where the block at rest stands, at the start.
struct Leaving {
  std::map<std::int64_t, std::array<double, 3>> rest_position;
  double mass = 0.0, kinetic = 0.0;
  Vec3 momentum{};
  std::size_t count = 0;
};

Leaving tally(const Particles& P) {
  Leaving l;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (P.body[p] == 0) {
      l.rest_position[P.id[p]] = {P.position[3 * p], P.position[3 * p + 1], P.position[3 * p + 2]};
      continue;
    }
    ++l.count;
    l.mass += P.mass[p];
    double v2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      l.momentum[d] += P.mass[p] * P.velocity[3 * p + d];
      v2 += P.velocity[3 * p + d] * P.velocity[3 * p + d];
    }
    l.kinetic += 0.5 * P.mass[p] * v2;
  }
  return l;
}

// Events: one per leaving particle, from the right bodies, outside the domain when recorded.
void check_events(const std::vector<RemovalEvent>& events, const GridGeometry& g,
                  const Leaving& leaving, double v) {
  ASSERT_EQ(events.size(), leaving.count);
  double event_mass = 0.0;
  std::set<std::int64_t> ids;
  for (const auto& e : events) {
    ids.insert(e.id);
    event_mass += e.mass;
    EXPECT_TRUE(e.body == 1 || e.body == 2);
    EXPECT_FALSE(g.contains(e.position.data()));
    EXPECT_GT(e.time, 0.0);
    EXPECT_GT(e.step, 0);
    // Moving at v along +x (body 1) or -y (body 2), to the same round-off as above.
    const int axis = e.body == 1 ? 0 : 1;
    EXPECT_NEAR(std::fabs(e.velocity[axis]), v, 1e-12 * v);
    if (axis == 0)
      EXPECT_GE(e.position[0], g.upper()[0]);
    else
      EXPECT_LT(e.position[1], g.origin[1]);
  }
  EXPECT_EQ(ids.size(), leaving.count);  // each particle once
  EXPECT_NEAR(event_mass, leaving.mass, 1e-13 * leaving.mass);
}

// The block at rest is all there, unmoved and at rest (no force on it: exactly zero).
void check_rest_block(const Particles& P, const Leaving& leaving) {
  ASSERT_EQ(P.size(), leaving.rest_position.size());
  for (std::size_t p = 0; p < P.size(); ++p) {
    ASSERT_EQ(P.body[p], 0);
    const auto& x = leaving.rest_position.at(P.id[p]);
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(P.position[3 * p + d], x[d]);
      EXPECT_EQ(P.velocity[3 * p + d], 0.0);
    }
  }
}

void leave_domain(ShapeFunction shape) {
  const Threads threads(1);  // 192 particles
  const double h = 1e-3, v = 1500.0;
  SolverSettings settings;
  settings.shape = shape;
  Solver solver(grid({0, 0, 0}, h, {16, 12, 8}), settings,
                one_material(std::make_unique<LinearElastic>("aluminium", 2700.0, 70e9, 0.33)),
                {"rest", "out_x", "out_y"}, {});
  // 2-cell blocks, 2 particles per cell per direction (64 particles each), two cells apart so that
  // no grid node is shared (no stencil reaches more than 1 + 1/4 cell from its particle).
  add_body(solver, geometry::Box({2 * h, 2 * h, 2 * h}, {4 * h, 4 * h, 4 * h}), 2, 0, 0,
           uniform({0, 0, 0}));
  add_body(solver, geometry::Box({10 * h, 2 * h, 2 * h}, {12 * h, 4 * h, 4 * h}), 2, 1, 0,
           uniform({v, 0, 0}));
  add_body(solver, geometry::Box({6 * h, 2 * h, 2 * h}, {8 * h, 4 * h, 4 * h}), 2, 2, 0,
           uniform({0, -v, 0}));
  solver.initialise();

  const Particles& P = solver.particles();
  const Leaving leaving = tally(P);
  const Vec3 p0 = total_momentum(solver);
  const double pscale = leaving.mass * v;  // |momentum| of each leaving block, x2
  const double E0 = solver.energy().total();

  std::vector<RemovalEvent> events;
  double max_momentum_error = 0.0;
  while (solver.removed().particles < static_cast<std::int64_t>(leaving.count) &&
         solver.step_count() < 200) {
    solver.step();
    for (auto& e : solver.take_removal_events()) events.push_back(e);
    const Vec3 p = total_momentum(solver);
    for (int d = 0; d < 3; ++d)
      max_momentum_error = std::max(max_momentum_error, std::fabs(p[d] - p0[d]) / pscale);
  }
  ASSERT_EQ(solver.removed().particles, static_cast<std::int64_t>(leaving.count))
      << "after " << solver.step_count() << " steps";
  EXPECT_TRUE(solver.take_removal_events().empty());  // taken: the next call has nothing

  const RemovedMaterial& r = solver.removed();
  std::printf(
      "[removal %s] %lld steps; relative errors: mass %.2e kinetic %.2e momentum %.2e, "
      "removed internal %.2e J, total momentum %.2e, total energy %.2e\n",
      shape == ShapeFunction::linear ? "linear" : "gimp",
      static_cast<long long>(solver.step_count()), std::fabs(r.mass - leaving.mass) / leaving.mass,
      std::fabs(r.kinetic - leaving.kinetic) / leaving.kinetic,
      std::max(std::fabs(r.momentum[0] - leaving.momentum[0]),
               std::fabs(r.momentum[1] - leaving.momentum[1])) /
          pscale,
      r.internal, max_momentum_error, std::fabs(solver.energy().total() - E0) / E0);
  // Mass: the same 128 numbers summed in another order, n eps ~ 1.4e-14 at worst.
  EXPECT_NEAR(r.mass, leaving.mass, 1e-13 * leaving.mass);
  // Kinetic energy and momentum: the blocks move rigidly and unstressed, so the only change of a
  // particle velocity is from forces made of round-off (the gradient of a uniform nodal velocity
  // field is ~eps v / h, not 0): measured ~1e-16 relative. 1e-12 leaves a wide margin and still
  // catches any real error (a particle missed, counted twice, or recorded with a stale velocity).
  EXPECT_NEAR(r.kinetic, leaving.kinetic, 1e-12 * leaving.kinetic);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(r.momentum[d], leaving.momentum[d], 1e-12 * pscale);
  EXPECT_NEAR(r.internal, 0.0, 1e-12 * leaving.kinetic);
  // Total momentum (particles + removed) and total energy (including removed) conserved.
  EXPECT_LT(max_momentum_error, 1e-12);
  EXPECT_NEAR(solver.energy().total(), E0, 1e-12 * E0);
  EXPECT_NEAR(solver.energy().removed_mass, leaving.mass, 1e-13 * leaving.mass);

  check_events(events, solver.grid().geometry(), leaving, v);
  check_rest_block(P, leaving);
}

TEST(Removal, LedgerAndEventsLinear) {
  leave_domain(ShapeFunction::linear);
}
TEST(Removal, LedgerAndEventsGimp) {
  leave_domain(ShapeFunction::gimp);
}

// Particles::erase takes points out of groups that must stay contiguous (a solver's materials):
// each group's last points fill its gaps. Every survivor keeps all its fields, no removed point
// remains, each group keeps its survivors, and a group emptied entirely disappears.
TEST(Removal, EraseKeepsGroupsContiguousAndEverySurvivor) {
  Particles P;
  P.add_field("damage", FieldKind::scalar, "1");
  const std::vector<std::size_t> sizes = {10, 3, 0, 25, 7};
  std::size_t n = 0;
  for (std::size_t g = 0; g < sizes.size(); ++g)
    for (std::size_t k = 0; k < sizes[g]; ++k, ++n) {
      P.resize(n + 1);
      P.field("damage")[n] = 0.5 * static_cast<double>(n);
      P.id[n] = static_cast<std::int64_t>(n);
      P.material[n] = static_cast<std::int64_t>(g);
      for (int d = 0; d < 3; ++d) P.position[3 * n + d] = static_cast<double>(n) + 0.1 * d;
    }
  // From the first group's start and end, all of the second group, the middle and end of the
  // fourth.
  const std::vector<std::uint32_t> removed = {0, 1, 9, 10, 11, 12, 20, 21, 30, 37, 44};
  P.erase(removed, sizes);
  const std::set<std::uint32_t> gone(removed.begin(), removed.end());
  ASSERT_EQ(P.size(), n - removed.size());
  std::set<std::int64_t> ids;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const auto id = P.id[p];
    EXPECT_FALSE(gone.count(static_cast<std::uint32_t>(id))) << id;
    ids.insert(id);
    EXPECT_EQ(P.field("damage")[p], 0.5 * static_cast<double>(id));
    for (int d = 0; d < 3; ++d) EXPECT_EQ(P.position[3 * p + d], static_cast<double>(id) + 0.1 * d);
    if (p > 0) {
      EXPECT_LE(P.material[p - 1], P.material[p]) << "groups must stay contiguous and in order";
    }
  }
  EXPECT_EQ(ids.size(), P.size());
}

}  // namespace
}  // namespace hvi::mpm::test
