// The points a hybrid's growing zone gets (driver::Hybrid::sample_ring): the small hybrid's panel
// (tests/driver/data/small_hybrid.toml: 0.5 mm facesheets sampled on the lattice, 0.1 mm core
// walls as point-type layers) cut to the ring between its 3 mm zone and a grown one: their volume,
// the facesheets' lattice, and the core walls' directions.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cases/run/bodies.hpp"
#include "cases/run/build_solver.hpp"
#include "cases/run/hybrid.hpp"
#include "cases/scene/scene.hpp"
#include "geometry/honeycomb.hpp"
#include "tests/support/sanitizers.hpp"

namespace hvi {
namespace {

const std::vector<std::string> growing = {"grid.upper=[\"7 mm\", \"7 mm\", \"3 mm\"]",
                                          "far_field.zone.grow.lower=[\"0 mm\", \"0 mm\"]",
                                          "far_field.zone.grow.upper=[\"6 mm\", \"6 mm\"]",
                                          "material.aluminium.library=Al5052",
                                          "material.aluminium.strength=johnson-cook",
                                          "material.aluminium.damage=johnson-cook"};

struct GrowingHybrid {
  scene::Scene scene = scene::load_scene(
      std::string(HVI_SOURCE_DIR) + "/tests/driver/data/small_hybrid.toml", growing);
  std::unique_ptr<mpm::Solver> solver = driver::make_solver(scene);
  driver::Hybrid hybrid{scene, *solver};
};

// The body's points over the in-plane box, one piece.
geometry::PointSet one_piece(const scene::Scene& s, std::size_t body,
                             const std::array<double, 4>& box) {
  const auto& clip = *s.bodies[body].clip;
  return driver::sample_body(
      s, body,
      *driver::make_body_solid(s, body,
                               {{box[0], box[1], clip.lower[2]}, {box[2], box[3], clip.upper[2]}}));
}

double sum(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0);
}

const std::array<double, 4> zone{0.0, 0.0, 3e-3, 3e-3}, grown{0.0, 0.0, 5e-3, 4e-3};

// Each body's ring points hold exactly the volume the zone gains: the grown zone's less the
// zone's (both sampled in one piece; the sampler gives every cut solid its exact volume, so this
// holds to round-off, 1e-12 relative), and lie in the ring.
TEST(ZoneGrowthSampling, TheRingHoldsTheVolumeTheZoneGains) {
  HVI_SKIP_UNDER_SANITIZERS(
      "62 s there; the sampling runs in ZoneGrowthSampling.CorePointsTakeTheirWallsDirection");
  GrowingHybrid s;
  ASSERT_EQ(s.scene.panels.size(), 1u);
  const auto boxes = coupling::ring(zone, grown);
  ASSERT_EQ(boxes.size(), 2u);  // above the zone along y, and beside it along x
  const std::vector<coupling::NewPoints> parts{s.hybrid.sample_ring(boxes, *s.solver)};
  for (std::size_t b = 1; b < 4; ++b) {  // front, core, rear (body 0 is the ball)
    double ring_volume = 0.0;
    std::size_t count = 0;
    for (const auto& part : parts)
      for (std::size_t k = 0; k < part.size(); ++k) {
        if (part.body[k] != static_cast<std::int64_t>(b)) continue;
        ring_volume += part.volume[k];
        ++count;
        const double x = part.position[3 * k], y = part.position[3 * k + 1];
        EXPECT_TRUE(x >= grown[0] && x <= grown[2] && y >= grown[1] && y <= grown[3]);
        EXPECT_FALSE(x < zone[2] && y < zone[3])
            << "a ring point inside the zone at " << x << ", " << y;
        EXPECT_EQ(part.material[k], static_cast<std::int64_t>(s.scene.bodies[b].material));
      }
    const double gained =
        sum(one_piece(s.scene, b, grown).volume) - sum(one_piece(s.scene, b, zone).volume);
    EXPECT_GT(count, 0u);
    EXPECT_NEAR(ring_volume / gained, 1.0, 1e-12) << s.scene.bodies[b].name;
  }
}

// The facesheets' lattice is anchored at the grid, so their ring points are exactly the grown
// zone's one-piece points outside the zone (the point-type core walls are not: a wall cut by a box
// edge ends there, so the ring's boxes split walls that one piece would not; their volume is
// checked above).
TEST(ZoneGrowthSampling, FacesheetPointsAreTheGrownZonesOutsideTheZone) {
  HVI_SKIP_UNDER_SANITIZERS(
      "60 s there; the sampling runs in ZoneGrowthSampling.CorePointsTakeTheirWallsDirection");
  GrowingHybrid s;
  for (const std::size_t b : {std::size_t{1}, std::size_t{3}}) {
    std::vector<std::array<double, 4>> ring_points, expected;
    const auto part = s.hybrid.sample_ring(coupling::ring(zone, grown), *s.solver);
    for (std::size_t k = 0; k < part.size(); ++k)
      if (part.body[k] == static_cast<std::int64_t>(b))
        ring_points.push_back({part.position[3 * k], part.position[3 * k + 1],
                               part.position[3 * k + 2], part.volume[k]});
    const auto whole = one_piece(s.scene, b, grown);
    for (std::size_t k = 0; k < whole.size(); ++k)
      if (!(whole.position[3 * k] < zone[2] && whole.position[3 * k + 1] < zone[3]))
        expected.push_back({whole.position[3 * k], whole.position[3 * k + 1],
                            whole.position[3 * k + 2], whole.volume[k]});
    std::sort(ring_points.begin(), ring_points.end());
    std::sort(expected.begin(), expected.end());
    ASSERT_EQ(ring_points.size(), expected.size()) << s.scene.bodies[b].name;
    for (std::size_t k = 0; k < expected.size(); ++k)
      for (int d = 0; d < 4; ++d) EXPECT_NEAR(ring_points[k][d], expected[k][d], 1e-15) << k;
  }
}

// The core's ring points carry the direction of the wall they lie in, for the take-over's wall
// stress (coupling/zone_growth.hpp); the facesheets' carry none. Checked against the pattern's own
// wall list: every core point away from a junction (its nearest wall nearer by 1 um than any wall
// of another family) takes the family and the direction of its nearest wall's mid-line.
TEST(ZoneGrowthSampling, CorePointsTakeTheirWallsDirection) {
  GrowingHybrid s;
  const auto part = s.hybrid.sample_ring(coupling::ring(zone, grown), *s.solver);
  ASSERT_EQ(part.wall_direction.size(), 2 * part.size());
  const geometry::HexPattern pattern(driver::panel_geometry(s.scene.panels[0]));
  const auto walls = pattern.walls({-1e-3, -1e-3}, {grown[2] + 1e-3, grown[3] + 1e-3});
  std::size_t checked = 0, core = 0;
  for (std::size_t k = 0; k < part.size(); ++k) {
    const double tx = part.wall_direction[2 * k], ty = part.wall_direction[2 * k + 1];
    if (part.body[k] != 2) {
      EXPECT_EQ(tx, 0.0);
      EXPECT_EQ(ty, 0.0);
      continue;
    }
    ++core;
    EXPECT_NEAR(std::hypot(tx, ty), 1.0, 1e-12);
    const geometry::Point2 p{part.position[3 * k], part.position[3 * k + 1]};
    std::array<double, 3> nearest{1.0, 1.0, 1.0};  // per family, m
    std::array<geometry::Point2, 3> along{};
    for (const auto& w : walls) {
      const double dx = w.b[0] - w.a[0], dy = w.b[1] - w.a[1], L2 = dx * dx + dy * dy;
      const double u = std::clamp(((p[0] - w.a[0]) * dx + (p[1] - w.a[1]) * dy) / L2, 0.0, 1.0);
      const double d = std::hypot(p[0] - w.a[0] - u * dx, p[1] - w.a[1] - u * dy);
      if (d < nearest[w.family]) {
        nearest[w.family] = d;
        along[w.family] = {dx / std::sqrt(L2), dy / std::sqrt(L2)};
      }
    }
    const auto f = static_cast<std::size_t>(std::min_element(nearest.begin(), nearest.end()) -
                                            nearest.begin());
    bool clear = true;
    for (std::size_t g = 0; g < 3; ++g) clear = clear && (g == f || nearest[g] > nearest[f] + 1e-6);
    if (!clear) continue;
    ++checked;
    EXPECT_NEAR(std::abs(tx * along[f][0] + ty * along[f][1]), 1.0, 1e-12) << p[0] << ", " << p[1];
  }
  EXPECT_GT(core, 100u);
  EXPECT_GT(checked, core / 2);
}

}  // namespace
}  // namespace hvi
