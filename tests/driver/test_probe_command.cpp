// hvi probe and hvi units end to end. On the small hybrid, run with a probe row every step, hvi
// probe at the run's own probe points (one on a far-field node, one on the rear facesheet's
// points in the MPM zone) gives the run's probes.csv values at every snapshot time: the far-field
// node's exactly, the points' mean to round-off. A point given badly, or a
// directory that is no run, is refused with exit code 2 and the reason; hvi units gives SI values
// and refuses a value of another dimension than the one expected.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_hvi.hpp"
#include "tests/support/scene_text.hpp"

namespace fs = std::filesystem;

namespace {

using namespace hvi::test;  // the run helpers of tests/support/run_hvi.hpp

const std::string hybrid = std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_hybrid.toml";

// The rows of a CSV text of numbers after its header.
std::vector<std::vector<double>> rows_of(const std::string& text) {
  const fs::path file = fs::path(testing::TempDir()) / "hvi_probe_rows.csv";
  std::ofstream(file) << text;
  return csv_rows(file);
}

// Every row of `probe` (time, u) equals the probes.csv row (step, time, u...) at its time, in
// column `column`, within `tolerance` m.
void expect_probe_rows(const std::vector<std::vector<double>>& probe,
                       const std::vector<std::vector<double>>& log, std::size_t column,
                       double tolerance) {
  ASSERT_EQ(probe.size(), 5u);  // t = 0, 1, 2, 3, 4 us
  for (const auto& row : probe) {
    const auto match =
        std::find_if(log.begin(), log.end(), [&](const auto& r) { return r[1] == row[0]; });
    ASSERT_NE(match, log.end()) << "no probes.csv row at t = " << row[0];
    EXPECT_NEAR(row[1], (*match)[column], tolerance) << "t = " << row[0];
  }
  EXPECT_GT(std::abs(probe.back()[1]), 1e-8);  // it moved
}

TEST(Probe, ReadsTheRunsOwnProbesAtItsSnapshots) {
  const fs::path dir = scratch("probe_hybrid");
  fs::create_directories(dir);
  std::ofstream(dir / "scene.toml") << read(hybrid) << "\n"
                                    << z_probe("zone_rear", R"(["1 mm", "1 mm", "-4 mm"])");
  const fs::path out = dir / "run";
  ASSERT_EQ(run("run " + (dir / "scene.toml").string() + " --out " + out.string() +
                " --threads 2 --set output.energy_every=1"),
            0);
  std::string header;
  const auto log = csv_rows(out / "probes.csv", &header);
  ASSERT_EQ(header, "step,time,rear_deflection,zone_rear");

  std::string csv, err;
  ASSERT_EQ(run("probe " + out.string() + " --point \"6 mm,0 mm,-4 mm\"", &err, &csv), 0) << err;
  EXPECT_NE(err.find("read the far-field node at 0.00629501, 0, -0.004 m"), std::string::npos)
      << err;
  const auto far = rows_of(csv);
  expect_probe_rows(far, log, 2, 0.0);  // the same node's displacement

  ASSERT_EQ(run("probe " + out.string() + " --point \"1 mm,1 mm,-4 mm\" --axis z", &err, &csv), 0)
      << err;
  EXPECT_NE(err.find("particles of body"), std::string::npos) << err;
  const auto zone = rows_of(csv);
  expect_probe_rows(zone, log, 3, 1e-15);  // the same mean, summed in another order
}

TEST(Probe, RefusesABadPointAndADirectoryThatIsNoRun) {
  std::string err;
  const fs::path empty = scratch("probe_empty");
  fs::create_directories(empty);
  EXPECT_EQ(run("probe " + empty.string() + " --point \"0 mm,20 furlongs,0\"", &err), 2);
  EXPECT_NE(err.find("--point '20 furlongs'"), std::string::npos) << err;
  EXPECT_EQ(run("probe " + empty.string() + " --point \"0 mm,2 mm\"", &err), 2);
  EXPECT_NE(err.find("expected three lengths X,Y,Z"), std::string::npos) << err;
  EXPECT_EQ(run("probe " + empty.string() + " --point \"0 mm,3 rad,0\"", &err), 2);
  EXPECT_NE(err.find("expected a length, got"), std::string::npos) << err;
  EXPECT_EQ(run("probe " + empty.string() + " --point \"0 mm,0 mm,0 mm\"", &err), 2);
  EXPECT_NE(err.find("scene.resolved.toml"), std::string::npos) << err;
}

TEST(Units, GivesSIValuesAndRefusesAnotherDimension) {
  std::string out, err;
  ASSERT_EQ(run("units \"-15.2 mm\" 20um \"4.5 km/s\" 0.3", &err, &out), 0) << err;
  EXPECT_EQ(out, "-0.0152\n2.0000000000000002e-05\n4500\n0.29999999999999999\n");
  EXPECT_EQ(run("units --expect length \"0.5 mm\" \"3 rad\"", &err, &out), 2);
  EXPECT_NE(err.find("hvi: '3 rad': expected a length, got a dimensionless number"),
            std::string::npos)
      << err;
  EXPECT_EQ(run("units \"2 furlongs\"", &err), 2);
  EXPECT_NE(err.find("hvi: '2 furlongs': "), std::string::npos) << err;
}

}  // namespace
