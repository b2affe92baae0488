// Hard cases stay numerically stable (cases/stability/, fast coarse versions here; the scenes'
// own resolution is the `long` version). Each run must finish with no NaN or non-positive volume
// (the solver stops with SolverError on either), keep kinetic + internal + dissipated + removed
// energy within a stated bound of the initial energy, and conserve momentum, including what left
// the grid, where no boundary acts.
#include <cmath>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>

#include "mpm/materials/hydro_material.hpp"
#include "tests/verification/scene_run.hpp"

namespace hvi {
namespace {

struct Balance {
  double energy_error;      // (E - E0) / E0
  double momentum_error;    // |p - p0| / |p0|, removed material included
  double mass_error;        // (m + m_removed - m0) / m0
  double momentum_error_z;  // |p_z - p_z0| / |p0|: along the impact axis only
};

Balance run_case(const std::string& file, const std::vector<std::string>& overrides,
                 double end_time, test::SceneRun** keep = nullptr) {
  static std::unique_ptr<test::SceneRun> last;
  last = std::make_unique<test::SceneRun>(file, overrides);
  test::SceneRun& run = *last;
  const mpm::EnergyReport e0 = run.solver->energy();
  EXPECT_NO_THROW(run.run_to(end_time));
  const mpm::EnergyReport e = run.solver->energy();
  double dp = 0, p0 = 0;
  for (int d = 0; d < 3; ++d) {
    dp += std::pow(e.momentum[d] + e.removed_momentum[d] - e0.momentum[d], 2);
    p0 += e0.momentum[d] * e0.momentum[d];
  }
  if (keep) *keep = last.get();
  const Balance b{
      e.total() / e0.total() - 1, std::sqrt(dp / p0), (e.mass + e.removed_mass) / e0.mass - 1,
      std::fabs(e.momentum[2] + e.removed_momentum[2] - e0.momentum[2]) / std::sqrt(p0)};
  std::printf("%s: energy %+.3f%%, momentum %.2e, mass %.2e, removed %lld particles (%.3g J)\n",
              file.c_str(), 100 * b.energy_error, b.momentum_error, b.mass_error,
              static_cast<long long>(run.solver->removed().particles), e.removed);
  return b;
}

// Momentum: the scatter, the nodal update and the FLIP gather conserve it to round-off; 1e-10 of
// the initial momentum leaves room for ~1e4 steps of 1e-15 relative errors.
constexpr double momentum_tolerance = 1e-10;

TEST(Stability, AluminiumOnAluminiumAt10kmPerSecond) {
  omp_set_num_threads(1);
  test::SceneRun* run = nullptr;
  const Balance b =
      run_case("stability/hypervelocity_10kms.toml", {"grid.cell_size=5e-4"}, 1.5e-6, &run);
  // Measured +3.9% at this resolution (+1.2% at the scene's 0.25 mm cells): MPM's grid
  // projection loses kinetic energy at strong shocks and the energy equation gains it back
  // through the viscosity, not exactly. 5% bounds it.
  EXPECT_LT(std::fabs(b.energy_error), 0.05);
  EXPECT_LT(b.momentum_error, momentum_tolerance);
  EXPECT_LT(std::fabs(b.mass_error), 1e-12);
  EXPECT_GT(run->solver->removed().particles, 100);  // debris left the grid and was accounted
}

TEST(Stability, ObliqueImpactAt60Degrees) {
  omp_set_num_threads(1);
  const Balance b = run_case("stability/oblique_60deg.toml", {"grid.cell_size=5e-4"}, 2e-6);
  EXPECT_LT(std::fabs(b.energy_error), 0.02);  // measured +0.3%
  EXPECT_LT(b.momentum_error, momentum_tolerance);
  EXPECT_LT(std::fabs(b.mass_error), 1e-12);
}

// The projectile far larger than a cell (6 cells in radius) and smaller than one (0.4 cell, 8
// points at 4 per cell per axis), at 4.5 km/s.
TEST(Stability, ProjectileLargerAndSmallerThanACell) {
  omp_set_num_threads(1);
  const std::vector<std::string> common = {"grid.cell_size=5e-4",
                                           "body.projectile.velocity=[0, 0, -4500]"};
  auto with = [&](std::vector<std::string> extra) {
    extra.insert(extra.begin(), common.begin(), common.end());
    return extra;
  };
  const Balance large = run_case(
      "stability/hypervelocity_10kms.toml",
      with({"body.projectile.sphere.radius=3e-3", "body.projectile.sphere.center=[0, 0, 3.25e-3]",
            "grid.upper=[6e-3, 6e-3, 7e-3]"}),
      1e-6);
  EXPECT_LT(std::fabs(large.energy_error), 0.03);  // measured +0.8%
  EXPECT_LT(large.momentum_error, momentum_tolerance);
  // A sub-cell projectile meets the plate through a few grid nodes: the grid compresses it
  // before FLIP decelerates it, and energy is created (measured +29% at cfl 0.5, +2.9% at 0.1,
  // +1.3% at 0.05: first order in dt). The scene warns about it and recommends cfl 0.05, with
  // which the balance holds within 2%; at the default it stays finite and bounded by 35%.
  const std::vector<std::string> small =
      with({"body.projectile.sphere.radius=2e-4", "body.projectile.sphere.center=[0, 0, 0.5e-3]",
            "body.projectile.particles_per_cell=4"});
  const auto scene = scene::load_scene(
      std::string(HVI_SOURCE_DIR) + "/cases/stability/hypervelocity_10kms.toml", small);
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("body 'projectile' is 0.8 cells across"), std::string::npos)
      << scene.warnings[0];
  const Balance coarse_dt = run_case("stability/hypervelocity_10kms.toml", small, 1e-6);
  EXPECT_LT(std::fabs(coarse_dt.energy_error), 0.35);
  EXPECT_LT(coarse_dt.momentum_error, momentum_tolerance);
  auto refined = small;
  refined.push_back("grid.cfl=0.05");
  const Balance fine_dt = run_case("stability/hypervelocity_10kms.toml", refined, 1e-6);
  EXPECT_LT(std::fabs(fine_dt.energy_error), 0.02);
  EXPECT_LT(fine_dt.momentum_error, momentum_tolerance);
}

// A plate one point thick at the coarsest grid (one point per cell, one cell thick).
TEST(Stability, PlateOnePointThick) {
  omp_set_num_threads(1);
  const Balance b =
      run_case("stability/hypervelocity_10kms.toml",
               {"grid.cell_size=5e-4", "body.projectile.velocity=[0, 0, -4500]",
                "body.plate.particles_per_cell=1", "body.plate.box.lower=[-5e-3, -5e-3, -5e-4]"},
               1e-6);
  EXPECT_LT(std::fabs(b.energy_error), 0.03);
  EXPECT_LT(b.momentum_error, momentum_tolerance);
}

// Honeycomb walls much thinner than a cell: 0.05 mm walls in 1 mm cells become one layer of
// points on each mid-surface. Quarter model: the symmetry planes take x and y momentum, so only
// the momentum along the impact axis is conserved.
TEST(Stability, HoneycombWallsMuchThinnerThanACell) {
  omp_set_num_threads(1);
  test::SceneRun* run = nullptr;
  const Balance b = run_case("stability/honeycomb_thin_walls.toml", {}, 4e-6, &run);
  EXPECT_LT(std::fabs(b.energy_error), 0.03);  // measured +1.2%
  EXPECT_LT(std::fabs(b.mass_error), 1e-12);
  EXPECT_LT(b.momentum_error_z, momentum_tolerance);
  EXPECT_GT(run->solver->removed().particles, 0);  // edge walls pushed out of the grid, accounted
}

// The 10 km/s shock, the 60-degree impact and the walls much thinner than a cell again, with one
// scene setting added; each keeps the bounds it has without it.
void hard_cases_with(const std::string& setting) {
  omp_set_num_threads(1);
  const Balance fast =
      run_case("stability/hypervelocity_10kms.toml", {"grid.cell_size=5e-4", setting}, 1.5e-6);
  EXPECT_LT(std::fabs(fast.energy_error), 0.05);
  EXPECT_LT(fast.momentum_error, momentum_tolerance);
  const Balance oblique =
      run_case("stability/oblique_60deg.toml", {"grid.cell_size=5e-4", setting}, 2e-6);
  EXPECT_LT(std::fabs(oblique.energy_error), 0.02);
  EXPECT_LT(oblique.momentum_error, momentum_tolerance);
  const Balance walls = run_case("stability/honeycomb_thin_walls.toml", {setting}, 4e-6);
  EXPECT_LT(std::fabs(walls.energy_error), 0.03);
  EXPECT_LT(walls.momentum_error_z, momentum_tolerance);
}

// The node-averaged dilatation (grid.dilatation = "node-average"): momentum stays exact (the
// averages move no momentum: they change the stress and the dilatation, not the transfers).
// Measured: energy +2.16%, +0.30% and +0.67% (own dilatation: +3.88%, +0.41%, +1.30%).
TEST(Stability, NodeAveragedDilatationInTheHardCases) {
  hard_cases_with("grid.dilatation=node-average");
}

// Contact ([contact], the projectile on a velocity field of its own; in the 60-degree impact it
// slides along the plate). Frictionless: the correction moves momentum between the fields of a
// node and nothing else. Measured: energy +2.88%, +0.23% and -2.65% (one field: +3.88%, +0.41%,
// +1.30%); the thin walls lose what the nodal corrections take where the projectile crushes them.
TEST(Stability, ContactInTheHardCases) {
  hard_cases_with("contact.bodies=[\"projectile\"]");
}

// Erosion keeps the books: the thin-wall case with every point of both materials eroded below
// V/V0 = 0.8 (far above the 0.5 a scene would use, so that 474 points erode in 4 us) keeps mass
// exact, axial momentum to round-off, and energy as well as without erosion (+1.3% then). Measured
// -0.4%; before the eroding step's unpaid work was taken out, +4.6%.
TEST(Stability, ErosionKeepsMassMomentumAndEnergy) {
  omp_set_num_threads(1);
  test::SceneRun* run = nullptr;
  std::vector<std::string> erode;
  for (const char* m : {"Al6061", "Al5052"}) {
    erode.push_back(fmt::format("material.{}.erosion=compression", m));
    erode.push_back(fmt::format("material.{}.compression_erosion.min_volume_ratio=0.8", m));
  }
  const Balance b = run_case("stability/honeycomb_thin_walls.toml", erode, 4e-6, &run);
  EXPECT_LT(std::fabs(b.energy_error), 0.02);
  EXPECT_LT(std::fabs(b.mass_error), 1e-12);
  EXPECT_LT(b.momentum_error_z, momentum_tolerance);
  const auto& P = run->particles();
  const auto& state = P.field("failed");
  int eroded = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (state[p] != mpm::failure_state::eroded) continue;
    ++eroded;
    // An eroded point carries no stress, and its volume stays where erosion froze it (< 0.8 V0).
    for (int c = 0; c < 6; ++c) ASSERT_EQ(P.stress[6 * p + c], 0.0);
    ASSERT_LT(P.volume[p], 0.8 * P.volume0[p]);
  }
  EXPECT_GT(eroded, 100);
}

// Spall: the release waves meet inside the target, the tension reaches sigma_max and the target
// fails in a layer; the spall layer flies off faster than the rest of the target.
TEST(Stability, SpallOpensAGapWithoutDiverging) {
  omp_set_num_threads(1);
  test::SceneRun* run = nullptr;
  const Balance b = run_case("stability/spall.toml", {}, 2e-6, &run);
  EXPECT_LT(std::fabs(b.energy_error), 0.02);  // measured +0.5%
  EXPECT_LT(b.momentum_error, momentum_tolerance);
  const auto& P = run->particles();
  const auto& failed = P.field("failed");
  int failures = 0;
  double v_rear = 0, v_middle = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    failures += failed[p] > 0;
    const double x0 = P.position[3 * p];  // current position
    if (x0 > 4.8e-3) v_rear = std::max(v_rear, P.velocity[3 * p]);
    if (x0 > 1.0e-3 && x0 < 2.0e-3) v_middle = std::max(v_middle, P.velocity[3 * p]);
  }
  EXPECT_GT(failures, 10);
  EXPECT_GT(v_rear - v_middle, 300.0);  // measured: ~930 m/s against ~15 m/s
}

}  // namespace
}  // namespace hvi
