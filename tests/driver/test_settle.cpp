// Stopping a run once its rear sheet has settled (measure.<holes>.stop_when_settled,
// cases/run/settle.hpp): the criterion on made-up histories, and a run that stops so, whose every
// snapshot is the full run's, also when it was interrupted before it settled and resumed.
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cases/cli/child_run.hpp"
#include "cases/run/settle.hpp"
#include "tests/support/run_hvi.hpp"

namespace {

using hvi::driver::RearState;
using hvi::driver::SettleCheck;
using namespace hvi::test;
constexpr double us = 1e-6, mm = 1e-3;

RearState hole(double t_us, double D_mm) {
  return {.time = t_us * us, .hole = true, .D = D_mm * mm, .equivalent = 0.9 * D_mm * mm};
}
RearState bulge(double t_us, double b_mm) {
  return {.time = t_us * us, .bulge = b_mm * mm};
}

// A hole that stops growing: settled once every snapshot of the last 3 us is within 2% of the
// newest, and not before the window is covered by snapshots.
TEST(Settle, AHoleHasSettledWhenItStoppedGrowingForTheWindow) {
  SettleCheck c(3 * us, 0.02);
  for (auto [t, D] :
       {std::pair{10.0, 4.2}, {11.0, 4.4}, {12.0, 4.8}, {13.0, 4.88}, {14.0, 4.9}, {15.0, 4.9}})
    c.add(hole(t, D));
  EXPECT_FALSE(c.settled());  // 12 us: 4.8 mm is 2.04% below 4.9 mm
  c.add(hole(16.0, 4.9));     // 13 to 16 us: all within 0.4%
  ASSERT_TRUE(c.settled());
  EXPECT_NE(c.settled()->find("P, D_r 4.900 mm"), std::string::npos) << *c.settled();
}

// Without a hole the deepest point of the sheet must have come to rest once the cloud has reached
// it: a sheet untouched, or bent microns by the wave the walls carry ahead of the cloud (a bulge
// under a quarter of its thickness), is never settled, however long it waits.
TEST(Settle, ASheetWithoutAHoleHasSettledWhenItsBulgeStopped) {
  SettleCheck untouched(2 * us, 0.02);
  for (int t = 0; t <= 10; ++t) untouched.add(bulge(t, 0.0));
  EXPECT_FALSE(untouched.settled());
  SettleCheck precursor(2 * us, 0.02);
  for (int t = 0; t <= 10; ++t) {
    RearState s = bulge(t, 0.006);
    s.thickness = 0.4 * mm;
    precursor.add(s);
  }
  EXPECT_FALSE(precursor.settled());
  SettleCheck c(2 * us, 0.02);
  for (auto [t, b] : {std::pair{10.0, 0.30}, {11.0, 0.42}, {12.0, 0.455}, {13.0, 0.46}}) {
    RearState s = bulge(t, b);
    s.thickness = 0.4 * mm;
    c.add(s);
  }
  EXPECT_FALSE(c.settled());  // 11 us: 0.42 mm is 8.7% below
  RearState last = bulge(14.0, 0.46);
  last.thickness = 0.4 * mm;
  c.add(last);
  ASSERT_TRUE(c.settled());  // 12 to 14 us within 1.1%, and 0.46 mm over t_r / 4
  EXPECT_NE(c.settled()->find("NP, bulge 0.460 mm"), std::string::npos) << *c.settled();
}

// A change of outcome inside the window (the hole opening, spall coming off a whole sheet) restarts
// the wait; spall beside a hole, there or gone, changes nothing.
TEST(Settle, AChangeOfOutcomeInTheWindowIsNotSettled) {
  SettleCheck c(2 * us, 0.05);
  c.add(bulge(10.0, 0.5));
  c.add(bulge(11.0, 0.5));
  c.add(hole(12.0, 1.0));
  c.add(hole(13.0, 1.0));
  EXPECT_FALSE(c.settled());  // the window reaches back to 11 us, NP then
  c.add(hole(14.0, 1.0));
  EXPECT_TRUE(c.settled());
  RearState spall = hole(15.0, 1.0);
  spall.spall = true;
  c.add(spall);
  EXPECT_TRUE(c.settled());
  SettleCheck whole(2 * us, 0.05);
  for (double t : {10.0, 11.0, 12.0}) whole.add(bulge(t, 0.5));
  EXPECT_TRUE(whole.settled());
  RearState off = bulge(13.0, 0.5);
  off.spall = true;
  whole.add(off);
  EXPECT_FALSE(whole.settled());
  for (double t : {14.0, 15.0}) {
    off.time = t * us;
    whole.add(off);
  }
  ASSERT_TRUE(whole.settled());
  EXPECT_NE(whole.settled()->find("P by detached spall, bulge 0.500 mm"), std::string::npos);
}

// A resumed run reads the states back from its holes_history.csv; a file that is not one is an
// error that names it.
TEST(Settle, ReadsAHistoryBack) {
  const fs::path dir = scratch("settle_history");
  fs::create_directories(dir);
  std::ofstream(dir / "h.csv")
      << "run,time,step,rear_perforated,D_r,D_r_equivalent,bulge,rear_spall_particles\n"
         "a,0,0,false,,,0,0\n"
         "a,1e-06,10,true,0.0049,0.0045,,3\n"
         "a,2e-06,20,true,0.0049,0.0045,,3\n";
  SettleCheck c(1 * us, 0.01);
  c.load(dir / "h.csv");
  ASSERT_TRUE(c.settled());
  EXPECT_NE(c.settled()->find("D_r 4.900 mm (equivalent 4.500 mm)"), std::string::npos);
  std::ofstream(dir / "bad.csv") << "run,time\na,0\n";
  try {
    c.load(dir / "bad.csv");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv: not a holes history"), std::string::npos);
  }
}

// A 4 mm sphere at 4.5 km/s through the demo's panel with a 4 mm core, on 0.8 mm cells, a snapshot
// every 0.5 us (about 7 s a run): the rear hole grows to 26.4 mm by 8 us and to 27.5 mm by 10 us.
// Stopped when settled over 1 us within 5%, the run ends at 8 us, the first snapshot whose last
// microsecond of snapshots lies within 5% of it, as "settled"; each snapshot it wrote is the full
// run's, and its hole is the full run's at that time, and a sweep counts it finished. Interrupted
// before it settles and resumed on another thread count, it stops at the same step; hvi settled
// finds that step in the full run.
TEST(Settle, ARunStopsOnceItsRearHoleHasSettledAtTheFullRunsState) {
  std::string scene = " ";
  scene += HVI_SOURCE_DIR;
  scene +=
      "/cases/demo.toml"
      " --set 'grid.cell_size=0.8 mm' --set 'output.interval=0.5 us' --set 'run.end_time=10 us'"
      " --set 'measure.holes.history=true' --set 'body.projectile.sphere.radius=2 mm'"
      " --set 'body.projectile.sphere.center=[\"0 mm\",\"0 mm\",\"2.2 mm\"]'"
      " --set 'panel.panel.core_height=4 mm'";
  const std::string stop =
      " --set 'measure.holes.stop_when_settled=1 us' --set measure.holes.settle_tolerance=0.05";
  const fs::path full = scratch("settle_full"), settled = scratch("settle_stopped"),
                 resumed = scratch("settle_resumed");
  ASSERT_EQ(run("run" + scene + " --threads 2 --out " + full.string()), 0);
  ASSERT_EQ(run("run" + scene + stop + " --threads 2 --out " + settled.string()), 0);
  const std::string summary = read(settled / "summary.toml");
  EXPECT_NE(summary.find("status = 'settled'"), std::string::npos) << summary;
  EXPECT_NE(summary.find("within 5% over the last 1 us"), std::string::npos) << summary;
  // A settled run ended as it should: a sweep (and a ballistic-limit search) counts it done.
  EXPECT_TRUE(hvi::driver::read_run_summary(settled).finished());
  const double t = summary_number(settled, "time");
  EXPECT_LT(t, 0.85 * summary_number(full, "time"));
  int snapshots = 0;
  for (const auto& f : fs::directory_iterator(settled / "snapshots")) {
    EXPECT_TRUE(read(f.path()) == read(full / "snapshots" / f.path().filename()))
        << f.path().filename();
    ++snapshots;
  }
  EXPECT_GE(snapshots, 15);
  // The stopped run's hole is the full run's row at its end time.
  const std::string history = read(full / "holes_history.csv");
  const std::string last_row = read(settled / "holes_history.csv");
  const std::string tail = last_row.substr(last_row.rfind('\n', last_row.size() - 2) + 1);
  EXPECT_NE(history.find(tail.substr(tail.find(','))), std::string::npos) << tail;
  const double D_r = summary_number(settled, "D_r");
  EXPECT_NEAR(D_r / summary_number(full, "D_r"), 1.0, 0.05);  // 26.4 mm against 27.5 mm

  // hvi settled replays the criterion on the full run's history: the stopped run's step.
  std::string replay;
  ASSERT_EQ(run("settled " + full.string() + " --window 1us --tolerance 0.05", nullptr, &replay),
            0);
  const std::string step =
      fmt::format("step {} of {}", summary_number(settled, "steps"), summary_number(full, "steps"));
  EXPECT_NE(replay.find(step), std::string::npos) << replay << " against " << step;

  ASSERT_EQ(
      run("run" + scene + stop + " --threads 2 --set run.max_steps=150 --out " + resumed.string()),
      0);
  EXPECT_NE(read(resumed / "summary.toml").find("status = 'stopped'"), std::string::npos);
  ASSERT_EQ(run("run --resume " + resumed.string() + " --threads 1 --set run.max_steps=0"), 0);
  EXPECT_EQ(summary_number(resumed, "steps"), summary_number(settled, "steps"));
  expect_same_output(settled, resumed, snapshots);
}

}  // namespace
