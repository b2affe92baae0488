// hvi ballistic-limit end to end on a small panel (tests/driver/data/small_panel_limit.toml):
// the first trial is the SRL equation's diameter, every trial's outcome is its run's measured
// rear sheet, the limit is the midpoint of the tightest bracket the trials give, and the command
// run again runs nothing new. Also hvi validate's errors on bad input.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "analysis/ballistic_limit_equation.hpp"
#include "analysis/table.hpp"
#include "cases/cli/rear_outcome.hpp"
#include "tests/support/run_hvi.hpp"
#include "tests/support/sanitizers.hpp"

namespace {

namespace fs = std::filesystem;
constexpr double mm = 1e-3;
const std::string scene = std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_panel_limit.toml";

TEST(BallisticLimitRun, TrialsBracketTheLimitAndResume) {
  const fs::path out = hvi::test::scratch("ballistic_limit");
  const std::string args = "ballistic-limit " + scene + " --speeds 3km/s --out " + out.string() +
                           " --tolerance 0.2 --max-trials 6 --threads 1";
  std::string err, said;
  ASSERT_EQ(hvi::test::run(args, &err, &said), 0) << err << said;

  const hvi::analysis::Table trials = hvi::analysis::read_csv(out / "trials.csv");
  ASSERT_GE(trials.rows.size(), 2u);
  // The first trial: the SRL diameter of the scene's panel (0.4 mm sheets, 2.8 mm apart, Al6061:
  // its Johnson-Cook A as the rear yield, 2770 kg/m^3), rounded to a micrometre.
  const hvi::analysis::SandwichPanel panel{0.4 * mm, 0.4 * mm, 2.8 * mm, 265e6, 2770};
  const double srl = hvi::analysis::srl_critical_diameter(panel, 2770, 3000).diameter;
  EXPECT_NEAR(trials.number(0, trials.column("diameter_mm")) * mm, srl, 0.5e-6);
  double stopped = 0, perforated = 1e9;
  for (std::size_t k = 0; k < trials.rows.size(); ++k) {
    const std::string run = trials.rows[k][trials.column("run")];
    const auto measured = hvi::driver::read_rear_outcome(out / "trials" / run);
    ASSERT_TRUE(measured) << run;
    const bool p = trials.rows[k][trials.column("outcome")] == "P";
    EXPECT_EQ(p, measured->perforated(hvi::driver::Criterion::either)) << run;
    const double d = trials.number(k, trials.column("diameter_mm"));
    if (p)
      perforated = std::min(perforated, d);
    else
      stopped = std::max(stopped, d);
  }
  const hvi::analysis::Table limits = hvi::analysis::read_csv(out / "ballistic_limit.csv");
  ASSERT_EQ(limits.rows.size(), 1u);
  EXPECT_EQ(limits.rows[0][limits.column("status")], "converged");
  EXPECT_DOUBLE_EQ(limits.number(0, limits.column("stopped_mm")), stopped);
  EXPECT_DOUBLE_EQ(limits.number(0, limits.column("perforated_mm")), perforated);
  EXPECT_LE(perforated / stopped - 1, 0.2 + 1e-9);
  EXPECT_NEAR(limits.number(0, limits.column("critical_diameter_mm")), 0.5 * (stopped + perforated),
              1e-6);
  EXPECT_TRUE(fs::exists(out / "ballistic_limit.png"));

  // Again: every trial is done, none runs.
  ASSERT_EQ(hvi::test::run(args, &err, &said), 0) << err << said;
  EXPECT_EQ(said.find("running"), std::string::npos) << said;
  EXPECT_EQ(hvi::analysis::read_csv(out / "trials.csv").rows.size(), trials.rows.size());
}

// Under mpirun the searches of two speeds share each round's trials among 2 ranks: the trials,
// their outcomes and the limits are the one-rank command's, and rank 1 ran some of them.
TEST(BallisticLimitRun, TwoRanksShareEachRoundsTrials) {
  const std::string mpirun = HVI_MPIEXEC;
  HVI_SKIP_WITHOUT_MPIRUN(mpirun);
  const fs::path one = hvi::test::scratch("ballistic_limit_one"),
                 two = hvi::test::scratch("ballistic_limit_two");
  const fs::path log = hvi::test::scratch("ballistic_limit_two.log");
  const std::string args = "ballistic-limit " + scene +
                           " --speeds 3,4km/s --tolerance 0.3 --max-trials 4 --threads 1"
                           " --parallel-searches 2 --out ";
  ASSERT_EQ(hvi::test::run_logged(args + one.string(), log), 0) << hvi::test::read(log);
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " +
                              mpirun + " --oversubscribe -np 2 " + HVI_BINARY + " " + args +
                              two.string() + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << hvi::test::read(log);
  const std::string console = hvi::test::read(log);
  EXPECT_NE(console.find("shared among 2 ranks"), std::string::npos) << console;
  EXPECT_NE(console.find("(rank 1)"), std::string::npos) << console;
  EXPECT_EQ(hvi::test::read(one / "trials.csv"), hvi::test::read(two / "trials.csv"));
  const auto a = hvi::analysis::read_csv(one / "ballistic_limit.csv"),
             b = hvi::analysis::read_csv(two / "ballistic_limit.csv");
  ASSERT_EQ(a.rows.size(), 2u);
  ASSERT_EQ(b.rows.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k)
    for (const char* c : {"speed_km_s", "critical_diameter_mm", "stopped_mm", "perforated_mm",
                          "trials", "status", "srl_critical_diameter_mm"})
      EXPECT_EQ(a.rows[k][a.column(c)], b.rows[k][b.column(c)]) << c;
}

TEST(BallisticLimitRun, BadOptionsAreRefusedBeforeAnyRun) {
  const fs::path out = hvi::test::scratch("ballistic_limit_bad");
  std::string err;
  EXPECT_EQ(
      hvi::test::run("ballistic-limit " + scene + " --speeds 2,3 --out " + out.string(), &err), 2);
  EXPECT_NE(err.find("give the speeds a unit"), std::string::npos) << err;
  EXPECT_EQ(hvi::test::run("ballistic-limit " + scene +
                               " --speeds 3km/s --projectile bullet --out " + out.string(),
                           &err),
            2);
  EXPECT_NE(err.find("no sphere body of that name"), std::string::npos) << err;
  EXPECT_EQ(hvi::test::run("ballistic-limit " + scene +
                               " --speeds 3km/s --start-from guess --out " + out.string(),
                           &err),
            2);
  EXPECT_NE(err.find("--start-from guess: expected neighbour or srl"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out / "trials"));
}

TEST(ValidateRun, AnUnknownShotIsRefused) {
  const fs::path out = hvi::test::scratch("validate_bad");
  std::string err;
  EXPECT_EQ(
      hvi::test::run("validate " + std::string(HVI_SOURCE_DIR) +
                         "/cases/experiments/hcsp_shots.csv --only 9-999 --out " + out.string(),
                     &err),
      2);
  EXPECT_NE(err.find("--only 9-999: no such shot"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
