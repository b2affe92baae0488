// The honeycomb panel: the cell pattern follows eq. (6), the wall list matches a hand count, a
// point of a wall finds its family and direction, the core volume equals the closed-form solidity
// for the paper's two panels, the analytic inside test agrees with the CGAL surface, and every
// generated body is a closed solid boundary.
#include <cmath>
#include <iostream>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "geometry/honeycomb.hpp"
#include "geometry/mesh_solid.hpp"
#include "geometry/surface.hpp"

namespace hvi::geometry {
namespace {

const double sqrt3 = std::sqrt(3.0);
constexpr double mm = 1e-3;

// The study panel of Section 4 (t_hc = 0.05 mm, D_hc = 3.0 mm, S = 14.2 mm) over an extent.
HoneycombPanel study_panel(Point2 lower, Point2 upper) {
  HoneycombPanel p;
  p.front_thickness = 0.5 * mm;
  p.rear_thickness = 0.5 * mm;
  p.wall_thickness = 0.05 * mm;
  p.cell_diameter = 3.0 * mm;
  p.core_height = 14.2 * mm;
  p.lower = lower;
  p.upper = upper;
  p.top = 0.0;
  return p;
}

// The validation panel of Section 3 (Turner: t_hc = 0.178 mm as the paper's text, D_hc = 4.76 mm,
// S = 35 mm, t_f = 0.5 mm, t_r = 0.4 mm).
HoneycombPanel validation_panel(Point2 lower, Point2 upper, double t_hc = 0.178 * mm) {
  HoneycombPanel p = study_panel(lower, upper);
  p.front_thickness = 0.5 * mm;
  p.rear_thickness = 0.4 * mm;
  p.wall_thickness = t_hc;
  p.cell_diameter = 4.76 * mm;
  p.core_height = 35 * mm;
  return p;
}

TEST(HexPattern, CentresFollowEquation6) {
  HoneycombPanel p = study_panel({-10 * mm, -10 * mm}, {10 * mm, 10 * mm});
  const double D = p.cell_diameter;
  for (const double rotation_deg : {0.0, 30.0, 17.0}) {
    p.rotation = rotation_deg * std::acos(-1.0) / 180.0;
    p.pattern_origin = {1.0 * mm, -2.0 * mm};
    const HexPattern pattern(p);
    const auto centres = pattern.centers(p.lower, p.upper);
    ASSERT_GT(centres.size(), 40u);
    for (const auto& c : centres) {
      // In the pattern frame: x_c = n D/2, y_c = m sqrt(3) D/2, n and m of the same parity, i.e.
      // eq. (6) with n = 2 n_x (+1) and m = 2 n_y (+1). Round-off of the rotation: 1e-12 D.
      const Point2 q = pattern.to_pattern(c);
      const double n = q[0] / (D / 2), m = q[1] / (sqrt3 * D / 2);
      EXPECT_NEAR(n, std::round(n), 1e-9);
      EXPECT_NEAR(m, std::round(m), 1e-9);
      EXPECT_EQ((std::lround(n) + std::lround(m)) % 2, 0) << n << " " << m;
      // Each centre's nearest neighbours are exactly D away (flat-to-flat distance).
      double nearest = 1e9;
      for (const auto& o : centres)
        if (&o != &c) nearest = std::min(nearest, std::hypot(o[0] - c[0], o[1] - c[1]));
      EXPECT_NEAR(nearest, D, 1e-12);
    }
    // The cell at the pattern origin.
    bool found = false;
    for (const auto& c : centres) found |= std::hypot(c[0] - 1.0 * mm, c[1] + 2.0 * mm) < 1e-15;
    EXPECT_TRUE(found);
  }
}

TEST(HexPattern, OriginAtVertexOrWall) {
  HoneycombPanel p = study_panel({-5 * mm, -5 * mm}, {5 * mm, 5 * mm});
  p.origin_at = PatternOrigin::vertex;
  const auto walls = HexPattern(p).walls(p.lower, p.upper);
  int meeting = 0;  // three walls meet at the origin
  for (const auto& w : walls)
    meeting += (std::hypot(w.a[0], w.a[1]) < 1e-15) + (std::hypot(w.b[0], w.b[1]) < 1e-15);
  EXPECT_EQ(meeting, 3);
  p.origin_at = PatternOrigin::wall;
  int through = 0;  // the origin is the middle of one wall
  for (const auto& w : HexPattern(p).walls(p.lower, p.upper))
    through += std::hypot((w.a[0] + w.b[0]) / 2, (w.a[1] + w.b[1]) / 2) < 1e-15;
  EXPECT_EQ(through, 1);
}

// Hand count (D = 3 mm, a cell centre at the origin, extent 4 mm x 2 mm): the six walls of the
// centre cell (its vertices are at (+-1.5, +-0.87) and (0, +-1.73) mm; the slanted walls cross
// y = +-1), plus the two slanted walls of each side neighbour (centres (+-3, 0)) that leave the
// vertices (+-1.5, +-0.87) outwards and reach y = +-1 at x = +-1.73 mm: 10 walls. Walls of the
// rows above and below (centres (+-1.5, +-2.6)) start at y = +-0.87 only at those same vertices
// and are the ones already counted.
TEST(HexPattern, WallCountMatchesHandCount) {
  const HoneycombPanel p = study_panel({-2 * mm, -1 * mm}, {2 * mm, 1 * mm});
  const auto walls = HexPattern(p).walls(p.lower, p.upper);
  EXPECT_EQ(walls.size(), 10u);
  int cut = 0;  // walls crossing y = +-1 mm: 4 of the centre cell, 4 of the neighbours
  for (const auto& w : walls) cut += !w.junction_a + !w.junction_b;
  EXPECT_EQ(cut, 8);
  // Over a larger extent every wall is listed once: no two walls share both ends.
  const HoneycombPanel big = study_panel({-20 * mm, -20 * mm}, {20 * mm, 20 * mm});
  const auto many = HexPattern(big).walls(big.lower, big.upper);
  for (std::size_t i = 0; i < many.size(); ++i)
    for (std::size_t j = i + 1; j < many.size(); ++j) {
      const bool same =
          std::hypot(many[i].a[0] - many[j].a[0], many[i].a[1] - many[j].a[1]) < 1e-12 &&
          std::hypot(many[i].b[0] - many[j].b[0], many[i].b[1] - many[j].b[1]) < 1e-12;
      ASSERT_FALSE(same) << i << " " << j;
    }
}

// Each wall's family and direction, as the take-over of a growing MPM zone gives its core points
// (coupling/zone_growth.hpp): every point of a wall, away from its junctions, finds that wall's
// family, and the direction is parallel to its mid-line, at any rotation of the pattern.
TEST(HexPattern, APointOfAWallFindsItsFamilyAndDirection) {
  for (const double rotation : {0.0, std::numbers::pi / 2, 0.3}) {
    HoneycombPanel p = study_panel({-10 * mm, -10 * mm}, {10 * mm, 10 * mm});
    p.rotation = rotation;
    p.pattern_origin = {0.37 * mm, -0.21 * mm};
    const HexPattern pattern(p);
    const auto walls = pattern.walls({-6 * mm, -6 * mm}, {6 * mm, 6 * mm});
    ASSERT_GT(walls.size(), 40u);
    for (const auto& w : walls) {
      const double length = std::hypot(w.b[0] - w.a[0], w.b[1] - w.a[1]);
      const Point2 along{(w.b[0] - w.a[0]) / length, (w.b[1] - w.a[1]) / length};
      const Point2 t = pattern.wall_direction(w.family);
      EXPECT_NEAR(std::hypot(t[0], t[1]), 1.0, 1e-15);
      EXPECT_NEAR(std::abs(t[0] * along[0] + t[1] * along[1]), 1.0, 1e-12) << rotation;
      // Points at a quarter, half and three quarters of the mid-line, and off it by +-0.4 of the
      // half thickness, all find the wall's family.
      for (const double s : {0.25, 0.5, 0.75})
        for (const double off : {-0.4, 0.0, 0.4}) {
          const double o = off * pattern.half_thickness(w.family);
          const Point2 x{w.a[0] + s * (w.b[0] - w.a[0]) - o * along[1],
                         w.a[1] + s * (w.b[1] - w.a[1]) + o * along[0]};
          EXPECT_EQ(pattern.wall_family(x), w.family) << rotation << " " << s << " " << off;
        }
    }
  }
  // At rotation 0 the ribbon walls (family 0, normal to x) run along y.
  const HexPattern plain(study_panel({-1 * mm, -1 * mm}, {1 * mm, 1 * mm}));
  EXPECT_NEAR(std::abs(plain.wall_direction(0)[1]), 1.0, 1e-15);
  EXPECT_EQ(plain.wall_family({1.5 * mm, 0.1 * mm}), 0);
}

// Core volume of the walls by hand: mid-line length x thickness x height, minus the junction
// overlap (sqrt 3 / 4) t^2 per junction vertex inside the extent (three walls of thickness t
// meeting at 120 degrees cover sqrt(3)/4 t^2 less than their three half-lengths' strips).
double hand_core_volume(const HoneycombPanel& p) {
  double area = 0.0;
  int junction_ends = 0;
  for (const auto& w : HexPattern(p).walls(p.lower, p.upper)) {
    area += std::hypot(w.b[0] - w.a[0], w.b[1] - w.a[1]) * w.thickness;
    junction_ends += w.junction_a + w.junction_b;
  }
  const double t = p.wall_thickness;
  return p.core_height * (area - junction_ends / 3.0 * sqrt3 / 4 * t * t);
}

TEST(HoneycombCore, VolumeEqualsClosedFormSolidityForThePapersPanels) {
  for (const bool validation : {false, true}) {
    const double D = validation ? 4.76 * mm : 3.0 * mm;
    // A whole number of pattern periods (D along x, sqrt(3) D along y), anywhere: the closed
    // form solidity x area x S holds exactly. (Offset so that no wall runs along an edge.)
    const Point2 lower{0.1 * D, 0.2 * D};
    const Point2 size{(validation ? 8 : 12) * D, (validation ? 3 : 4) * sqrt3 * D};
    const Point2 upper{lower[0] + size[0], lower[1] + size[1]};
    const HoneycombPanel p =
        validation ? validation_panel(lower, upper) : study_panel(lower, upper);
    const HoneycombCore core(p, p.core_box());
    const double closed_form =
        honeycomb_solidity(D, p.wall_thickness, false) * size[0] * size[1] * p.core_height;
    const SurfaceCheck check = check_surface(core.surface());
    ASSERT_TRUE(check.ok()) << check.problem();
    std::cout << (validation ? "validation" : "study") << " panel core, " << size[0] / mm << " x "
              << size[1] / mm << " mm: closed form " << closed_form
              << " m^3; exact (CGAL plan) / closed form - 1 = " << core.volume() / closed_form - 1
              << ", mesh / closed form - 1 = " << check.volume / closed_form - 1
              << ", hand count / closed form - 1 = " << hand_core_volume(p) / closed_form - 1
              << "\n";
    // Tolerance: 0.1 % as the issue asks; plan area and mesh volume agree with it to round-off.
    EXPECT_NEAR(core.volume() / closed_form, 1.0, 1e-3);
    EXPECT_NEAR(check.volume / closed_form, 1.0, 1e-3);
    EXPECT_NEAR(hand_core_volume(p) / closed_form, 1.0, 1e-3);
  }
  // The paper's own extents, which are not whole periods (the 1 g study half model, 36 x 18 mm,
  // and a 40 x 40 mm validation panel): against the hand count of the clipped walls.
  for (const bool validation : {false, true}) {
    const HoneycombPanel p = validation ? validation_panel({-20 * mm, -20 * mm}, {20 * mm, 20 * mm})
                                        : study_panel({-18 * mm, 0}, {18 * mm, 18 * mm});
    const HoneycombCore core(p, p.core_box());
    const double hand = hand_core_volume(p);
    std::cout << (validation ? "validation" : "study") << " panel core, paper extent: exact "
              << core.volume() << " m^3, hand count " << hand
              << " m^3, exact / hand - 1 = " << core.volume() / hand - 1 << "\n";
    EXPECT_NEAR(core.volume() / hand, 1.0, 1e-3);
  }
}

TEST(HoneycombCore, TurnersFoilAndDoubleWalls) {
  const double D = 4.76 * mm;
  const Point2 upper{6 * D, 2 * sqrt3 * D};
  for (const double t : {0.178 * mm, 0.0178 * mm})  // the paper's text, and Turner's 0.0007 in foil
    for (const bool doubled : {false, true}) {
      HoneycombPanel p = validation_panel({0, 0}, upper, t);
      p.double_walls = doubled;
      const HoneycombCore core(p, p.core_box());
      const double closed_form =
          honeycomb_solidity(D, t, doubled) * upper[0] * upper[1] * p.core_height;
      EXPECT_NEAR(core.volume() / closed_form, 1.0, 1e-9) << t << " " << doubled;
      const SurfaceCheck check = check_surface(core.surface());
      EXPECT_TRUE(check.ok()) << check.problem();
      EXPECT_NEAR(check.volume / closed_form, 1.0, 1e-9);
    }
  // Single walls: solidity (2 t / D)(1 - t / (2 D)) (Gibson & Ashby with l = D / sqrt 3).
  EXPECT_NEAR(honeycomb_solidity(3e-3, 5e-5, false), 2 * 5e-5 / 3e-3 * (1 - 5e-5 / 6e-3), 1e-15);
  // Double walls add one more t on a third of the walls: to first order 2t/D + (2/3)(t/D)... the
  // exact value is checked against the CGAL plan above; here it only has to exceed single walls.
  EXPECT_GT(honeycomb_solidity(3e-3, 5e-5, true), honeycomb_solidity(3e-3, 5e-5, false));
}

// The analytic inside test (nearest cell, shrunk hexagon) and the CGAL surface (2D booleans,
// triangulation, extrusion) describe the same solid: they agree at random points, for a rotated
// pattern with double walls cut by a clip box.
// A rear gap (the diagnosis of the rear sheet's bond, issue #83) ends the core that far above the
// rear facesheet, which stays where it was: the core's volume shrinks by the gap's share.
TEST(HoneycombCore, ARearGapLiftsTheCoresFootOffTheRearSheet) {
  HoneycombPanel p = validation_panel({-6 * mm, -6 * mm}, {6 * mm, 6 * mm}, 0.01778 * mm);
  const HoneycombCore standing(p, p.core_box());
  p.rear_gap = 0.4 * mm;
  const HoneycombCore lifted(p, p.core_box());
  EXPECT_NEAR(p.core_box().lower[2], p.rear_box().upper[2] + 0.4 * mm, 1e-15);
  EXPECT_DOUBLE_EQ(p.rear_box().upper[2], -(0.5 + 35) * mm);
  EXPECT_NEAR(lifted.volume() / standing.volume(), (35.0 - 0.4) / 35.0, 1e-12);
  EXPECT_FALSE(lifted.contains({4.76 / 2 * mm, 0.0, p.rear_box().upper[2] + 0.2 * mm}));
  EXPECT_TRUE(standing.contains({4.76 / 2 * mm, 0.0, p.rear_box().upper[2] + 0.2 * mm}));
}

TEST(HoneycombCore, InsideTestAgreesWithTheSurface) {
  HoneycombPanel p = validation_panel({-6 * mm, -5 * mm}, {7 * mm, 6 * mm});
  p.rotation = 0.3;
  p.double_walls = true;
  p.pattern_origin = {0.4 * mm, 0.1 * mm};
  const Bounds clip{{-10 * mm, 0.0, -20 * mm}, {10 * mm, 10 * mm, 0.0}};
  const PanelSolids panel = make_panel(p, &clip);
  const MeshSolid mesh(panel.core->surface());
  EXPECT_NEAR(mesh.volume() / panel.core->volume(), 1.0, 1e-9);
  std::mt19937_64 rng(7);
  const Bounds b = panel.core->bounds();
  int inside = 0;
  for (int i = 0; i < 20000; ++i) {
    Point x;
    for (int d = 0; d < 3; ++d)
      x[d] = std::uniform_real_distribution<double>(b.lower[d], b.upper[d])(rng);
    inside += panel.core->contains(x);
    EXPECT_EQ(panel.core->contains(x), mesh.contains(x)) << x[0] << " " << x[1] << " " << x[2];
  }
  // About the solidity of the double-walled pattern (~0.11) of the points fall in walls.
  EXPECT_GT(inside, 1000);
}

// Quarter models of Turner's shots (docs/verification/paper_cases.md, "A quarter model halves a
// shot's cost") rest on this: with a cell centre on the impact axis and the pattern turned by a
// multiple of 30 degrees, the planes x = 0 and y = 0 are mirror planes of the core, so a quarter of
// the panel holds exactly a quarter of its walls. A turn of 15 degrees breaks the x = 0 mirror (the
// negative control).
TEST(HexPattern, CellCentreAxesAreMirrorPlanesAtMultiplesOf30Degrees) {
  const double turns[] = {0.0, 30.0, 60.0, 90.0, 15.0};
  for (const double degrees : turns) {
    HoneycombPanel p = validation_panel({-10 * mm, -10 * mm}, {10 * mm, 10 * mm}, 0.0178 * mm);
    p.rotation = degrees * M_PI / 180.0;
    const HoneycombCore core(p, p.core_box());
    Bounds quarter = p.core_box();
    quarter.lower[0] = quarter.lower[1] = 0.0;
    const HoneycombCore quarter_core(p, quarter);
    // Mirror test at random points of the core's box: the inside test is exact (no mesh), so a
    // mirror image must answer the same unless the point lies within round-off of a wall face.
    std::mt19937_64 rng(11);
    const Bounds b = core.bounds();
    int mismatches = 0, inside = 0;
    for (int i = 0; i < 40000; ++i) {
      Point x;
      for (int d = 0; d < 3; ++d)
        x[d] = std::uniform_real_distribution<double>(b.lower[d], b.upper[d])(rng);
      const bool in = core.contains(x);
      inside += in;
      mismatches += in != core.contains({-x[0], x[1], x[2]});
      mismatches += in != core.contains({x[0], -x[1], x[2]});
    }
    std::cout << degrees << " degrees: " << inside << " of 40000 points in walls, " << mismatches
              << " mirror mismatches, quarter / whole = " << quarter_core.volume() / core.volume()
              << "\n";
    if (degrees == 15.0) {
      // Foil walls fill under 1% of the core, yet a broken mirror shows in over a thousand of the
      // 80,000 tests (1,162 with this seed); a hundred leaves room for another random sample.
      EXPECT_GT(mismatches, 100);
      continue;
    }
    EXPECT_GT(inside, 100) << degrees;  // the sample reaches the walls
    EXPECT_EQ(mismatches, 0) << degrees;
    // The quarter's walls: a quarter of the panel's, to the round-off of the planar booleans.
    EXPECT_NEAR(quarter_core.volume() / (core.volume() / 4), 1.0, 1e-12) << degrees;
  }
}

TEST(HoneycombPanel, EveryBodyIsAClosedSolidBoundary) {
  HoneycombPanel p = study_panel({-18 * mm, -18 * mm}, {18 * mm, 18 * mm});
  p.top = 1 * mm;
  for (const bool clipped : {false, true}) {
    const Bounds clip{{-20 * mm, 0.0, -1.0}, {20 * mm, 20 * mm, 1.0}};  // the half model y >= 0
    const PanelSolids panel = make_panel(p, clipped ? &clip : nullptr);
    for (const Solid* s : {panel.front.get(), panel.core.get(), panel.rear.get()}) {
      const SurfaceCheck check = check_surface(s->surface());
      EXPECT_TRUE(check.ok()) << check.problem();
      EXPECT_TRUE(check.bounds_volume && check.outward);
      EXPECT_NEAR(check.volume / s->volume(), 1.0, 1e-9);
    }
    // Layers: front [top - t_f, top], core below it, rear below the core.
    EXPECT_DOUBLE_EQ(panel.front->bounds().upper[2], 1 * mm);
    EXPECT_DOUBLE_EQ(panel.core->bounds().upper[2], panel.front->bounds().lower[2]);
    EXPECT_DOUBLE_EQ(panel.rear->bounds().upper[2], panel.core->bounds().lower[2]);
    EXPECT_NEAR(panel.rear->bounds().lower[2], (1 - 0.5 - 14.2 - 0.5) * mm, 1e-15);
  }
}

}  // namespace
}  // namespace hvi::geometry
