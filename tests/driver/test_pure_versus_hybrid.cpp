// Long tier (about 2.5 min on 2 threads): the hybrid's far field carries the panel's flexure as
// the all-MPM panel does. cases/hybrid's 1 g sphere on the 60 x 60 mm panel, all material points
// (panel_60mm_mpm.toml) and hybrid (panel_60mm_hybrid.toml: an MPM zone 2 d_p across, finite
// elements beyond), at 200 m/s instead of 2.2 or 4.5 km/s: it punches a 10.2 mm plug out of the
// front sheet and stops in the core (rear sheet NP, bulging 0.17 mm), so nothing fails near the
// probe (the far field's plastic strain stays below 0.2%) and what is compared is the far field
// alone; at 2.2 km/s the rear sheet tears to within 8 mm of the probe
// (docs/verification/pure_vs_hybrid.md).
//
// The plug's hole D_f agrees within the 5% (measured -0.7%), both rear sheets hold, and
// the rear facesheet's deflection 20 mm from the axis, along x and along y, agrees within the
// issue's 10% at 30, 35 and 40 us, once the flexural wave has reached the probe (measured at
// d232b8c: the hybrid 0.2-6.2% deeper). Not before: at 20 us the probe sits on the wave's rising
// front (-12.5 um at 20 us, -31 um at 25 us: 3.7 um/us), where 10% of the deflection is a third of
// a microsecond of arrival time, and the hybrid reads 10-14% deeper there. A precursor before
// the main wave (under 0.6 um at 6-10 us, half that on 0.2 mm cells) the far field carries only
// in part.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/run_hvi.hpp"

namespace {

namespace fs = std::filesystem;
using namespace hvi::test;  // the run helpers of tests/support/run_hvi.hpp

// What a run of the pair leaves: its probes.csv (columns step, time, deflection_20mm along x,
// deflection_20mm_y) and its measured holes.
struct PairRun {
  std::vector<std::vector<double>> rows;
  double front_hole = 0;       // D_f, m
  double rear_perforated = 0;  // 1 or 0
  // The probe in `column` at time t, linear between the rows around it.
  double at(double t, std::size_t column) const {
    for (std::size_t k = 1; k < rows.size(); ++k)
      if (rows[k][1] >= t) {
        const double w = (t - rows[k - 1][1]) / (rows[k][1] - rows[k - 1][1]);
        return (1 - w) * rows[k - 1][column] + w * rows[k][column];
      }
    return std::nan("");
  }
};

PairRun run_case(const std::string& file, const std::string& name) {
  const fs::path out = scratch(name);
  const std::string sets =
      " --threads 2 --set 'body.projectile.velocity=[\"0 m/s\", \"0 m/s\", \"-200 m/s\"]'"
      " --set run.end_time=40us --set output.interval=20us";
  EXPECT_EQ(run("run " + std::string(HVI_SOURCE_DIR) + "/cases/hybrid/" + file + " --out " +
                out.string() + sets),
            0);
  std::string header;
  PairRun r{csv_rows(out / "probes.csv", &header), summary_number(out, "D_f"),
            summary_number(out, "rear_perforated")};
  EXPECT_EQ(header, "step,time,deflection_20mm,deflection_20mm_y");
  fs::remove_all(out);
  return r;
}

TEST(PureVersusHybridLong, FarFieldDeflectionFollowsTheAllMpmPanel) {
  const PairRun pure = run_case("panel_60mm_mpm.toml", "pure_200");
  const PairRun hybrid = run_case("panel_60mm_hybrid.toml", "hybrid_200");
  // The hole target, 5%, on the plug the sphere punches (measured 10.25 and 10.18 mm);
  // the rear sheet holds in both.
  std::printf("D_f: pure %.3f mm, hybrid %.3f mm\n", pure.front_hole * 1e3,
              hybrid.front_hole * 1e3);
  EXPECT_NEAR(hybrid.front_hole, pure.front_hole, 0.05 * pure.front_hole);
  EXPECT_EQ(pure.rear_perforated, 0.0);
  EXPECT_EQ(hybrid.rear_perforated, 0.0);
  for (const double t : {30e-6, 35e-6, 40e-6})
    for (const std::size_t column : {2, 3}) {
      const double p = pure.at(t, column), h = hybrid.at(t, column);
      std::printf("t = %.0f us, %s: pure %.2f um, hybrid %.2f um (%+.1f%%)\n", t * 1e6,
                  column == 2 ? "along x" : "along y", p * 1e6, h * 1e6, 100 * (h - p) / p);
      // The flexural wave has arrived: the panel sinks tens of micrometres there.
      EXPECT_LT(p, -30e-6);
      EXPECT_LT(std::fabs(h - p), 0.10 * std::fabs(p)) << "t = " << t << ", column " << column;
    }
}

}  // namespace
