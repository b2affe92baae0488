// The hvi command line end to end: bad input stops before anything is written (exit code 2), a
// run records its resolved scene and code revision, the same scene gives byte-identical output
// for 1 and 2 threads, and a run resumed from a checkpoint matches an uninterrupted one byte for
// byte.
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace fs = std::filesystem;

namespace {

const std::string hvi = HVI_BINARY;
const std::string scene = std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_spheres.toml";

fs::path scratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("hvi_cli_" + name);
  fs::remove_all(p);
  return p;
}

// Runs hvi with `args`; returns its exit code, stderr in `err`.
int run(const std::string& args, std::string* err = nullptr) {
  // One file per test: ctest runs the tests of this file in parallel.
  const fs::path log = fs::path(testing::TempDir()) /
                       ("hvi_cli_stderr_" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) + ".txt");
  const std::string cmd = hvi + " " + args + " > /dev/null 2> " + log.string();
  const int status = std::system(cmd.c_str());
  if (err) {
    std::ifstream in(log);
    std::stringstream s;
    s << in.rdbuf();
    *err = s.str();
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Every snapshot file, energy.csv and the XDMF index of two runs are byte-identical.
void expect_same_output(const fs::path& a, const fs::path& b) {
  EXPECT_TRUE(read(a / "energy.csv") == read(b / "energy.csv")) << "energy.csv differs";
  EXPECT_TRUE(read(a / "particles.xmf") == read(b / "particles.xmf")) << "particles.xmf differs";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(a / "snapshots")) {
    const fs::path other = b / "snapshots" / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(read(entry.path()) == read(other)) << entry.path().filename() << " differs";
    ++files;
  }
  EXPECT_EQ(files, 5);  // t = 0, 1, 2, 3, 4 us
}

TEST(Cli, CheckAcceptsAValidScene) { EXPECT_EQ(run("check " + scene), 0); }

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

TEST(Cli, ResumedRunMatchesUninterruptedRun) {
  const fs::path full = scratch("full"), parts = scratch("parts");
  ASSERT_EQ(run("run " + scene + " --out " + full.string() + " --threads 2"), 0);
  // Stop after 37 steps (between snapshots and between energy rows), then resume.
  ASSERT_EQ(run("run " + scene + " --out " + parts.string() + " --threads 2 --set run.max_steps=37"), 0);
  EXPECT_FALSE(fs::exists(parts / "snapshots" / "particles_000004.h5"));
  ASSERT_EQ(run("run --resume " + parts.string() + " --threads 1 --set run.max_steps=0"), 0);
  expect_same_output(full, parts);
}

// A run that goes wrong stops at the first bad step with a message naming the particle, body,
// material, position, time and step, and leaves a checkpoint from before it. (Linear shape
// functions with USL are unstable for these spheres: a node's tiny mass blows up a velocity.)
TEST(Cli, FailedRunNamesTheParticleAndLeavesACheckpointFromBefore) {
  const fs::path out = scratch("fail");
  std::string err;
  EXPECT_EQ(run("run " + scene + " --out " + out.string() + " --set grid.shape_function=linear --set grid.scheme=usl", &err), 3);
  for (const char* part : {"the run failed: step ", ", t = ", "particle ", "(body 'left', material 'steel') at (",
                           "non-positive volume"})
    EXPECT_NE(err.find(part), std::string::npos) << part << " in: " << err;
  EXPECT_NE(err.find("checkpoint.h5 (step 0)"), std::string::npos) << err;
  EXPECT_TRUE(fs::exists(out / "checkpoint.h5"));
  EXPECT_TRUE(fs::exists(out / "failure.h5"));
}

// A run whose energy runs away stops at the first energy row past run.max_energy_growth, naming
// the fastest particle. (A 0.4-cell projectile gains ~29% at cfl 0.5: see test_stability.)
TEST(Cli, EnergyRunawayStopsTheRun) {
  const fs::path out = scratch("runaway");
  const std::string stability = std::string(HVI_SOURCE_DIR) + "/cases/stability/hypervelocity_10kms.toml";
  std::string err;
  EXPECT_EQ(run("run " + stability + " --out " + out.string() +
                    " --threads 1 --set grid.cell_size=5e-4 --set body.projectile.velocity=[0,0,-4500]"
                    " --set body.projectile.sphere.radius=2e-4 --set body.projectile.sphere.center=[0,0,0.5e-3]"
                    " --set body.projectile.particles_per_cell=4 --set run.end_time=1e-6"
                    " --set output.energy_every=1 --set run.max_energy_growth=0.1",
                &err),
            3);
  EXPECT_NE(err.find("the total energy grew by"), std::string::npos) << err;
  EXPECT_NE(err.find("(run.max_energy_growth = 10%)"), std::string::npos) << err;
  EXPECT_NE(err.find("this particle moves fastest"), std::string::npos) << err;
}

}  // namespace
