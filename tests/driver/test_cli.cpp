// The hvi command line end to end: bad input stops before anything is written (exit code 2), a
// run records its resolved scene and code revision, the same scene gives byte-identical output
// for 1 and 2 threads, and a run resumed from a checkpoint matches an uninterrupted one byte for
// byte (the same for a hybrid: test_cli_hybrid.cpp); displacement probes; hvi compare.
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
#include "tests/support/scene_text.hpp"

namespace fs = std::filesystem;

namespace {

using namespace hvi::test;  // the run helpers of tests/support/run_hvi.hpp

const std::string hvi = HVI_BINARY;
const std::string scene = std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_spheres.toml";

TEST(Cli, CheckAcceptsAValidScene) {
  EXPECT_EQ(run("check " + scene), 0);
}

TEST(Cli, BadSceneStopsBeforeWritingAnything) {
  const fs::path out = scratch("bad");
  std::string err;
  EXPECT_EQ(run("run " + scene + " --out " + out.string() + " --set grid.cfl=2", &err), 2);
  EXPECT_FALSE(fs::exists(out));
  EXPECT_NE(err.find("--set grid.cfl=2:1:"), std::string::npos) << err;
  EXPECT_NE(err.find("key 'grid.cfl'"), std::string::npos) << err;
  EXPECT_EQ(run("check " + scene + " --set grid.cel_size=1", &err), 2);
  EXPECT_NE(err.find("did you mean 'cell_size'"), std::string::npos) << err;
}

TEST(Cli, RunRecordsResolvedSceneAndRevision) {
  const fs::path out = scratch("record");
  ASSERT_EQ(run("run " + scene + " --out " + out.string() + " --threads 2"), 0);
  const std::string resolved = read(out / "scene.resolved.toml");
  EXPECT_NE(resolved.find("interval = 9.9999999999999995e-07"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("scheme = 'musl'"), std::string::npos) << resolved;  // a default
  // A scene without [far_field] builds, writes and logs nothing of one.
  EXPECT_FALSE(fs::exists(out / "far_field.pvd"));
  EXPECT_FALSE(fs::exists(out / "far_field"));
  EXPECT_EQ(read(out / "energy.csv").find("coupled"), std::string::npos);
  const std::string info = read(out / "run.json");
  EXPECT_NE(info.find("\"git_revision\""), std::string::npos) << info;
  // The resolved scene is itself a valid scene.
  EXPECT_EQ(run("check " + (out / "scene.resolved.toml").string()), 0);
  // A second run into the same directory is refused without --overwrite.
  EXPECT_EQ(run("run " + scene + " --out " + out.string()), 2);
}

TEST(Cli, OutputIsBitwiseIdenticalForOneAndTwoThreads) {
  const fs::path one = scratch("threads1"), two = scratch("threads2");
  ASSERT_EQ(run("run " + scene + " --out " + one.string() + " --threads 1"), 0);
  ASSERT_EQ(run("run " + scene + " --out " + two.string() + " --threads 2"), 0);
  expect_same_output(one, two);
}

// grid.stencil_cache keeps each point's GIMP weights between a step's transfers: the output is
// the same bytes with it and without it (the default), for MUSL with the node average (one
// evaluation a step instead of five) and for USF, which scatters mass and force in separate passes.
// On 2 threads: USF with cpGIMP and the node average differed from run to run while it stretched
// the domains between its transfers (a domain outgrowing its owner block's stencil wrote outside
// its colour).
TEST(Cli, OutputIsBitwiseIdenticalWithAndWithoutTheStencilCache) {
  for (const std::string scheme : {"musl", "usf"}) {
    SCOPED_TRACE(scheme);
    const std::string set =
        " --threads 2 --set grid.shape_function=cpgimp --set grid.dilatation=node-average"
        " --set grid.scheme=" +
        scheme;
    const fs::path on = scratch("cache_on_" + scheme), off = scratch("cache_off_" + scheme);
    ASSERT_EQ(
        run("run " + scene + " --out " + on.string() + set + " --set grid.stencil_cache=true"), 0);
    ASSERT_EQ(
        run("run " + scene + " --out " + off.string() + set + " --set grid.stencil_cache=false"),
        0);
    expect_same_output(on, off);
  }
}

// With hydrocode materials the models declare their fields (plastic strain, damage, failed, ...)
// once they run; a resumed run declares them from the checkpoint in the same order, so its
// snapshot files are byte-identical too, not only their datasets.
TEST(Cli, ResumedHydrocodeRunMatchesUninterruptedRun) {
  const std::string hydro =
      " --set material.steel.library=Al6061 --set material.steel.strength=johnson-cook"
      " --set material.steel.eos=mie-gruneisen --set material.steel.damage=johnson-cook";
  const fs::path full = scratch("hydro_full"), parts = scratch("hydro_parts");
  ASSERT_EQ(run("run " + scene + " --out " + full.string() + " --threads 2" + hydro), 0);
  ASSERT_EQ(run("run " + scene + " --out " + parts.string() +
                " --threads 2 --set run.max_steps=37" + hydro),
            0);
  ASSERT_EQ(run("run --resume " + parts.string() + " --threads 1 --set run.max_steps=0"), 0);
  expect_same_output(full, parts);
}

TEST(Cli, ResumedRunMatchesUninterruptedRun) {
  const fs::path full = scratch("full"), parts = scratch("parts");
  ASSERT_EQ(run("run " + scene + " --out " + full.string() + " --threads 2"), 0);
  // Stop after 37 steps (between snapshots and between energy rows), then resume.
  ASSERT_EQ(
      run("run " + scene + " --out " + parts.string() + " --threads 2 --set run.max_steps=37"), 0);
  EXPECT_FALSE(fs::exists(parts / "snapshots" / "particles_000004.h5"));
  const double first_wall = summary_number(parts, "wall_seconds");
  EXPECT_EQ(summary_number(parts, "wall_seconds_total"), first_wall);  // one invocation so far
  // What hvi measure wrote of the state at step 37 (here stand-ins) is stale once the run goes on:
  // resuming removes it, so a sweep measures the run again instead of tabling the old reading.
  for (const char* f : {"measurements.csv", "measurements.json", "measurements_history.csv"})
    std::ofstream(parts / f) << "step 37\n";
  // Resumed twice: to step 50, then to the end.
  ASSERT_EQ(run("run --resume " + parts.string() + " --threads 1 --set run.max_steps=50"), 0);
  for (const char* f : {"measurements.csv", "measurements.json", "measurements_history.csv"})
    EXPECT_FALSE(fs::exists(parts / f)) << f;
  const double second_wall = summary_number(parts, "wall_seconds");
  ASSERT_EQ(run("run --resume " + parts.string() + " --threads 1 --set run.max_steps=0"), 0);
  expect_same_output(full, parts);
  // The run's cost is all three invocations': the earlier ones', recorded in the last checkpoint,
  // plus the last one's (to the last bit: the same doubles added in the same order).
  const double third_wall = summary_number(parts, "wall_seconds");
  EXPECT_GT(second_wall, 0.0);
  EXPECT_GT(third_wall, 0.0);
  EXPECT_EQ(summary_number(parts, "wall_seconds_total"), (first_wall + second_wall) + third_wall);
  EXPECT_EQ(summary_number(full, "wall_seconds_total"), summary_number(full, "wall_seconds"));
  // Each resume is a line of resumes.jsonl, with where it continued from and what ran it.
  std::ifstream resumes(parts / "resumes.jsonl");
  std::vector<std::string> lines;
  for (std::string line; std::getline(resumes, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("\"step\" : 37,"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("\"step\" : 50,"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("\"command\" : \"" + hvi + " run --resume "), std::string::npos)
      << lines[1];
  EXPECT_NE(lines[1].find("\"threads\" : 1"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("\"git_revision\" : \""), std::string::npos) << lines[1];
  EXPECT_FALSE(fs::exists(full / "resumes.jsonl"));
}

// SIGTERM, what a batch scheduler sends before its time limit, stops a run as Ctrl-C does: at the
// end of the step, with a checkpoint and exit code 143 (128 + 15). Wherever the signal lands, the
// run resumed from that checkpoint continues it byte for byte.
TEST(Cli, SigtermStopsTheRunWithACheckpointItResumesFrom) {
  const fs::path stopped = scratch("sigterm"), straight = scratch("sigterm_straight");
  // 100 times the scene's 4 us (about 10,000 steps), so the signal arrives long before the end.
  const std::string end_time = "run.end_time=400us";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::freopen("/dev/null", "w", stdout);
    execl(hvi.c_str(), hvi.c_str(), "run", scene.c_str(), "--out", stopped.c_str(), "--threads",
          "1", "--set", end_time.c_str(), static_cast<char*>(nullptr));
    std::_Exit(127);
  }
  // Wait until the time loop has written a few energy rows (one every 5 steps), then signal.
  const auto rows = [&] {
    std::ifstream in(stopped / "energy.csv");
    return std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n');
  };
  for (int i = 0; i < 6000 && rows() < 20; ++i) usleep(10000);
  ASSERT_GE(rows(), 20) << "the run did not start its time loop within 60 s";
  ASSERT_EQ(kill(child, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by the signal instead of stopping";
  EXPECT_EQ(WEXITSTATUS(status), 143);
  EXPECT_NE(read(stopped / "summary.toml").find("status = 'interrupted'"), std::string::npos);
  const auto steps = static_cast<std::int64_t>(summary_number(stopped, "steps"));
  ASSERT_GE(steps, 90);  // the header and rows at steps 0, 5, ..., 90 were there before the signal
  ASSERT_LT(steps, 10000);  // well before the end
  // Resumed to 10 steps past the signal, and the same run without the signal.
  const std::string until = " --set run.max_steps=" + std::to_string(steps + 10);
  ASSERT_EQ(run("run --resume " + stopped.string() + " --threads 2" + until), 0);
  ASSERT_EQ(run("run " + scene + " --out " + straight.string() + " --threads 2 --set " + end_time +
                until),
            0);
  EXPECT_EQ(summary_number(stopped, "steps"), static_cast<double>(steps + 10));
  const auto files =
      std::distance(fs::directory_iterator(stopped / "snapshots"), fs::directory_iterator{});
  EXPECT_GE(files, 1);
  expect_same_output(straight, stopped, static_cast<int>(files));
}

// A run that goes wrong stops at the first bad step with a message naming the particle, body,
// material, position, time and step, and leaves a checkpoint from before it. (Linear shape
// functions with USL are unstable for these spheres: a node's tiny mass blows up a velocity.)
TEST(Cli, FailedRunNamesTheParticleAndLeavesACheckpointFromBefore) {
  const fs::path out = scratch("fail");
  std::string err;
  EXPECT_EQ(run("run " + scene + " --out " + out.string() +
                    " --set grid.shape_function=linear --set grid.scheme=usl",
                &err),
            3);
  for (const char* part : {"the run failed: step ", ", t = ", "particle ",
                           "(body 'left', material 'steel') at (", "non-positive volume"})
    EXPECT_NE(err.find(part), std::string::npos) << part << " in: " << err;
  EXPECT_NE(err.find("checkpoint.h5 (step 0)"), std::string::npos) << err;
  EXPECT_TRUE(fs::exists(out / "checkpoint.h5"));
  EXPECT_TRUE(fs::exists(out / "failure.h5"));
}

// A run whose energy runs away stops at the first energy row past run.max_energy_growth, naming
// the fastest particle. (A 0.4-cell projectile gains ~29% at cfl 0.5: see test_stability.)
TEST(Cli, EnergyRunawayStopsTheRun) {
  const fs::path out = scratch("runaway");
  const std::string stability =
      std::string(HVI_SOURCE_DIR) + "/cases/stability/hypervelocity_10kms.toml";
  std::string err;
  EXPECT_EQ(
      run("run " + stability + " --out " + out.string() +
              " --threads 1 --set grid.cell_size=5e-4 --set body.projectile.velocity=[0,0,-4500]"
              " --set body.projectile.sphere.radius=2e-4 --set "
              "body.projectile.sphere.center=[0,0,0.5e-3]"
              " --set body.projectile.particles_per_cell=4 --set run.end_time=1e-6"
              " --set output.energy_every=1 --set run.max_energy_growth=0.1",
          &err),
      3);
  EXPECT_NE(err.find("the total energy grew by"), std::string::npos) << err;
  EXPECT_NE(err.find("(run.max_energy_growth = 10%)"), std::string::npos) << err;
  EXPECT_NE(err.find("this particle moves fastest"), std::string::npos) << err;
}

// A run says, before its time loop, what its output will take of the disk: the snapshots still due
// and the checkpoint (twice in a fresh run: the first, and the next one written aside before it
// replaces it), each within 1% of the files it then writes (HDF5 adds a few kB of metadata). The
// demo on 0.8 mm cells to 1 us: one snapshot to come after the first; three with snapshots every
// 0.4 us. hvi check announces the whole run's, four snapshots.
TEST(Cli, ARunSaysWhatItsOutputWillTakeOfTheDisk) {
  HVI_SKIP_UNDER_SANITIZERS("242 s under the sanitizers; the estimate runs in MemoryEstimate.*");
  const fs::path out = scratch("disk");
  const std::string log = (fs::path(testing::TempDir()) / "hvi_cli_disk.log").string();
  const std::string command =
      hvi + " run " + std::string(HVI_SOURCE_DIR) + "/cases/demo.toml --out " + out.string() +
      " --threads 2 --set 'run.end_time=1 us' --set 'grid.cell_size=0.8 mm' > " + log + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0);
  const std::string said = read(log);
  const std::regex line(
      R"(output: 1 snapshot of about ([0-9.]+) MB and a checkpoint of ([0-9.]+) MB to come, ([0-9.]+) MB in all; [0-9.]+ [kMG]B free on the disk)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(said, m, line)) << said;
  const double snapshot = std::stod(m[1]) * 1e6, checkpoint = std::stod(m[2]) * 1e6,
               all = std::stod(m[3]) * 1e6;
  EXPECT_NEAR(snapshot,
              static_cast<double>(fs::file_size(out / "snapshots" / "particles_000001.h5")),
              0.01 * snapshot);
  EXPECT_NEAR(checkpoint, static_cast<double>(fs::file_size(out / "checkpoint.h5")),
              0.01 * checkpoint);
  EXPECT_NEAR(all, snapshot + 2 * checkpoint, 0.01 * all);
  // Every 0.4 us: 0.4 and 0.8 us, then the end, 3 to come, and so many written.
  const fs::path often = scratch("disk_often");
  const std::string again = hvi + " run " + std::string(HVI_SOURCE_DIR) +
                            "/cases/demo.toml --out " + often.string() +
                            " --threads 2 --set 'run.end_time=1 us' --set 'grid.cell_size=0.8 mm' "
                            "--set 'output.interval=0.4 us' > " +
                            log + " 2>&1";
  ASSERT_EQ(std::system(again.c_str()), 0);
  EXPECT_NE(read(log).find("output: 3 snapshots of about"), std::string::npos) << read(log);
  const auto files =
      std::distance(fs::directory_iterator(often / "snapshots"), fs::directory_iterator());
  EXPECT_EQ(files, 4);
  // Keeping the newest one, at most two are on the disk at once: the newest, and the one it
  // replaces.
  const fs::path kept = scratch("disk_kept");
  const std::string keep = hvi + " run " + std::string(HVI_SOURCE_DIR) + "/cases/demo.toml --out " +
                           kept.string() +
                           " --threads 2 --set 'run.end_time=1 us' --set 'grid.cell_size=0.8 mm' "
                           "--set 'output.interval=0.4 us'" +
                           " --set output.keep_snapshots=1 > " + log + " 2>&1";
  ASSERT_EQ(std::system(keep.c_str()), 0);
  EXPECT_NE(read(log).find("output: 2 snapshots of about"), std::string::npos) << read(log);
  EXPECT_EQ(std::distance(fs::directory_iterator(kept / "snapshots"), fs::directory_iterator()), 2);
  const std::string check_kept = hvi + " check " + std::string(HVI_SOURCE_DIR) +
                                 "/cases/demo.toml --set 'run.end_time=1 us'" +
                                 " --set 'grid.cell_size=0.8 mm' --set 'output.interval=0.4 us' "
                                 "--set output.keep_snapshots=1 > " +
                                 log + " 2>&1";
  ASSERT_EQ(std::system(check_kept.c_str()), 0);
  EXPECT_NE(read(log).find("output: 3 snapshots of about"), std::string::npos)
      << read(log);  // with the first
  // hvi check gives the whole run's: the 4 snapshots and the checkpoint twice.
  const std::string check =
      hvi + " check " + std::string(HVI_SOURCE_DIR) + "/cases/demo.toml --set 'run.end_time=1 us'" +
      " --set 'grid.cell_size=0.8 mm' --set 'output.interval=0.4 us' > " + log + " 2>&1";
  ASSERT_EQ(std::system(check.c_str()), 0);
  const std::string checked = read(log);
  const std::regex whole(
      R"(output: 4 snapshots of about ([0-9.]+) MB and a checkpoint of ([0-9.]+) MB, ([0-9.]+) MB in all)");
  ASSERT_TRUE(std::regex_search(checked, m, whole)) << checked;
  EXPECT_EQ(std::stod(m[1]) * 1e6, snapshot);
  EXPECT_EQ(std::stod(m[2]) * 1e6, checkpoint);
  EXPECT_NEAR(std::stod(m[3]) * 1e6, 4 * snapshot + 2 * checkpoint, 0.01 * all);
}

// A run with a kind = "holes" measure measures its last snapshot after the solver is freed: what
// it writes (measurements.json, the summary's hole sizes) is what hvi measure gives the run
// directory afterwards, byte for byte, and the summary has the command's peak memory with the
// measurement beside the run's. The demo on 0.8 mm cells to 1 us (front sheet perforated, rear
// sheet whole: the bulge, which reads the first snapshot's rear sheet, is measured too).
TEST(Cli, TheRunsOwnHoleMeasurementIsTheStandaloneOne) {
  const fs::path out = scratch("holes");
  ASSERT_EQ(run("run " + std::string(HVI_SOURCE_DIR) + "/cases/demo.toml --out " + out.string() +
                " --threads 2 --set 'run.end_time=1 us' --set 'grid.cell_size=0.8 mm'"),
            0);
  const std::string own = read(out / "measurements.json");
  EXPECT_NE(own.find("\"rear_bulge\""), std::string::npos) << own;
  EXPECT_EQ(summary_number(out, "front_perforated"), 1.0);
  EXPECT_EQ(summary_number(out, "rear_perforated"), 0.0);
  EXPECT_GT(summary_number(out, "peak_memory_bytes"), 0.0);
  EXPECT_GE(summary_number(out, "peak_memory_with_measure_bytes"),
            summary_number(out, "peak_memory_bytes"));
  const double D_f = summary_number(out, "D_f");
  EXPECT_EQ(read(out / "timing.csv").find("measure the holes"),
            std::string::npos);  // no history asked for
  EXPECT_FALSE(fs::exists(out / "holes_history.csv"));
  ASSERT_EQ(run("measure " + out.string()), 0);
  EXPECT_TRUE(read(out / "measurements.json") == own);
  const auto front_D = own.find("\"D\" : ");  // the front sheet's comes first
  ASSERT_NE(front_D, std::string::npos) << own;
  EXPECT_EQ(std::stod(own.substr(front_D + 6)), D_f);
}

// A holes measure with history = true measures each snapshot as the run writes it: its
// holes_history.csv is what hvi measure --snapshot all writes afterwards, byte for byte, and the
// run's final measurements.json is the standalone one. With output.keep_snapshots = 2 only the
// first snapshot and the newest two stay (the index lists just those), yet the history, written as
// the run went and rewritten from its checkpoint on a resume, has every row. The demo on 0.8 mm
// cells to 1 us, a snapshot every 0.25 us.
TEST(Cli, TheHoleHistoryIsHviMeasuresAndSurvivesKeepingOnlyTheNewestSnapshots) {
  HVI_SKIP_UNDER_SANITIZERS("80 s there; hvi measure runs in MeasureCommand.*");
  const std::string demo = " " + std::string(HVI_SOURCE_DIR) +
                           "/cases/demo.toml --threads 2 --set 'run.end_time=1 us'" +
                           " --set 'grid.cell_size=0.8 mm' --set 'output.interval=0.25 us'" +
                           " --set 'measure=[{name=\"holes\",kind=\"holes\",history=true}]'";
  const fs::path all = scratch("history_all"), kept = scratch("history_kept");
  ASSERT_EQ(run("run" + demo + " --out " + all.string()), 0);
  const std::string history = read(all / "holes_history.csv");
  const std::string final_holes = read(all / "measurements.json");
  ASSERT_EQ(run("measure " + all.string() + " --snapshot all"), 0);
  EXPECT_TRUE(read(all / "measurements_history.csv") == history) << history;
  ASSERT_EQ(run("measure " + all.string()), 0);
  EXPECT_TRUE(read(all / "measurements.json") == final_holes);
  // Six lines: the header and t = 0, 0.25, 0.5, 0.75 and 1 us; the front sheet perforated by the
  // end.
  std::vector<std::string> lines;
  {
    std::istringstream in(history);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  ASSERT_EQ(lines.size(), 6u) << history;
  EXPECT_EQ(lines[0].rfind("run,time,step,", 0), 0u) << lines[0];
  EXPECT_EQ(summary_number(all, "front_perforated"), 1.0);
  // Its cost is a phase of its own, there only when the scene asks for the history.
  EXPECT_NE(read(all / "timing.csv").find("\"measure the holes\","), std::string::npos);

  // Keeping the newest two, stopped between snapshots and resumed.
  ASSERT_EQ(run("run" + demo + " --out " + kept.string() +
                " --set 'output.keep_snapshots=2' --set run.max_steps=25"),
            0);
  ASSERT_EQ(run("run --resume " + kept.string() + " --threads 1 --set run.max_steps=0"), 0);
  std::vector<std::string> files;
  for (const auto& f : fs::directory_iterator(kept / "snapshots"))
    files.push_back(f.path().filename().string());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"particles_000000.h5", "particles_000003.h5",
                                             "particles_000004.h5"}));
  const std::string index = read(kept / "particles.xmf");
  for (const char* n : {"000000", "000003", "000004"})
    EXPECT_NE(index.find(n), std::string::npos) << n;
  for (const char* n : {"000001", "000002"}) EXPECT_EQ(index.find(n), std::string::npos) << n;
  // The same rows but for the run column (the directory's name).
  auto without_run = [](const std::string& csv) {
    std::string out;
    std::istringstream in(csv);
    for (std::string line; std::getline(in, line);) out += line.substr(line.find(',')) + '\n';
    return out;
  };
  EXPECT_EQ(without_run(read(kept / "holes_history.csv")), without_run(history));
  EXPECT_TRUE(read(kept / "measurements.json").find("\"D\" : ") != std::string::npos);
}

// A body in free flight: every particle keeps its velocity and moves with the grid velocity,
// which a uniform field reproduces exactly, so the probe reads v t to round-off.
TEST(Cli, DisplacementProbeFollowsARigidTranslation) {
  const fs::path dir = scratch("probe");
  fs::create_directories(dir);
  std::ofstream(dir / "scene.toml")
      << hvi::test::run_and_grid("4 us", R"(["0 mm", "0 mm", "0 mm"])",
                                 R"(["6 mm", "6 mm", "6 mm"])", "0.5 mm")
      << hvi::test::elastic_aluminium("al") << R"([[body]]
name = "block"
material = "al"
velocity = ["50 m/s", "0 m/s", "-250 m/s"]
box = { lower = ["2 mm", "2 mm", "3 mm"], upper = ["4 mm", "4 mm", "5 mm"] }
)" << hvi::test::z_probe("drop", R"(["3 mm", "3 mm", "4 mm"])");
  ASSERT_EQ(run("run " + (dir / "scene.toml").string() + " --out " + (dir / "run").string() +
                " --threads 2"),
            0);
  const auto rows = csv_rows(dir / "run" / "probes.csv");
  ASSERT_GT(rows.size(), 2u);
  for (const auto& r : rows) EXPECT_NEAR(r[2], -250.0 * r[1], 1e-12) << "t = " << r[1];
  EXPECT_NEAR(rows.back()[2], -1e-3, 1e-12);
  for (const char* key : {"drop", "drop_peak"})
    EXPECT_NEAR(summary_number(dir / "run", key), -1e-3, 1e-15) << key;  // NaN (absent) fails too
}

TEST(Cli, CompareTabulatesTwoRunsWithTheirDifference) {
  const fs::path a = scratch("compare_a"), b = scratch("compare_b");
  fs::create_directories(a);
  fs::create_directories(b);
  std::ofstream(a / "summary.toml")
      << "status = 'finished'\nwall_seconds = 100.0\nparticles = 1000\n"
         "[measures]\nD_f = 10.0\nD_r = 20.0\n";
  std::ofstream(b / "summary.toml")
      << "status = 'finished'\nwall_seconds = 20.0\nwall_seconds_total = 30.0\nparticles = "
         "100\nfar_field_nodes = 50\n"
         "mpm_zone_limit_reached_steps = 12\npeak_memory_bytes = "
         "4e8\npeak_memory_with_measure_bytes = 5e8\n"
         "[measures]\nD_f = 10.5\n";
  const fs::path table = scratch("compare_out.md");
  ASSERT_EQ(
      std::system(
          (hvi + " compare " + a.string() + " " + b.string() + " > " + table.string()).c_str()),
      0);
  const std::string t = read(table);
  EXPECT_NE(t.find("| D_f | 10 | 10.5 | +5.00% |"), std::string::npos) << t;
  EXPECT_NE(t.find("| D_r | 20 | — |  |"), std::string::npos) << t;
  // B was resumed: its cost is all its invocations (wall_seconds_total), A's its one.
  EXPECT_NE(t.find("| wall time (s) | 100 | 30 | -70.00% |"), std::string::npos) << t;
  EXPECT_NE(t.find("| far-field nodes | — | 50 |  |"), std::string::npos) << t;
  // Keys only one run has: a growing zone's limit record, the command's peak with its measurement.
  EXPECT_NE(t.find("| steps the damage held the MPM zone at its limit | — | 12 |  |"),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("| peak memory with the hole measurement (MB) | — | 500 |  |"),
            std::string::npos)
      << t;
  EXPECT_EQ(run("compare " + a.string() + " " + (b / "missing").string()), 2);

  // A hole reaching its sheet's edge (a hybrid's torn zone) is a lower bound, and so is its
  // difference.
  std::ofstream(b / "summary.toml")
      << "status = 'finished'\nwall_seconds = 20.0\nparticles = 100\n"
         "[measures]\nD_f = 10.5\nD_r = 19.0\nrear_hole_open = 1.0\nfront_hole_open = 0.0\n";
  ASSERT_EQ(
      std::system(
          (hvi + " compare " + a.string() + " " + b.string() + " > " + table.string()).c_str()),
      0);
  const std::string bounded = read(table);
  EXPECT_NE(bounded.find("| D_r | 20 | ≥ 19 | -5.00% (B a lower bound) |"), std::string::npos)
      << bounded;
  EXPECT_NE(bounded.find("| D_f | 10 | 10.5 | +5.00% |"), std::string::npos) << bounded;
  EXPECT_EQ(bounded.find("held the MPM zone"), std::string::npos)
      << bounded;  // neither run has the key
}

// hvi fit A B: the rows of several tables are fitted together (the paper fits eq. 18 to the
// parameter study and the structure study at once). Six exact rows of (D_f - d_p)/d_p =
// 2 (v_p/c_f)^0.5 (t_f/d_p)^0.3 split over two files, three each: neither file alone leaves a
// degree of freedom, together they give the coefficients back to round-off.
TEST(Cli, FitMergesSeveralTables) {
  const fs::path a = scratch("fit_a.csv"), b = scratch("fit_b.csv");
  auto rows = [](const std::vector<std::pair<double, double>>& vd) {
    std::ostringstream csv;
    csv.precision(17);
    csv << "run,v_p,d_p,t_f,c_f,D_f\n";
    for (const auto& [v, d] : vd) {
      const double D = d * (1.0 + 2.0 * std::pow(v / 5000.0, 0.5) * std::pow(0.5e-3 / d, 0.3));
      csv << "r," << v << ',' << d << ",0.0005,5000," << D << '\n';
    }
    return csv.str();
  };
  std::ofstream(a) << rows({{1300, 2e-3}, {2200, 4e-3}, {4500, 8e-3}});
  std::ofstream(b) << rows({{2900, 2e-3}, {3600, 6e-3}, {1800, 8e-3}});
  const fs::path json = scratch("fit_merged.json");
  const fs::path out = scratch("fit_merged.txt");
  ASSERT_EQ(std::system((hvi + " fit " + a.string() + " " + b.string() + " --form front --json " +
                         json.string() + " > " + out.string())
                            .c_str()),
            0);
  const std::string t = read(out);
  EXPECT_NE(t.find("6 of 6 rows fitted"), std::string::npos) << t;
  const std::string j = read(json);
  auto value = [&j](const std::string& name) {
    std::smatch m;
    const std::regex re("\"" + name + "\"\\s*:\\s*\\{[^}]*\"value\"\\s*:\\s*([-+0-9.eE]+)");
    return std::regex_search(j, m, re) ? std::stod(m[1]) : NAN;
  };
  EXPECT_NEAR(value("a0"), 2.0, 1e-9) << j;
  EXPECT_NEAR(value("a1"), 0.5, 1e-9) << j;
  EXPECT_NEAR(value("a2"), 0.3, 1e-9) << j;
  EXPECT_EQ(run("fit " + a.string() + " --form front"), 2);  // 3 rows, 3 parameters: no dof
}

}  // namespace

namespace {

// The first number after `key` in a JSON text (enough for the flat fields read here).
double json_number(const std::string& text, const std::string& key, std::size_t from = 0) {
  const auto at = text.find("\"" + key + "\"", from);
  if (at == std::string::npos) return std::nan("");
  return std::stod(text.substr(text.find(':', at) + 1));
}

}  // namespace

// hvi measure --images says where each top view lies, so that a reader (hvi report) draws hvi's
// own raster in millimetres: the PGM's size is nx x ny, its pixel the hole measurement's, and the
// raster covers the impact axis.
TEST(Cli, MeasureImagesSayWhereTheTopViewsLie) {
  const fs::path run_dir = scratch("top_view_run"), out = scratch("top_view_measure");
  ASSERT_EQ(
      run("run " + std::string(HVI_SOURCE_DIR) + "/cases/demo.toml --out " + run_dir.string() +
          " --threads 2 --set 'run.end_time=1 us' --set 'grid.cell_size=0.8 mm'"),
      0);
  ASSERT_EQ(run("measure " + run_dir.string() + " --images --out " + out.string()), 0);
  const std::string json = read(out / "measurements.json");
  const auto front = json.find("\"front\"");
  ASSERT_NE(front, std::string::npos) << json;
  const auto view = json.find("\"top_view\"", front);
  ASSERT_NE(view, std::string::npos) << json;
  const double x0 = json_number(json, "x0", view), y0 = json_number(json, "y0", view);
  const double pixel = json_number(json, "pixel", view);
  const int nx = static_cast<int>(json_number(json, "nx", view));
  const int ny = static_cast<int>(json_number(json, "ny", view));
  EXPECT_DOUBLE_EQ(pixel, json_number(json, "resolution", front));
  std::istringstream pgm(read(out / "top_view_front.pgm"));
  std::string magic;
  int width = 0, height = 0;
  pgm >> magic >> width >> height;
  EXPECT_EQ(magic, "P5");
  EXPECT_EQ(width, nx);
  EXPECT_EQ(height, ny);
  // The demo's axis is x = y = 0, on its two symmetry planes; the mirrored raster spans it.
  EXPECT_LT(x0, 0.0);
  EXPECT_GT(x0 + nx * pixel, 0.0);
  EXPECT_LT(y0, 0.0);
  EXPECT_GT(y0 + ny * pixel, 0.0);
}
