// The hvi command line end to end with a hybrid (a scene with a [far_field]): its balance holds
// across the coupling, its output is byte-identical for 1 and 2 threads and on resume, with J2,
// rate-dependent, finite-strain and failing layers, and with a zone that grows.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_hvi.hpp"
#include "tests/support/sanitizers.hpp"

namespace fs = std::filesystem;

namespace {

using namespace hvi::test;  // the run helpers of tests/support/run_hvi.hpp

const std::string hvi = HVI_BINARY;
const std::string hybrid = std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_hybrid.toml";
// J2 facesheets in the far field: the panel's aluminium made Al6061 with Johnson-Cook strength,
// so that they have a hardening curve.
const std::string j2 =
    " --set far_field.plasticity=j2 --set material.aluminium.library=Al6061"
    " --set material.aluminium.strength=johnson-cook";

// The small hybrid: the far field's momentum and energy enter the balance. No boundary acts
// along z (the symmetry planes are x = 0 and y = 0), so the z momentum of particles plus far
// field is conserved exactly; the energy is conserved to what the same impact on an all-MPM
// panel conserves (+0.12%) plus the interface's share: the bound 0.5% is met with -0.29% with the
// default 8 core elements (-0.13% with 4; the earlier coupling, whose far field moved with its own
// FLIP velocity, gained 4.5%).
TEST(Cli, HybridBalancesMomentumAndEnergyAndWritesItsFarField) {
  const fs::path out = scratch("hybrid");
  ASSERT_EQ(run("run " + hybrid + " --out " + out.string() + " --threads 2"), 0);
  std::string header;
  const auto rows = csv_rows(out / "energy.csv", &header);
  EXPECT_NE(header.find(",coupled_kinetic,coupled_strain"), std::string::npos) << header;
  ASSERT_GT(rows.size(), 10u);
  const double pz0 = rows.front()[10], pz1 = rows.back()[10];  // momentum_z
  EXPECT_NEAR(pz1 / pz0, 1.0, 1e-12);
  const double E0 = rows.front()[7], E1 = rows.back()[7];  // total
  EXPECT_LT(std::abs(E1 / E0 - 1.0), 0.005) << "energy balance " << E1 / E0 - 1.0;
  EXPECT_GT(rows.back()[13] + rows.back()[14], 0.1 * E0);  // the far field took a share
  const std::string pvd = read(out / "far_field.pvd");
  int entries = 0;
  for (auto at = pvd.find("<DataSet"); at != std::string::npos; at = pvd.find("<DataSet", at + 1))
    ++entries;
  EXPECT_EQ(entries, 5);  // t = 0, 1, 2, 3, 4 us
  EXPECT_TRUE(fs::exists(out / "far_field" / "far_field_000000.vtu"));
  EXPECT_NE(read(out / "summary.toml").find("far_field_nodes = 2420"), std::string::npos);
}

TEST(Cli, HybridOutputIsBitwiseIdenticalForOneAndTwoThreadsAndOnResume) {
  HVI_SKIP_UNDER_SANITIZERS(
      "72 s there; a hybrid runs in Cli.HybridBalancesMomentumAndEnergyAndWritesItsFarField");
  const fs::path two = scratch("hybrid2"), one = scratch("hybrid1"),
                 parts = scratch("hybrid_parts");
  ASSERT_EQ(run("run " + hybrid + " --out " + two.string() + " --threads 2"), 0);
  ASSERT_EQ(run("run " + hybrid + " --out " + one.string() + " --threads 1"), 0);
  ASSERT_EQ(
      run("run " + hybrid + " --out " + parts.string() + " --threads 2 --set run.max_steps=37"), 0);
  ASSERT_EQ(run("run --resume " + parts.string() + " --threads 1 --set run.max_steps=0"), 0);
  for (const fs::path& other : {one, parts}) {
    expect_same_output(two, other);
    for (const char* f : {"probes.csv", "far_field.pvd"})
      EXPECT_TRUE(read(two / f) == read(other / f)) << f << " differs in " << other;
    int files = 0;
    for (const auto& entry : fs::directory_iterator(two / "far_field")) {
      EXPECT_TRUE(read(entry.path()) == read(other / "far_field" / entry.path().filename()))
          << entry.path().filename() << " differs in " << other;
      ++files;
    }
    EXPECT_EQ(files, 10);  // a VTU file and a node file per snapshot
  }
}

// The small hybrid with `sets` run on 2 threads into scratch(name), on 1 thread, and stopped at
// step `stop` (37 unless said) then resumed on 1 thread: all three write the same bytes (snapshots,
// energy.csv, the far field's VTU files), and the energy balance holds to `bound` (the 0.5% of the
// elastic hybrid above unless said). Returns the two-thread run's directory.
fs::path expect_hybrid_balances_and_repeats_bitwise(const std::string& sets,
                                                    const std::string& name, double bound = 0.005,
                                                    int stop = 37) {
  const fs::path two = scratch(name), one = scratch(name + "_1"), parts = scratch(name + "_parts");
  EXPECT_EQ(run("run " + hybrid + " --out " + two.string() + " --threads 2" + sets), 0);
  EXPECT_EQ(run("run " + hybrid + " --out " + one.string() + " --threads 1" + sets), 0);
  EXPECT_EQ(run("run " + hybrid + " --out " + parts.string() +
                " --threads 2 --set run.max_steps=" + std::to_string(stop) + sets),
            0);
  EXPECT_EQ(run("run --resume " + parts.string() + " --threads 1 --set run.max_steps=0"), 0);
  for (const fs::path& other : {one, parts}) {
    expect_same_output(two, other);
    for (const auto& entry : fs::directory_iterator(two / "far_field"))
      EXPECT_TRUE(read(entry.path()) == read(other / "far_field" / entry.path().filename()))
          << entry.path().filename() << " differs in " << other;
  }
  const auto rows = csv_rows(two / "energy.csv");
  EXPECT_FALSE(rows.empty());
  if (!rows.empty()) {
    EXPECT_LT(std::abs(rows.back()[7] / rows.front()[7] - 1.0), bound)
        << "energy balance " << rows.back()[7] / rows.front()[7] - 1.0;
  }
  return two;
}

// The same hybrid with J2 facesheets in the far field (far_field.plasticity = "j2"; the panel's
// aluminium made Al6061 with Johnson-Cook strength so they have a hardening curve): the far field
// yields near the zone, its plastic work enters the balance (the same 0.5% bound as above) and
// its plastic state the checkpoints, so a resumed run and a one-thread run repeat the two-thread
// run byte for byte.
TEST(Cli, HybridWithPlasticFacesheetsBalancesEnergyAndResumesBitwise) {
  HVI_SKIP_UNDER_SANITIZERS("72 s there; the J2 facesheets run in tests/fem");
  const fs::path two = expect_hybrid_balances_and_repeats_bitwise(j2, "hybrid_j2");
  const auto rows = csv_rows(two / "energy.csv");
  ASSERT_FALSE(rows.empty());
  const double E0 = rows.front()[7];
  const double alpha = summary_number(two, "far_field_max_plastic_strain");
  const double work = summary_number(two, "far_field_plastic_work");
  EXPECT_GT(alpha, 1e-3);            // the far field did yield...
  EXPECT_GT(work, 1e-4 * E0);        // ...and took plastic work
  EXPECT_LT(work, rows.back()[14]);  // which coupled_strain (elastic + plastic) holds
  EXPECT_NE(read(two / "far_field" / "far_field_000000.vtu").find("equivalent_plastic_strain"),
            std::string::npos);
}

// The same J2 hybrid with the facesheets' yield at their strain rate (far_field.strain_rate =
// "johnson-cook"; Al6061's C = 0.015): the strain each quadrature point had at the last step is
// state, in the checkpoints, so a resumed run and a one-thread run repeat the two-thread run byte
// for byte; the balance holds to the same 0.5%; and the far field, its yield raised by the rate
// factor (1.07-1.14 at 1e2-1e4 /s), yields less than at the reference rate.
TEST(Cli, HybridWithRateDependentFacesheetsBalancesEnergyAndResumesBitwise) {
  HVI_SKIP_UNDER_SANITIZERS("101 s there; the rate term runs in tests/fem");
  const fs::path rate = expect_hybrid_balances_and_repeats_bitwise(
      j2 + " --set far_field.strain_rate=johnson-cook", "hybrid_j2_rate");
  const fs::path reference = scratch("hybrid_j2_reference");
  ASSERT_EQ(run("run " + hybrid + " --out " + reference.string() + " --threads 2" + j2), 0);
  const double alpha = summary_number(rate, "far_field_max_plastic_strain");
  const double alpha_reference = summary_number(reference, "far_field_max_plastic_strain");
  EXPECT_GT(alpha, 1e-4);             // it yields...
  EXPECT_LT(alpha, alpha_reference);  // ...less than at the reference rate
  EXPECT_LT(summary_number(rate, "far_field_plastic_work"),
            summary_number(reference, "far_field_plastic_work"));
}

// The same J2 hybrid with finite-strain kinematics in the far field (far_field.kinematics =
// "finite"): the energy balance holds to the same 0.5% (Saint Venant-Kirchhoff's strain energy is
// exact, so the far field adds no error of its own), the momentum exactly, and one thread and a
// resumed run repeat two threads byte for byte (the far field's step follows the stretch of the
// last force evaluation; the next step is chosen before a checkpoint is written and kept in it).
TEST(Cli, HybridWithFiniteStrainBalancesEnergyAndResumesBitwise) {
  HVI_SKIP_UNDER_SANITIZERS("128 s there; finite strain runs in tests/fem");
  // safety 0.3: the far field's step, which follows its stretch, sets the pace at every step.
  const std::string finite = " --set far_field.kinematics=finite --set far_field.safety=0.3" + j2;
  const fs::path two = expect_hybrid_balances_and_repeats_bitwise(finite, "hybrid_finite");
  const auto rows = csv_rows(two / "energy.csv");
  ASSERT_FALSE(rows.empty());
  EXPECT_NEAR(rows.back()[10] / rows.front()[10], 1.0, 1e-12);  // momentum_z
  EXPECT_GT(summary_number(two, "far_field_max_plastic_strain"), 1e-3);
}

// The same hybrid with a failing core (far_field.core = "failing") and failing facesheets
// (far_field.plasticity = "failing"), the ball at 2 km/s so that the far field's core tears beside
// the zone: its damage is in the checkpoints, so a resumed run and a one-thread run repeat the
// two-thread run byte for byte. The panel is Al5052 with Johnson-Cook strength and damage (the
// core's walls need both), which fails in the MPM zone too: this coarse scene then balances to
// about +2% whatever the core (elastic +1.95%, yielding +2.21%), so the bound is 3%, and the
// failing core's own share is checked against the yielding core's: within 0.1% (measured 0.01%;
// booking a torn point's elastic predictor each step, a force it never exerts, added 0.5%).
TEST(Cli, HybridWithFailingCoreBalancesEnergyAndResumesBitwise) {
  HVI_SKIP_UNDER_SANITIZERS("104 s there; the failing core runs in tests/fem");
  const std::string al5052 =
      " --set far_field.plasticity=failing --set material.aluminium.library=Al5052"
      " --set material.aluminium.strength=johnson-cook --set material.aluminium.damage=johnson-cook"
      " --set body.ball.velocity=[0,0,-2000]";
  const fs::path two = expect_hybrid_balances_and_repeats_bitwise(
      al5052 + " --set far_field.core=failing", "hybrid_failing", 0.03);
  EXPECT_GT(summary_number(two, "far_field_core_failed_volume"), 1e-9);  // 1 mm^3: the core tore
  EXPECT_GT(summary_number(two, "far_field_facesheet_failed_volume"), 0.0);  // and a facesheet
  EXPECT_NE(read(two / "far_field" / "far_field_000000.vtu").find("core_damage"),
            std::string::npos);
  EXPECT_NE(read(two / "far_field" / "far_field_000000.vtu").find("facesheet_damage"),
            std::string::npos);
  const fs::path yielding = scratch("hybrid_yielding");
  ASSERT_EQ(run("run " + hybrid + " --out " + yielding.string() + " --threads 2" + al5052 +
                " --set far_field.core=yielding"),
            0);
  const auto a = csv_rows(two / "energy.csv"), b = csv_rows(yielding / "energy.csv");
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(b.empty());
  EXPECT_NEAR(a.back()[7] / a.front()[7], b.back()[7] / b.front()[7], 1e-3);
}

// The failing hybrid above with a zone that grows ([far_field.zone.grow]) from 3 mm up to 6 mm
// by 1 mm steps where the panel's damage comes within 1 mm of its edge, and its displacement probe
// moved to x = 5 mm, on a far-field node the zone grows over. The zone first grows at step 41,
// where the resumed run stops, so its checkpoint holds the grown zone's band and points: a
// one-thread and a resumed run repeat the two-thread run byte for byte (snapshots, energy,
// far-field VTU files and probes). The balance holds to the failing hybrid's 3% (the energy the
// take-overs do not carry over is booked, not lost). The zone grows to [0, 6] x [0, 6] mm, along
// x at step 133, where the far field's own failing layers have torn just beyond its edge (the
// points' damage, tested where they started, stopped short of it), and in the last step that tear
// reaches past the 6 mm limit (one step held at the limit). The probe's
// reading goes on without a jump where its node is taken over (step 79): its change across that
// row (5 steps) is below 5% of the reading (measured 2.4%, 0.080 of 3.40 um, as the probe of the
// same run with its zone held at 4 mm, short of the probe, moves by 0.097 um there; when the probe
// took the points' own mean displacement it jumped by a third of its reading, 2.8 of 8.5 um).
// hvi measure reads the points born after t = 0.
TEST(Cli, HybridWithAGrowingZoneRepeatsBitwiseAndItsProbeGoesOn) {
  HVI_SKIP_UNDER_SANITIZERS("370 s there; the take-over runs in ZoneGrowth.*");
  const std::string growing =
      " --set far_field.plasticity=failing --set far_field.core=failing --set "
      "material.aluminium.library=Al5052"
      " --set material.aluminium.strength=johnson-cook --set material.aluminium.damage=johnson-cook"
      " --set body.ball.velocity=[0,0,-2000] --set 'grid.upper=[\"7 mm\",\"7 mm\",\"3 mm\"]'"
      " --set 'far_field.zone.grow.lower=[\"0 mm\",\"0 mm\"]' --set "
      "'far_field.zone.grow.upper=[\"6 mm\",\"6 mm\"]'"
      " --set 'far_field.zone.grow.step=1 mm' --set 'far_field.zone.grow.margin=1 mm'"
      " --set 'measure.rear_deflection.point=[\"5 mm\",\"0 mm\",\"-4 mm\"]'";
  const fs::path two =
      expect_hybrid_balances_and_repeats_bitwise(growing, "hybrid_growing", 0.03, 41);
  for (const char* other : {"hybrid_growing_1", "hybrid_growing_parts"})
    EXPECT_TRUE(read(two / "probes.csv") == read(fs::path(testing::TempDir()) /
                                                 ("hvi_cli_" + std::string(other)) / "probes.csv"))
        << other;
  EXPECT_EQ(summary_number(two, "far_field_elements_taken_over"),
            1080);  // 27 columns of 40 elements
  EXPECT_EQ(summary_number(two, "mpm_zone_limit_reached_steps"),
            1);  // the far field's tear, at the end
  EXPECT_NE(read(two / "summary.toml")
                .find("mpm_zone = [ 0.0, 0.0, 0.0060000000000000001, 0.0060000000000000001 ]"),
            std::string::npos);
  const auto probe = csv_rows(two / "probes.csv");  // step, time, rear_deflection every 5 steps
  std::size_t taken = 0;  // the first row after the zone took the probe's node (step 79)
  while (taken < probe.size() && probe[taken][0] < 79) ++taken;
  ASSERT_LT(taken + 1, probe.size());
  ASSERT_GE(taken, 1u);
  const double across = probe[taken][2] - probe[taken - 1][2];
  EXPECT_LT(std::abs(across), 0.05 * std::abs(probe[taken - 1][2]))
      << across << " from " << probe[taken - 1][2];
  EXPECT_EQ(run("measure " + two.string()), 0);
  EXPECT_NE(read(two / "measurements.json").find("\"perforated\" : true"), std::string::npos);
  // hvi probe at the probe's point: the node while the far field holds it (at t = 0 the run's
  // own reading, exactly), then the points that took it over, by their undeformed positions.
  std::string csv, err;
  ASSERT_EQ(run("probe " + two.string() + " --point \"5 mm,0 mm,-4 mm\"", &err, &csv), 0) << err;
  EXPECT_NE(err.find("(from t = "), std::string::npos) << err;
  EXPECT_NE(err.find("the zone grown over it)"), std::string::npos) << err;
  const fs::path probe_csv = two / "probe_history.csv";
  std::ofstream(probe_csv) << csv;
  const auto history = csv_rows(probe_csv);
  ASSERT_EQ(history.size(), 5u);  // t = 0, 1, 2, 3, 4 us
  EXPECT_EQ(history.front()[1], probe.front()[2]);
  for (const auto& row : history) EXPECT_TRUE(std::isfinite(row[1])) << "t = " << row[0];
}

// The same growing hybrid with its limit at 5 mm: the damage reaches the zone's edge there at
// step 122 (y = 5 mm; the points' damage) and 133 (x = 5 mm; the far field's own tear beyond it),
// and the run says so, once per side, and counts the steps it did in the summary and its closing
// lines (13 of the 134, from 3.66 us to the end). A run stopped at step 118 and resumed reports the
// same: the record is in the checkpoint.
TEST(Cli, AGrowingZoneHeldAtItsLimitByTheDamageSaysSo) {
  HVI_SKIP_UNDER_SANITIZERS("172 s there; the take-over runs in ZoneGrowth.*");
  const std::string growing =
      " --set far_field.plasticity=failing --set far_field.core=failing --set "
      "material.aluminium.library=Al5052"
      " --set material.aluminium.strength=johnson-cook --set material.aluminium.damage=johnson-cook"
      " --set body.ball.velocity=[0,0,-2000] --set 'grid.upper=[\"7 mm\",\"7 mm\",\"3 mm\"]'"
      " --set 'far_field.zone.grow.lower=[\"0 mm\",\"0 mm\"]' --set "
      "'far_field.zone.grow.upper=[\"5 mm\",\"5 mm\"]'"
      " --set 'far_field.zone.grow.step=1 mm' --set 'far_field.zone.grow.margin=1 mm'";
  const fs::path whole = scratch("hybrid_limit"), parts = scratch("hybrid_limit_parts");
  const std::string log = (fs::path(testing::TempDir()) / "hvi_cli_hybrid_limit.log").string();
  const std::string command = hvi + " run " + hybrid + " --out " + whole.string() + " --threads 2" +
                              growing + " > " + log + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string said = read(log);
  EXPECT_NE(said.find("step 122, t = 3.65608e-06 s: the panel's damage reached the MPM zone's edge "
                      "at y = 5 mm, its limit"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("step 133, t = 3.99986e-06 s: the panel's damage reached the MPM zone's edge "
                      "at x = 5 mm, its limit"),
            std::string::npos)
      << said;
  EXPECT_NE(said.find("MPM zone: [0, 5] x [0, 5] mm, 640 far-field elements taken over; the damage "
                      "held it at its limit "
                      "(x = 5 mm, y = 5 mm) at 13 steps"),
            std::string::npos)
      << said;
  EXPECT_EQ(summary_number(whole, "mpm_zone_limit_reached_steps"), 13);
  EXPECT_NEAR(summary_number(whole, "mpm_zone_limit_reached_first_time"), 3.65608e-6, 1e-11);
  EXPECT_NEAR(summary_number(whole, "mpm_zone_limit_reached_last_time"), 4e-6, 1e-15);
  ASSERT_EQ(run("run " + hybrid + " --out " + parts.string() +
                " --threads 2 --set run.max_steps=118" + growing),
            0);
  ASSERT_EQ(run("run --resume " + parts.string() + " --threads 1 --set run.max_steps=0"), 0);
  for (const char* key : {"mpm_zone_limit_reached_steps", "mpm_zone_limit_reached_first_time",
                          "mpm_zone_limit_reached_last_time"})
    EXPECT_EQ(summary_number(parts, key), summary_number(whole, key)) << key;
}

}  // namespace
