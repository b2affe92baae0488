// `mpirun -np N hvi run`: one run spread over the ranks of an MPI job (mpm/solver_ranks.cpp) writes
// the bytes a run on one rank writes: every snapshot file, particles.xmf and energy.csv, also when
// it is stopped on 3 ranks and resumed on 2; also with the node-averaged dilatation and contact.
// Also a hybrid's far field, and a zone that grows over it; a run that fails ends every rank
// cleanly. Under mpirun, oversubscribed (this machine has 2 cores).
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/run_hvi.hpp"

namespace fs = std::filesystem;

namespace {

using namespace hvi::test;

const std::string demo = std::string(HVI_SOURCE_DIR) + "/cases/demo.toml";
// The demo's first 0.6 us (about 55 steps: the sphere enters the front sheet), a snapshot every
// 0.2 us.
const std::string shortened = " --set 'run.end_time=0.6 us' --set 'output.interval=0.2 us'";

int on_ranks(int ranks, const std::string& args, const fs::path& log) {
  const std::string command =
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_WAIT_POLICY=passive " +
      std::string(HVI_MPIEXEC) + " --oversubscribe -np " + std::to_string(ranks) + " " +
      HVI_BINARY + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// `scene` run with `args` into `out` on 3 ranks until step `stop`, then resumed on 2 ranks of
// `threads` threads to its end; false with the log's text on the failing launch.
testing::AssertionResult stopped_on_three_resumed_on_two(const std::string& scene,
                                                         const std::string& args,
                                                         const fs::path& out, int stop, int threads,
                                                         const fs::path& log) {
  if (on_ranks(3,
               "run " + scene + " --out " + out.string() + args +
                   " --set run.max_steps=" + std::to_string(stop),
               log) != 0)
    return testing::AssertionFailure() << "on 3 ranks: " << read(log);
  if (on_ranks(2,
               "run --resume " + out.string() + " --threads " + std::to_string(threads) +
                   " --set run.max_steps=0",
               log) != 0)
    return testing::AssertionFailure() << "resumed on 2 ranks: " << read(log);
  return testing::AssertionSuccess();
}

TEST(RunOnRanks, WritesTheOneRankRunsBytesAndResumesOnAnotherRankCount) {
  if (std::string(HVI_MPIEXEC).empty()) GTEST_SKIP() << "hvi is built without MPI";
  const fs::path one = scratch("ranks_one"), spread = scratch("ranks_spread");
  const fs::path log = scratch("ranks_log.txt");
  ASSERT_EQ(run("run " + demo + " --out " + one.string() + " --threads 1" + shortened), 0);
  // Stopped on 3 ranks between snapshots and between energy rows, resumed on 2.
  ASSERT_EQ(on_ranks(3,
                     "run " + demo + " --out " + spread.string() + " --threads 1" + shortened +
                         " --set run.max_steps=25",
                     log),
            0)
      << read(log);
  EXPECT_NE(read(log).find("1 threads on each of 3 ranks"), std::string::npos) << read(log);
  EXPECT_NE(read(log).find("ranks: 3; the partition cut"), std::string::npos) << read(log);
  ASSERT_EQ(
      on_ranks(2, "run --resume " + spread.string() + " --threads 1 --set run.max_steps=0", log), 0)
      << read(log);
  EXPECT_NE(read(log).find("ranks: 2;"), std::string::npos) << read(log);
  expect_same_output(one, spread, 4);
  EXPECT_EQ(summary_number(spread, "ranks"), 2.0);
}

// A displacement probe chooses its points among all of them (rank 0 gathers them once) and reads
// them at every energy row (the ranks send rank 0 those points alone); the closing measures that
// read points are maxima taken over the ranks. probes.csv, every output file and the measures are
// the one-rank run's bytes.
TEST(RunOnRanks, ProbesAndPointMeasuresReadTheOneRankRunsPoints) {
  if (std::string(HVI_MPIEXEC).empty()) GTEST_SKIP() << "hvi is built without MPI";
  const fs::path scene = scratch("ranks_probe.toml");
  // On the front sheet where the sphere strikes it: its points move apart from the first steps.
  std::ofstream(scene) << read(demo)
                       << "\n[[measure]]\nname = \"front_deflection\"\nkind = \"displacement\"\n"
                          "point = [\"0.5 mm\", \"0.5 mm\", \"-0.25 mm\"]\nbody = \"panel.front\"\n"
                          "axis = \"z\"\n"
                          // The points that read every point at the end: the furthest projectile
                          // point back, the widest front-sheet point, the largest plastic strain.
                          "[[measure]]\nname = \"tail\"\nkind = \"extent_max\"\naxis = \"z\"\n"
                          "body = \"projectile\"\nsurface = true\n"
                          "[[measure]]\nname = \"width\"\nkind = \"diameter\"\naxis = \"z\"\n"
                          "body = \"panel.front\"\nsurface = true\n"
                          "[[measure]]\nname = \"strain\"\nkind = \"field_max\"\n"
                          "field = \"plastic_strain\"\n";
  const fs::path one = scratch("ranks_probe_one"), spread = scratch("ranks_probe_spread");
  const fs::path log = scratch("ranks_probe_log.txt");
  const std::string args =
      " --threads 1 --set 'run.end_time=0.3 us' --set 'output.interval=0.1 us'";
  ASSERT_EQ(run("run " + scene.string() + " --out " + one.string() + args), 0);
  ASSERT_EQ(on_ranks(2, "run " + scene.string() + " --out " + spread.string() + args, log), 0)
      << read(log);
  expect_same_output(one, spread, 4);
  EXPECT_FALSE(read(one / "probes.csv").empty());
  EXPECT_EQ(read(one / "probes.csv"), read(spread / "probes.csv"));
  for (const char* m : {"tail", "width", "strain", "front_deflection", "front_deflection_peak"}) {
    EXPECT_FALSE(std::isnan(summary_number(one, m))) << m;
    EXPECT_EQ(summary_number(one, m), summary_number(spread, m)) << m;
  }
  // Rank 0 gathered every point once, to choose the probe's points; each row asked the ranks for
  // those points alone, and the closing measures their maxima (the phase table's last column
  // counts the calls).
  const std::string said = read(log);
  const auto row = said.find("ranks: gather for output");
  ASSERT_NE(row, std::string::npos) << said;
  const std::string line = said.substr(row, said.find('\n', row) - row);
  EXPECT_EQ(line.substr(line.find_last_of(' ') + 1), "1") << line;
}

// The node-averaged dilatation (the paper's fine front-hole study uses it) and contact: their sums
// are shared between ranks like the grid's, so the demo with both writes the one-rank run's bytes
// on 2 ranks.
TEST(RunOnRanks, NodeAverageAndContactWriteTheOneRankRunsBytes) {
  if (std::string(HVI_MPIEXEC).empty()) GTEST_SKIP() << "hvi is built without MPI";
  const fs::path one = scratch("ranks_average_one"), spread = scratch("ranks_average_spread");
  const fs::path log = scratch("ranks_average_log.txt");
  const std::string args = " --threads 1 --set grid.dilatation=node-average" +
                           std::string(" --set 'contact.bodies=[\"projectile\"]'") + shortened;
  ASSERT_EQ(run("run " + demo + " --out " + one.string() + args), 0);
  ASSERT_EQ(on_ranks(2, "run " + demo + " --out " + spread.string() + args, log), 0) << read(log);
  expect_same_output(one, spread, 4);
}

// The core's bond ([bond]): each rank gathers every interface point and sums the node areas in id
// order, so the demo with its core bonded, and the energy ledger's sums, write the one-rank run's
// bytes on 2 ranks (the bonds the sphere breaks in the front sheet among them).
TEST(RunOnRanks, ABondedCoreAndTheEnergyLedgerWriteTheOneRankRunsBytes) {
  if (std::string(HVI_MPIEXEC).empty()) GTEST_SKIP() << "hvi is built without MPI";
  const fs::path one = scratch("ranks_bond_one"), spread = scratch("ranks_bond_spread");
  const fs::path log = scratch("ranks_bond_log.txt");
  const std::string args =
      " --threads 1 --set bond.panel=panel --set 'bond.normal_strength=40 MPa'"
      " --set 'bond.shear_strength=30 MPa' --set 'bond.width=0.3 mm'"
      " --set output.energy_ledger=true" +
      shortened;
  ASSERT_EQ(run("run " + demo + " --out " + one.string() + args), 0);
  ASSERT_EQ(on_ranks(2, "run " + demo + " --out " + spread.string() + args, log), 0) << read(log);
  expect_same_output(one, spread, 4);
  EXPECT_TRUE(read(one / "energy_ledger.csv") == read(spread / "energy_ledger.csv"));
}

// A hybrid ([far_field]): every rank steps the whole far field, and each tie reads its grid node
// on the rank owning the node's block (coupling/far_field_coupling.hpp). With failing J2
// facesheets and a failing core (their plastic state and damage are in the checkpoint), a run
// stopped on 3 ranks of 1 thread and resumed on 2 ranks of 2 threads writes the one-thread,
// one-rank run's bytes: snapshots, energy.csv, probes.csv and every far-field file.
const std::string small_hybrid =
    std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_hybrid.toml";
const std::string failing_hybrid =
    " --set far_field.plasticity=failing --set far_field.core=failing"
    " --set material.aluminium.library=Al5052 --set material.aluminium.strength=johnson-cook"
    " --set material.aluminium.damage=johnson-cook --set body.ball.velocity=[0,0,-2000]";

// The snapshots, energy.csv, probes.csv and every far-field file of 5 snapshots (a VTU file and a
// nodes file each).
void expect_same_far_field_output(const fs::path& one, const fs::path& spread) {
  expect_same_output(one, spread);
  EXPECT_TRUE(read(one / "probes.csv") == read(spread / "probes.csv"));
  EXPECT_FALSE(read(one / "probes.csv").empty());
  int files = 0;
  for (const auto& entry : fs::directory_iterator(one / "far_field")) {
    EXPECT_TRUE(read(entry.path()) == read(spread / "far_field" / entry.path().filename()))
        << entry.path().filename() << " differs";
    ++files;
  }
  EXPECT_EQ(files, 10);
}

TEST(RunOnRanks, AHybridWritesTheOneRankRunsBytesAndResumesOnAnotherRankCount) {
  if (std::string(HVI_MPIEXEC).empty()) GTEST_SKIP() << "hvi is built without MPI";
  const fs::path one = scratch("ranks_hybrid_one"), spread = scratch("ranks_hybrid_spread");
  const fs::path log = scratch("ranks_hybrid_log.txt");
  const std::string args = " --threads 1" + failing_hybrid;
  ASSERT_EQ(run("run " + small_hybrid + " --out " + one.string() + args), 0);
  ASSERT_TRUE(stopped_on_three_resumed_on_two(small_hybrid, args, spread, 60, 2, log));
  EXPECT_NE(read(log).find("particles, 2 threads)"), std::string::npos) << read(log);
  EXPECT_NE(read(log).find("ranks: 2;"), std::string::npos) << read(log);
  expect_same_far_field_output(one, spread);
  EXPECT_GT(summary_number(one, "far_field_max_plastic_strain"), 0.0);  // the far field yielded
}

// A zone that grows over the far field ([far_field.zone.grow], as tests/driver/test_cli_hybrid's
// growing hybrid: from 3 to 6 mm by 1 mm steps, its probe on a node the zone takes over): the
// damage of every rank's points counts, rank 0 adds the new points, every rank takes the cells
// out of its far field. Stopped on 3 ranks at step 41, where the zone first grows, and resumed on
// 2 (the checkpoint holds the grown zone), it writes the one-rank run's bytes.
TEST(RunOnRanks, AGrowingZoneWritesTheOneRankRunsBytes) {
  if (std::string(HVI_MPIEXEC).empty()) GTEST_SKIP() << "hvi is built without MPI";
  const fs::path one = scratch("ranks_growing_one"), spread = scratch("ranks_growing_spread");
  const fs::path log = scratch("ranks_growing_log.txt");
  const std::string args =
      " --threads 1" + failing_hybrid + " --set 'grid.upper=[\"7 mm\",\"7 mm\",\"3 mm\"]'" +
      " --set 'far_field.zone.grow.lower=[\"0 mm\",\"0 mm\"]'" +
      " --set 'far_field.zone.grow.upper=[\"6 mm\",\"6 mm\"]'" +
      " --set 'far_field.zone.grow.step=1 mm' --set 'far_field.zone.grow.margin=1 mm'" +
      " --set 'measure.rear_deflection.point=[\"5 mm\",\"0 mm\",\"-4 mm\"]'";
  ASSERT_EQ(run("run " + small_hybrid + " --out " + one.string() + args), 0);
  ASSERT_TRUE(stopped_on_three_resumed_on_two(small_hybrid, args, spread, 41, 1, log));
  EXPECT_NE(read(log).find("the MPM zone grew to [0, 6] x [0, 6] mm"), std::string::npos)
      << read(log);
  expect_same_far_field_output(one, spread);
  EXPECT_EQ(summary_number(one, "far_field_elements_taken_over"),
            summary_number(spread, "far_field_elements_taken_over"));
}

// A run that goes wrong on ranks (the small spheres with linear shape functions and USL, as in
// Cli.FailedRunNamesTheParticleAndLeavesACheckpointFromBefore): the rank holding a bad point
// finds it, every rank learns of it at the same point of the step, and every rank ends with the
// run's failure code. The message names a particle and the step one rank names, rank 0 writes
// failure.h5 with every point, and no rank aborts the job.
TEST(RunOnRanks, AFailingRunEndsEveryRankWithItsMessageWithoutAborting) {
  if (std::string(HVI_MPIEXEC).empty()) GTEST_SKIP() << "hvi is built without MPI";
  const std::string spheres = std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_spheres.toml";
  const std::string args = " --threads 1 --set grid.shape_function=linear --set grid.scheme=usl";
  const fs::path one = scratch("ranks_fail_one"), spread = scratch("ranks_fail_spread");
  const fs::path log = scratch("ranks_fail_log.txt");
  std::string err;
  ASSERT_EQ(run("run " + spheres + " --out " + one.string() + args, &err), 3);
  ASSERT_EQ(on_ranks(2, "run " + spheres + " --out " + spread.string() + args, log), 3)
      << read(log);
  const std::string said = read(log);
  const auto failing_step = [](const std::string& text) {
    const auto at = text.find("the run failed: step ");
    return at == std::string::npos ? std::string() : text.substr(at, text.find(',', at) - at);
  };
  EXPECT_FALSE(failing_step(err).empty()) << err;
  EXPECT_EQ(failing_step(said), failing_step(err)) << said;
  for (const char* part : {"particle ", "(body '", "non-positive volume", "failure.h5"})
    EXPECT_NE(said.find(part), std::string::npos) << part << " in: " << said;
  EXPECT_EQ(said.find("MPI_ABORT"), std::string::npos) << said;
  EXPECT_TRUE(fs::exists(spread / "failure.h5"));
  EXPECT_EQ(fs::file_size(spread / "failure.h5"), fs::file_size(one / "failure.h5"));
}

}  // namespace
