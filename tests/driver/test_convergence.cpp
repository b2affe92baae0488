// hvi convergence: the observed order and the Richardson extrapolation recover a known power law
// for any refinement ratio, refuse a ladder that does not converge monotonically, the ladder's
// cell sizes follow --ratio, and a level that fails says why on the console.
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cases/cli/convergence_command.hpp"

namespace fs = std::filesystem;
using hvi::driver::richardson;

namespace {

// q(h) = q* + C h^p sampled at h, h/r, h/r^2: the extrapolation is exact for this model, so only
// round-off separates it from q* (tolerance 1e-10 relative).
void expect_recovers(double q_star, double c, double p, double h, double r) {
  auto q = [&](double hk) { return q_star + c * std::pow(hk, p); };
  const auto e = richardson(q(h), q(h / r), q(h / (r * r)), r);
  EXPECT_NEAR(e.order, p, 1e-10) << "r = " << r;
  EXPECT_NEAR(e.value, q_star, 1e-10 * std::fabs(q_star)) << "r = " << r;
}

// `hvi convergence ARGS` with its console in `log`; the exit code (-1 if it did not exit normally).
int convergence(const std::string& args, const fs::path& log) {
  const std::string cmd =
      std::string(HVI_BINARY) + " convergence " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST(Convergence, RichardsonRecoversAPowerLawForAnyRatio) {
  expect_recovers(10.6e-3, 13.0, 1.0, 0.4e-3, 2.0);               // first order, halving
  expect_recovers(10.6e-3, 13.0, 1.0, 0.4e-3, std::sqrt(2.0));    // first order, sqrt(2) ladder
  expect_recovers(26.5e-3, -2.0e3, 2.0, 0.8e-3, std::sqrt(2.0));  // second order, from below
  expect_recovers(1.0, 0.5, 1.7, 0.3, 1.5);
}

TEST(Convergence, RichardsonRefusesALadderThatDoesNotConvergeMonotonically) {
  EXPECT_TRUE(std::isnan(richardson(1.0, 2.0, 1.5, 2.0).value));  // oscillates
  EXPECT_TRUE(std::isnan(richardson(1.0, 1.0, 1.0, 2.0).order));  // no change
  EXPECT_TRUE(std::isnan(richardson(1.0, 1.1, 1.3, 2.0).value));  // diverges: order < 0
}

TEST(Convergence, LadderCellSizesFollowTheRatio) {
  const fs::path out = fs::path(testing::TempDir()) / "hvi_convergence_ratio";
  fs::remove_all(out);
  const fs::path log = fs::path(testing::TempDir()) / "hvi_convergence_ratio.log";
  ASSERT_EQ(
      convergence(std::string(HVI_SOURCE_DIR) +
                      "/tests/driver/data/drift.toml --levels 2 --ratio 1.25 --threads 1 --out " +
                      out.string(),
                  log),
      0)
      << std::ifstream(log).rdbuf();
  // convergence.csv: level,cell_size,...; the scene's 0.5 mm, then 0.5 / 1.25 = 0.4 mm.
  std::ifstream csv(out / "convergence.csv");
  std::string line;
  std::getline(csv, line);
  std::set<std::string> cells;
  while (std::getline(csv, line)) {
    std::stringstream s(line);
    std::string level, cell;
    std::getline(s, level, ',');
    std::getline(s, cell, ',');
    cells.insert(level + "=" + cell);
  }
  EXPECT_EQ(cells, (std::set<std::string>{"h0=0.0005", "h1=0.0004"}));
  std::stringstream md;
  md << std::ifstream(out / "convergence.md").rdbuf();
  EXPECT_NE(md.str().find("--levels 2 --ratio 1.25"), std::string::npos) << md.str();
}

// A level that fails stops the ladder, and the console carries the run's own account of the failure
// and its warnings (two spheres colliding on linear shape functions with USL: see test_cli).
TEST(Convergence, AFailedLevelSaysWhyOnTheConsole) {
  const fs::path out = fs::path(testing::TempDir()) / "hvi_convergence_failed";
  fs::remove_all(out);
  const fs::path log = fs::path(testing::TempDir()) / "hvi_convergence_failed.log";
  ASSERT_EQ(
      convergence(std::string(HVI_SOURCE_DIR) +
                      "/tests/driver/data/small_spheres.toml --levels 2 --threads 1 --out " +
                      out.string() + " --set grid.shape_function=linear --set grid.scheme=usl",
                  log),
      3)
      << std::ifstream(log).rdbuf();
  std::stringstream console;
  console << std::ifstream(log).rdbuf();
  for (const char* part :
       {"hvi convergence: level h0 failed; see ", "  hvi: the run failed: step ",
        "non-positive volume", "  warning: material 'steel' names no equation of state"})
    EXPECT_NE(console.str().find(part), std::string::npos) << part << " in:\n" << console.str();
  EXPECT_FALSE(fs::exists(out / "h1"));  // the ladder stopped at its first level
}
