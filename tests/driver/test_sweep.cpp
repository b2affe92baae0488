// hvi sweep end to end: a study file expands to the product of its axes plus its listed runs,
// every run lands in sweep.csv with its measures, a second call skips what is done, and a bad
// level stops the sweep before anything runs.
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "cases/cli/sweep_command.hpp"
#include "cases/scene/scene.hpp"
#include "tests/support/run_hvi.hpp"
#include "tests/support/sanitizers.hpp"

namespace fs = std::filesystem;

namespace {

const std::string hvi = HVI_BINARY;
const std::string data = std::string(HVI_SOURCE_DIR) + "/tests/driver/data/";

using hvi::test::read;
using hvi::test::run_logged;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) out.push_back(cell);
  return out;
}

// sweep.csv as run name -> column -> cell.
std::map<std::string, std::map<std::string, std::string>> table(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);
  const auto header = split(line);
  std::map<std::string, std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const auto cells = split(line);
    for (std::size_t k = 0; k < header.size() && k < cells.size(); ++k)
      rows[cells[0]][header[k]] = cells[k];
  }
  return rows;
}

TEST(Sweep, StudyExpandsToTheProductOfItsAxesAndItsRuns) {
  const hvi::driver::Study s =
      hvi::driver::load_study(data + "drift_study.toml", {"grid.cell_size=1 mm"});
  ASSERT_EQ(s.runs.size(), 5u);
  EXPECT_EQ(s.runs[0].name, "v100_r1");  // the first axis varies slowest
  EXPECT_EQ(s.runs[1].name, "v100_r15");
  EXPECT_EQ(s.runs[3].name, "v200_r15");
  EXPECT_EQ(s.runs[4].name, "still");
  // The study's overrides, the level's, then the command line's (the later one wins).
  const std::vector<std::string> expected{"run.end_time=2 us", "body.ball.velocity=[200, 0, 0]",
                                          "body.ball.sphere.radius=1.5 mm", "grid.cell_size=1 mm"};
  EXPECT_EQ(s.runs[3].overrides, expected);
  EXPECT_EQ(s.runs[3].labels.size(), 2u);
  EXPECT_EQ(s.runs[3].labels[1].first, "size");
  EXPECT_EQ(s.runs[3].labels[1].second, "r15");
}

TEST(Sweep, TheCommandLineOverridesARunsOwnSetButMayNotFixAnAxis) {
  // A [[run]]'s own value gives way to the command line's: the paper's study, whose runs each set
  // their model area, cut to a quarter model.
  const std::string quarter = R"(grid.lower=["0 mm", "0 mm", "-25 mm"])";
  const hvi::driver::Study s = hvi::driver::load_study(
      std::string(HVI_SOURCE_DIR) + "/cases/paper/study/study.toml", {quarter});
  ASSERT_EQ(s.runs.size(), 25u);
  for (const auto& run : s.runs) {
    ASSERT_FALSE(run.overrides.empty());
    EXPECT_EQ(run.overrides.back(), quarter) << run.name;
    EXPECT_NE(std::find_if(run.overrides.begin(), run.overrides.end(),
                           [](const std::string& o) { return o.starts_with("grid.lower="); }),
              run.overrides.end() - 1)
        << run.name << " sets its own grid.lower, which the command line's follows";
  }
  // ...but fixing what an axis varies would make its levels one run: an error naming the key.
  try {
    hvi::driver::load_study(data + "drift_study.toml", {" body.ball.sphere.radius =2 mm"});
    FAIL() << "an override of an axis's key was accepted";
  } catch (const hvi::scene::SceneError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_EQ(e.diagnostics()[0].key, "body.ball.sphere.radius");
    EXPECT_EQ(e.diagnostics()[0].file, "--set");
  }
}

// An empty directory `name` under the tests' temporary directory.
fs::path fresh(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / name;
  fs::remove_all(dir);
  return dir;
}

// `study` swept into `out` as one plain process, one thread per run (the table to compare with).
testing::AssertionResult plain_sweep(const std::string& study, const fs::path& out,
                                     const fs::path& log) {
  if (run_logged("sweep " + study + " --out " + out.string() + " --threads 1", log) == 0)
    return testing::AssertionSuccess();
  return testing::AssertionFailure() << read(log);
}

// The drift study's 5 rows in two sweeps' sweep.csv, the same but for each run's own wall time and
// memory peak.
void expect_same_rows(const fs::path& one, const fs::path& two) {
  auto a = table(one / "sweep.csv"), b = table(two / "sweep.csv");
  ASSERT_EQ(a.size(), 5u);
  for (auto* rows : {&a, &b})
    for (auto& [name, row] : *rows)
      for (const char* own : {"wall_seconds", "peak_memory_bytes"}) row.erase(own);
  EXPECT_EQ(a, b);
}

// mpirun -np 2 hvi sweep: the runs are handed out between the ranks, and sweep.csv holds what one
// rank's sweep writes, but for the runs' own wall times and memory peaks.
TEST(Sweep, TwoRanksShareAStudyAndFillTheSameTable) {
  const std::string mpirun = HVI_MPIEXEC;
  HVI_SKIP_WITHOUT_MPIRUN(mpirun);
  const fs::path one = fresh("hvi_sweep_one_rank"), two = fresh("hvi_sweep_two_ranks");
  const std::string study = data + "drift_study.toml";
  const fs::path log = fs::path(testing::TempDir()) / "hvi_sweep_ranks.log";
  ASSERT_TRUE(plain_sweep(study, one, log));
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " +
                              mpirun + " --oversubscribe -np 2 " + hvi + " sweep " + study +
                              " --out " + two.string() + " --threads 1 > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read(log);
  const std::string console = read(log);
  EXPECT_NE(console.find("handed out to 2 ranks"), std::string::npos) << console;
  EXPECT_NE(console.find("(rank 1)"), std::string::npos) << console;  // rank 1 ran some
  expect_same_rows(one, two);

  // Any other command on several ranks is refused before it does anything.
  const std::string check = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpirun +
                            " --oversubscribe -np 2 " + hvi + " check " + data + "drift.toml > " +
                            log.string() + " 2>&1";
  const int refused = std::system(check.c_str());
  EXPECT_TRUE(WIFEXITED(refused) && WEXITSTATUS(refused) == 2) << read(log);
  EXPECT_NE(read(log).find("share their work among ranks"), std::string::npos) << read(log);
}

// hvi sweep --ranks-per-run 2: each run is an MPI job of 2 ranks that the launcher starts, one
// at a time; sweep.csv holds what a one-rank sweep writes (but for the runs' own wall times and
// memory peaks), and each run's log says it ran on 2 ranks. Under mpirun itself it is refused.
TEST(Sweep, RanksPerRunStartsEachRunAsAnMpiJobAndFillsTheSameTable) {
  const std::string mpirun = HVI_MPIEXEC;
  HVI_SKIP_WITHOUT_MPIRUN(mpirun);
  const fs::path one = fresh("hvi_sweep_one_rank_per_run");
  const fs::path two = fresh("hvi_sweep_two_ranks_per_run");
  const std::string study = data + "drift_study.toml";
  const fs::path log = fs::path(testing::TempDir()) / "hvi_sweep_ranks_per_run.log";
  ASSERT_TRUE(plain_sweep(study, one, log));
  const std::string root = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 ";
  const std::string launcher = mpirun + " --oversubscribe -np {ranks}";
  const std::string command = root + hvi + " sweep " + study + " --out " + two.string() +
                              " --threads 1 --ranks-per-run 2 --launcher '" + launcher + "' > " +
                              log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read(log);
  EXPECT_NE(read(log).find("each an MPI job: " + mpirun + " --oversubscribe -np 2"),
            std::string::npos)
      << read(log);
  expect_same_rows(one, two);
  for (const auto& [name, row] : table(one / "sweep.csv"))
    EXPECT_NE(read(two / (name + ".log")).find("ranks: 2;"), std::string::npos) << name;

  const std::string nested = root + mpirun + " --oversubscribe -np 2 " + hvi + " sweep " + study +
                             " --out " + two.string() + " --ranks-per-run 2 > " + log.string() +
                             " 2>&1";
  const int refused = std::system(nested.c_str());
  EXPECT_TRUE(WIFEXITED(refused) && WEXITSTATUS(refused) == 2) << read(log);
  EXPECT_NE(read(log).find("start the sweep itself without mpirun"), std::string::npos)
      << read(log);
}

TEST(Sweep, RunsEveryScenePutsItsMeasuresInOneTableAndSkipsWhatIsDone) {
  HVI_SKIP_UNDER_SANITIZERS(
      "19 s in Release; the sweep runs in Sweep.RunsMadeOneAtATimeShareOneTable");
  const fs::path out = fs::path(testing::TempDir()) / "hvi_sweep";
  fs::remove_all(out);
  const fs::path log = fs::path(testing::TempDir()) / "hvi_sweep.log";
  ASSERT_EQ(
      run_logged("sweep " + data + "drift_study.toml --out " + out.string() + " --threads 2", log),
      0)
      << read(log);
  auto rows = table(out / "sweep.csv");
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows["v200_r15"]["speed"], "v200");
  EXPECT_EQ(rows["v200_r15"]["size"], "r15");
  for (const auto& [name, row] : rows) {
    EXPECT_EQ(row.at("status"), "finished") << name;
    // The run's peak memory; the command's with a hole measurement only where a run has one
    // (these do not).
    EXPECT_GT(std::stod(row.at("peak_memory_bytes")), 0.0) << name;
    EXPECT_EQ(row.at("peak_memory_with_measure_bytes"), "") << name;
  }
  // A free elastic sphere translates rigidly: its front advances by v t, so the 200 m/s runs lead
  // the 100 m/s ones by 100 m/s x 2 us = 0.2 mm, and the still one stays where it started.
  auto front = [&](const std::string& run) { return std::stod(rows[run]["front"]); };
  EXPECT_NEAR(front("v200_r1") - front("v100_r1"), 0.2e-3, 1e-12);
  EXPECT_NEAR(front("v200_r15") - front("v100_r15"), 0.2e-3, 1e-12);
  EXPECT_NEAR(front("v100_r1") - front("still"), 0.2e-3, 1e-12);
  EXPECT_GT(front("v100_r15"), front("v100_r1"));  // the larger sphere reaches further

  // Done runs are not run again: their rows (wall times included) are unchanged.
  const std::string before = read(out / "sweep.csv");
  ASSERT_EQ(run_logged("sweep " + data + "drift_study.toml --out " + out.string(), log), 0)
      << read(log);
  EXPECT_NE(read(log).find("v200_r15: done"), std::string::npos) << read(log);
  EXPECT_EQ(read(out / "sweep.csv"), before);

  // A later end time in the study: every run is run on from its checkpoint (the sphere drifts
  // 0.1 mm more per 100 m/s), and the table is rebuilt.
  const double first_wall = std::stod(rows["v200_r15"]["wall_seconds"]);
  ASSERT_EQ(run_logged("sweep " + data + "drift_study.toml --out " + out.string() +
                           " --set run.end_time=3us",
                       log),
            0)
      << read(log);
  EXPECT_NE(read(log).find("v200_r15: running on to 3 us"), std::string::npos) << read(log);
  // The run's log names it, and keeps the first part above the second.
  const std::string run_log = read(out / "v200_r15.log");
  const auto first = run_log.find("hvi sweep: run 'v200_r15' of ");
  EXPECT_EQ(first, 0u) << run_log;
  EXPECT_NE(run_log.find("hvi sweep: run 'v200_r15' of ", first + 1), std::string::npos) << run_log;
  rows = table(out / "sweep.csv");
  EXPECT_NEAR(front("v200_r1") - front("v100_r1"), 0.3e-3, 1e-12);
  // Its wall time is what both parts cost, not the run-on's alone (sweep.csv keeps 10 digits).
  const toml::table summary = toml::parse_file((out / "v200_r15" / "summary.toml").string());
  const double run_on_wall = summary["wall_seconds"].value_or(0.0);
  EXPECT_GT(run_on_wall, 0.0);
  EXPECT_NEAR(std::stod(rows["v200_r15"]["wall_seconds"]), first_wall + run_on_wall,
              1e-9 * (first_wall + run_on_wall));
  EXPECT_NEAR(front("v100_r1") - front("still"), 0.3e-3, 1e-12);
  const hvi::scene::Scene extended =
      hvi::scene::load_scene((out / "v100_r1" / "scene.resolved.toml").string());
  EXPECT_EQ(extended.end_time, 3e-6);

  // Another output cadence is not another run.
  EXPECT_EQ(run_logged("sweep " + data + "drift_study.toml --out " + out.string() +
                           " --set run.end_time=3us --set output.interval=0.5us",
                       log),
            0)
      << read(log);
  EXPECT_NE(read(log).find("v200_r15: done"), std::string::npos) << read(log);
  EXPECT_EQ(read(log).find("it keeps the [[measure]]"), std::string::npos) << read(log);

  // Nor is another list of measures: a done run keeps those it was run with, its row unchanged,
  // and the console says so.
  const std::string measured = read(out / "sweep.csv");
  const std::string other_measure =
      R"( --set 'measure=[{name="back",kind="extent_min",axis="x"}]')";
  EXPECT_EQ(run_logged("sweep " + data + "drift_study.toml --out " + out.string() +
                           " --set run.end_time=3us" + other_measure,
                       log),
            0)
      << read(log);
  const std::string said = read(log);
  const auto done = said.find("v200_r15: done");
  ASSERT_NE(done, std::string::npos) << said;
  EXPECT_EQ(
      said.find("    it keeps the [[measure]] it was started with (the study's differ)\n", done),
      said.find('\n', done) + 1)
      << said;
  EXPECT_EQ(read(out / "sweep.csv"), measured);

  // An earlier end time, or any other key changed, is refused before anything runs.
  const std::string after = read(out / "sweep.csv");
  EXPECT_EQ(run_logged("sweep " + data + "drift_study.toml --out " + out.string(), log), 2);
  EXPECT_NE(read(log).find("ran to 3 us but the study now ends at 2 us"), std::string::npos)
      << read(log);
  EXPECT_EQ(run_logged("sweep " + data + "drift_study.toml --out " + out.string() +
                           " --set run.end_time=3us --set grid.cfl=0.3",
                       log),
            2);
  EXPECT_NE(read(log).find("key 'grid.cfl' differs"), std::string::npos) << read(log);
  EXPECT_EQ(read(out / "sweep.csv"), after);

  // Run on with other measures, a run keeps its own: the sphere's front, 0.4 mm ahead per 100 m/s.
  ASSERT_EQ(run_logged("sweep " + data + "drift_study.toml --out " + out.string() +
                           " --set run.end_time=4us" + other_measure,
                       log),
            0)
      << read(log);
  EXPECT_NE(
      read(log).find(
          "v200_r15: running on to 4 us...\n    it keeps the [[measure]] it was started with"),
      std::string::npos)
      << read(log);
  rows = table(out / "sweep.csv");
  EXPECT_NEAR(front("v200_r1") - front("v100_r1"), 0.4e-3, 1e-12);
  EXPECT_EQ(rows["v200_r1"].count("back"), 0u);
}

TEST(Sweep, RunsMadeOneAtATimeShareOneTable) {
  // Long runs go one `--only` at a time into one directory; the table keeps the earlier ones'
  // rows, in the study's order, and lists no run that has not been started.
  const fs::path out = fs::path(testing::TempDir()) / "hvi_sweep_only";
  fs::remove_all(out);
  const fs::path log = fs::path(testing::TempDir()) / "hvi_sweep_only.log";
  ASSERT_EQ(
      run_logged("sweep " + data + "drift_study.toml --out " + out.string() + " --only still", log),
      0)
      << read(log);
  ASSERT_EQ(
      run_logged("sweep " + data + "drift_study.toml --out " + out.string() + " --only v100_r1",
                 log),
      0)
      << read(log);
  const auto rows = table(out / "sweep.csv");
  ASSERT_EQ(rows.size(), 2u) << read(out / "sweep.csv");
  EXPECT_EQ(rows.at("still").at("status"), "finished");
  EXPECT_EQ(rows.at("v100_r1").at("status"), "finished");
  EXPECT_EQ(rows.at("v100_r1").at("speed"), "v100");
  // The same drift as in the full sweep: 100 m/s x 2 us.
  EXPECT_NEAR(std::stod(rows.at("v100_r1").at("front")) - std::stod(rows.at("still").at("front")),
              0.2e-3, 1e-12);
  const std::string csv = read(out / "sweep.csv");
  EXPECT_LT(csv.find("\nv100_r1,"), csv.find("\nstill,"));  // the study's order

  // A run continued by hand to a later end: the same sweep, its end time set to the run's, counts
  // it done and tables its new state (100 m/s x 3 us), not the row of its first sitting.
  ASSERT_EQ(
      run_logged("run --resume " + (out / "v100_r1").string() + " --set run.end_time=3us", log), 0)
      << read(log);
  ASSERT_EQ(run_logged("sweep " + data + "drift_study.toml --out " + out.string() +
                           " --only v100_r1 --set run.end_time=3us",
                       log),
            0)
      << read(log);
  EXPECT_NE(read(log).find("v100_r1: done"), std::string::npos) << read(log);
  const auto later = table(out / "sweep.csv");
  EXPECT_NEAR(std::stod(later.at("v100_r1").at("front")) - std::stod(later.at("still").at("front")),
              0.3e-3, 1e-12);
}

// A run that does not finish is reported on the sweep's console with the run's own account of
// it and its warnings, and tabled as stopped (it ended cleanly short of its end time) or failed.
TEST(Sweep, TheConsoleSaysWhyARunStoppedOrFailed) {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_sweep_why";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path log = dir / "console.txt";

  // Stopped by run.max_steps, at 2 km/s, 43% of the steel's bulk sound speed: the EOS warning.
  std::ofstream(dir / "stopped.toml")
      << "scene = \"" << data << "drift.toml\"\n"
      << "[[run]]\nname = \"still\"\n"
      << "set = [\"body.ball.velocity=[2000, 0, 0]\", \"run.max_steps=3\"]\n";
  ASSERT_EQ(
      run_logged(
          "sweep " + (dir / "stopped.toml").string() + " --out " + (dir / "stopped").string(), log),
      3)
      << read(log);
  std::string console = read(log);
  for (const char* part : {"    stopped after ", "(exit 0); see ",
                           "      hvi: stopped (run.max_steps) at t = ", ", step 3: 3 steps in ",
                           "      warning: material 'steel' names no equation of state"})
    EXPECT_NE(console.find(part), std::string::npos) << part << " in:\n" << console;
  EXPECT_EQ(console.find("hvi: " + data + "drift.toml"), std::string::npos)
      << console;  // not the banner
  EXPECT_EQ(table(dir / "stopped" / "sweep.csv").at("still").at("status"), "stopped");

  // Failed: two spheres colliding on linear shape functions with USL (see test_cli).
  std::ofstream(dir / "failed.toml")
      << "scene = \"" << data << "small_spheres.toml\"\n"
      << "[[run]]\nname = \"unstable\"\n"
      << "set = [\"grid.shape_function=linear\", \"grid.scheme=usl\"]\n";
  ASSERT_EQ(
      run_logged("sweep " + (dir / "failed.toml").string() + " --out " + (dir / "failed").string(),
                 log),
      3)
      << read(log);
  console = read(log);
  for (const char* part :
       {"    failed after ", "(exit 3); see ", "      hvi: the run failed: step ",
        "non-positive volume", "checkpoint.h5 (step 0) the last state before it"})
    EXPECT_NE(console.find(part), std::string::npos) << part << " in:\n" << console;
  // The spheres meet at 600 m/s, 13% of that sound speed: the warning comes after the failure.
  const auto warning = console.find(
      "      warning: material 'steel' names no equation of state, but the impact speed 600.1 m/s");
  ASSERT_NE(warning, std::string::npos) << console;
  EXPECT_GT(warning, console.find("the last state before it")) << console;
  EXPECT_EQ(table(dir / "failed" / "sweep.csv").at("unstable").at("status"), "failed");
}

TEST(Sweep, ABadLevelStopsTheSweepBeforeAnythingRuns) {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_sweep_bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(data + "drift.toml", dir / "drift.toml");
  std::string study = read(data + "drift_study.toml");
  study.replace(study.find("radius=1.5 mm"), 13, "radius=1.5 kg");
  std::ofstream(dir / "study.toml") << study;
  const fs::path out = dir / "out";
  const fs::path log = dir / "log.txt";
  EXPECT_EQ(run_logged("sweep " + (dir / "study.toml").string() + " --out " + out.string(), log),
            2);
  EXPECT_NE(read(log).find("body.ball.sphere.radius"), std::string::npos) << read(log);
  EXPECT_NE(read(log).find("v100_r15"), std::string::npos) << read(log);  // the first run it is in
  EXPECT_FALSE(fs::exists(out));
}

TEST(Sweep, StudyFileErrorsNameTheLine) {
  const fs::path file = fs::path(testing::TempDir()) / "hvi_bad_study.toml";
  std::ofstream(file) << "scene = \"drift.toml\"\n[[run]]\nname = \"a\"\nsett = [\"x=1\"]\n";
  try {
    hvi::driver::load_study(file.string());
    FAIL() << "accepted";
  } catch (const hvi::scene::SceneError& e) {
    const auto& d = e.diagnostics().front();
    EXPECT_EQ(d.line, 4);
    EXPECT_NE(d.text().find("did you mean"), std::string::npos) << d.text();
  }
}

// The studies shipped in cases/paper/ stay valid as the scene keys evolve: every run's scene
// resolves (sweep --list checks each one and exits 2 on the first bad key), at both resolutions
// where the base scene has them.
TEST(Sweep, ShippedPaperStudiesResolve) {
  const std::string cases = std::string(HVI_SOURCE_DIR) + "/cases/paper/";
  const fs::path out = fs::path(testing::TempDir()) / "hvi_sweep_list";
  const fs::path log = fs::path(testing::TempDir()) / "hvi_sweep_list.log";
  for (const std::string study : {"validation/printed.toml", "validation/foil.toml",
                                  "study/study.toml", "structure/structure.toml"})
    for (const std::string resolution : {"coarse", "paper"})
      EXPECT_EQ(run_logged("sweep " + cases + study + " --out " + out.string() +
                               " --list --set resolution=" + resolution,
                           log),
                0)
          << study << " " << resolution << ": " << read(log);
  for (const std::string study : {"study/front_hole_knobs.toml", "study/front_hole_fine.toml"})
    EXPECT_EQ(run_logged("sweep " + cases + study + " --out " + out.string() + " --list", log), 0)
        << study << ": " << read(log);
  EXPECT_FALSE(fs::exists(out));  // listing writes nothing
}

}  // namespace
