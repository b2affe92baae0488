// Hole measurement (paper Section 4.2, eqs. 8-11) on synthetic facesheets with holes of known
// shape. Two errors are told apart:
//  - the measurement error: the raster and ray march against the exact boundary of the union of
//    the particles' footprints along the same ray (footprint_union_distance); bounded by one
//    raster cell;
//  - the discretisation error of the particle set itself: a lattice of spacing h represents a
//    boundary only to within a footprint. If the hole is convex, the ray meets its boundary at an
//    angle alpha, and particles are kept when their centre is outside, the footprint-union boundary
//    lies within h / (sqrt(2) sin alpha) of the true one (a kept footprint reaches h / sqrt(2) from
//    its centre; alpha = 90 deg on a circle, on the axes of an ellipse and on the flats of a
//    hexagon, 60 deg at a hexagon's corner).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/facesheet.hpp"
#include "synthetic.hpp"

namespace hvi::analysis {
namespace {

using test::plate;

constexpr double mm = 1e-3;
constexpr double h = 0.05 * mm;  // point spacing
constexpr double half = 4 * mm;  // plate 8 x 8 mm
constexpr double pi = std::numbers::pi;
constexpr double deg = pi / 180;

FacesheetOptions options(DiameterRule rule, double rotation = 0) {
  FacesheetOptions o;
  o.rule = rule;
  o.rotation = rotation;
  return o;
}

FacesheetResult measure(const ParticleData& p, const FacesheetOptions& o) {
  return measure_facesheet(p.view(), 0, o);
}

// r_theta of a circle, a regular hexagon with corners at 0, 60, ... deg (flats at 30, 90, ...),
// and an ellipse with semi-axes A (x) and B (y).
double hexagon_r(double circumradius, double theta) {
  const double flat = circumradius * std::sqrt(3.0) / 2;
  double best = INFINITY;
  for (int k = 0; k < 6; ++k) {
    const double c = std::cos(theta - (30 + 60 * k) * deg);
    if (c > 1e-12) best = std::min(best, flat / c);
  }
  return best;
}
double ellipse_r(double A, double B, double theta) {
  return A * B / std::hypot(B * std::cos(theta), A * std::sin(theta));
}

test::Inside circle(double R) {
  return [R](double x, double y) { return x * x + y * y < R * R; };
}
test::Inside hexagon(double circumradius) {
  return [circumradius](double x, double y) {
    const double flat = circumradius * std::sqrt(3.0) / 2;
    for (int k = 0; k < 6; ++k)
      if (x * std::cos((30 + 60 * k) * deg) + y * std::sin((30 + 60 * k) * deg) >= flat)
        return false;
    return true;
  };
}
test::Inside ellipse(double A, double B) {
  return [A, B](double x, double y) { return (x * x) / (A * A) + (y * y) / (B * B) < 1; };
}

// The raster and ray march against the exact footprint union: within one raster cell in every
// direction, with the raster aligned to the lattice (pixel h/4) and not (pixel h/3.7). Gap closing
// is off here: it is a deliberate change of the material set (tested below).
TEST(Hole, RasterMatchesTheFootprintUnionToOneCell) {
  const ParticleData p = plate(half, h, 2, ellipse(2.0 * mm, 1.5 * mm));
  for (const double pixel : {h / 4, h / 3.7}) {
    FacesheetOptions o = options(DiameterRule::six_directions, 10 * deg);
    o.view.gap_closing = 0;
    o.view.resolution = pixel;
    const FacesheetResult f = measure(p, o);
    ASSERT_TRUE(f.hole.perforated);
    double worst = 0;
    std::array<double, 12> exact{};
    for (int k = 0; k < 12; ++k) {
      exact[k] = test::footprint_union_distance(p.view(), 0, 0, HoleGeometry::angle(k, o.rotation));
      worst = std::max(worst, std::abs(f.hole.r[k] - exact[k]) / pixel);
    }
    EXPECT_LE(worst, 1.0) << "pixel " << pixel;
    // A diameter is a sum of two radii (eq. 8) or twice a mean of six (eqs. 9-10): within two
    // cells of the exact one, by the bound above.
    double h_exact = 0, v_exact = 0;
    for (int k = 0; k < 6; ++k) {
      h_exact += 2 * exact[2 * k] / 6;
      v_exact += 2 * exact[(3 + 2 * k) % 12] / 6;
    }
    EXPECT_NEAR(f.hole.D_h, h_exact, 2 * pixel);
    EXPECT_NEAR(f.hole.D_v, v_exact, 2 * pixel);
    std::printf(
        "raster vs footprint union, pixel h/%.2g: worst r_theta error %.3f cells; D_h %.3f, "
        "D_v %.3f cells\n",
        h / pixel, worst, (f.hole.D_h - h_exact) / pixel, (f.hole.D_v - v_exact) / pixel);
  }
}

// Circle of radius 2.013 mm (40.26 h: not a lattice multiple): every r_theta within h/sqrt(2) + 1
// cell of R, plus the closing's rounding of the staircase's convex corners, at most (sqrt(2) - 1)
// rho with rho = 0.375 h.
TEST(Hole, CircleDiameters) {
  const double R = 2.013 * mm;
  const ParticleData p = plate(half, h, 2, circle(R));
  for (const auto rule : {DiameterRule::two_chords, DiameterRule::six_directions}) {
    const FacesheetResult f = measure(p, options(rule));
    const HoleGeometry& g = f.hole;
    ASSERT_TRUE(g.perforated);
    EXPECT_FALSE(g.open);
    EXPECT_DOUBLE_EQ(g.resolution, h / 4);
    const double tolerance = h / std::sqrt(2.0) + g.resolution + (std::sqrt(2.0) - 1) * 0.375 * h;
    double worst = 0;
    for (int k = 0; k < 12; ++k) {
      EXPECT_NEAR(g.r[k], R, tolerance) << "theta = " << 30 * k;
      worst = std::max(worst, std::abs(g.r[k] - R));
    }
    EXPECT_NEAR(g.D_h, 2 * R, 2 * tolerance);
    EXPECT_NEAR(g.D_v, 2 * R, 2 * tolerance);
    EXPECT_NEAR(g.eccentricity, 1.0, 4 * tolerance / (2 * R));
    // The area averages the staircase over the whole boundary: the equivalent diameter is within
    // one cell of 2R (measured: see the printout).
    EXPECT_NEAR(g.equivalent_diameter, 2 * R, g.resolution);
    std::printf(
        "circle (%s): worst |r_theta - R| %.2f cells (bound %.2f); D = %.5f mm (2R = %.5f mm, "
        "error "
        "%.2f cells), D_eq = %.5f mm (error %.2f cells)\n",
        to_string(rule).c_str(), worst / g.resolution, tolerance / g.resolution, g.D / mm,
        2 * R / mm, (g.D - 2 * R) / g.resolution, g.equivalent_diameter / mm,
        (g.equivalent_diameter - 2 * R) / g.resolution);
  }
}

// Regular hexagon, circumradius 1.987 mm, corners at 0, 60, ... deg: r_theta is the circumradius at
// the corners (even k) and R sqrt(3)/2 at the flats (odd k). Six-direction rule (eqs. 9-10): D_h
// averages corners (2R), D_v flats (sqrt(3) R), e = 2/sqrt(3); turned by 30 deg they swap. Two
// chords (eq. 8): D_h = r_0 + r_180 = 2R, D_v = r_90 + r_270 = sqrt(3) R.
TEST(Hole, HexagonFlatsAndCorners) {
  const double R = 1.987 * mm, flat = R * std::sqrt(3.0) / 2;
  const ParticleData p = plate(half, h, 2, hexagon(R));
  const FacesheetResult f = measure(p, options(DiameterRule::six_directions));
  const HoleGeometry& g = f.hole;
  ASSERT_TRUE(g.perforated);
  const double cell = g.resolution, rounding = (std::sqrt(2.0) - 1) * 0.375 * h;
  const double at_flat = h / std::sqrt(2.0) + cell + rounding;  // alpha = 90 deg
  const double at_corner =
      h / (std::sqrt(2.0) * std::sin(60 * deg)) + cell + rounding;  // alpha = 60 deg
  for (int k = 0; k < 12; ++k) {
    EXPECT_NEAR(g.r[k], hexagon_r(R, 30 * k * deg), k % 2 ? at_flat : at_corner)
        << "theta = " << 30 * k;
    std::printf("hexagon r_%d = %.5f mm (analytic %.5f, error %.2f cells)\n", 30 * k, g.r[k] / mm,
                hexagon_r(R, 30 * k * deg) / mm, (g.r[k] - hexagon_r(R, 30 * k * deg)) / cell);
  }
  EXPECT_NEAR(g.D_h, 2 * R, 2 * at_corner);
  EXPECT_NEAR(g.D_v, 2 * flat, 2 * at_flat);
  EXPECT_NEAR(g.eccentricity, 2 / std::sqrt(3.0), 2 * (at_corner + at_flat) / (2 * flat));

  const FacesheetResult turned = measure(p, options(DiameterRule::six_directions, 30 * deg));
  EXPECT_NEAR(turned.hole.D_h, 2 * flat, 2 * at_flat);
  EXPECT_NEAR(turned.hole.D_v, 2 * R, 2 * at_corner);
  // Turning by 60 deg maps the direction set of each average onto itself: same D_h, D_v (to the
  // lattice's own asymmetry, within the bounds).
  const FacesheetResult sixty = measure(p, options(DiameterRule::six_directions, 60 * deg));
  EXPECT_NEAR(sixty.hole.D_h, g.D_h, 2 * at_corner);

  const FacesheetResult chords = measure(p, options(DiameterRule::two_chords));
  EXPECT_DOUBLE_EQ(chords.hole.D_h, chords.hole.r[0] + chords.hole.r[6]);
  EXPECT_DOUBLE_EQ(chords.hole.D_v, chords.hole.r[3] + chords.hole.r[9]);
  EXPECT_NEAR(chords.hole.D_h, 2 * R, 2 * at_corner);
  EXPECT_NEAR(chords.hole.D_v, 2 * flat, 2 * at_flat);
  std::printf(
      "hexagon: D_h = %.5f mm (2R = %.5f), D_v = %.5f mm (sqrt(3) R = %.5f), e = %.5f (%.5f)\n",
      g.D_h / mm, 2 * R / mm, g.D_v / mm, 2 * flat / mm, g.eccentricity, 2 / std::sqrt(3.0));
}

// Ellipse with semi-axes 2.4 mm (x) and 1.6 mm (y): two chords give e = A / B = 1.5 (eq. 11); the
// six-direction averages follow r(theta) = AB / sqrt((B cos)^2 + (A sin)^2).
TEST(Hole, EllipseEccentricity) {
  const double A = 2.4 * mm, B = 1.6 * mm;
  const ParticleData p = plate(half, h, 2, ellipse(A, B));
  const double cell = h / 4, rounding = (std::sqrt(2.0) - 1) * 0.375 * h;
  const FacesheetResult chords = measure(p, options(DiameterRule::two_chords));
  const double axis_tol =
      h / std::sqrt(2.0) + cell + rounding;  // the rays meet the axes' ends at 90 deg
  EXPECT_NEAR(chords.hole.D_h, 2 * A, 2 * axis_tol);
  EXPECT_NEAR(chords.hole.D_v, 2 * B, 2 * axis_tol);
  EXPECT_NEAR(chords.hole.eccentricity, A / B, 0.01);  // 2 tol/(2B) (1 + A/B) = 0.0094
  // Off the axes the ray meets the ellipse at alpha >= asin(B/A) (= 41.8 deg): a looser bound.
  const double off_axis = h / (std::sqrt(2.0) * (B / A)) + cell + rounding;
  const FacesheetResult six = measure(p, options(DiameterRule::six_directions));
  double h_exact = 0, v_exact = 0;
  for (int k = 0; k < 6; ++k) {
    h_exact += 2 * ellipse_r(A, B, 60 * k * deg) / 6;
    v_exact += 2 * ellipse_r(A, B, (90 + 60 * k) * deg) / 6;
  }
  EXPECT_NEAR(six.hole.D_h, h_exact, 2 * off_axis);
  EXPECT_NEAR(six.hole.D_v, v_exact, 2 * off_axis);
  EXPECT_NEAR(six.hole.eccentricity, h_exact / v_exact, 0.02);
  std::printf(
      "ellipse: e (two chords) = %.5f (A/B = 1.5); e (six directions) = %.5f (analytic %.5f)\n",
      chords.hole.eccentricity, six.hole.eccentricity, h_exact / v_exact);
}

// No hole: NP exactly, every size zero. A hole away from the impact point does not count.
TEST(Hole, NoHoleIsNotPerforated) {
  for (const auto& hole : {test::Inside{}, test::Inside{[](double x, double y) {
                             return (x - 2.5 * mm) * (x - 2.5 * mm) + y * y < 1 * mm * mm;
                           }}}) {
    const FacesheetResult f =
        measure(plate(half, h, 2, hole), options(DiameterRule::six_directions));
    EXPECT_FALSE(f.hole.perforated);
    EXPECT_FALSE(f.hole.open);
    EXPECT_EQ(f.hole.D, 0.0);
    EXPECT_EQ(f.hole.area, 0.0);
    for (double r : f.hole.r) EXPECT_EQ(r, 0.0);
  }
}

// Failed particles and missing particles make the same hole.
TEST(Hole, FailedIsLikeRemoved) {
  const auto a =
      measure(plate(half, h, 2, circle(1.5 * mm), false), options(DiameterRule::two_chords));
  const auto b =
      measure(plate(half, h, 2, circle(1.5 * mm), true), options(DiameterRule::two_chords));
  EXPECT_EQ(a.hole.r, b.hole.r);
  EXPECT_EQ(a.hole.area, b.hole.area);
}

// Half and quarter models mirrored across their symmetry planes give the full model's answer. The
// mirrored set has the same footprints as the full one, so the rasters and sizes are identical
// (to round-off in the pixel origin: 1e-9 of a cell).
TEST(Hole, HalfAndQuarterModelsMirrored) {
  const ParticleData full = plate(half, h, 2, ellipse(2.2 * mm, 1.4 * mm));
  for (const auto& [x_half, y_half] :
       {std::pair{false, true}, std::pair{true, true}, std::pair{true, false}}) {
    const ParticleData part = test::cut(full.view(), x_half, y_half);
    MirrorPlanes planes;
    if (x_half) planes.x = 0.0;
    if (y_half) planes.y = 0.0;
    const ParticleData whole = mirrored(part.view(), planes, 1 << 30);
    ASSERT_EQ(whole.size(), full.size());
    for (const auto rule : {DiameterRule::two_chords, DiameterRule::six_directions}) {
      const auto a = measure(full, options(rule)), b = measure(whole, options(rule));
      for (int k = 0; k < 12; ++k) EXPECT_NEAR(a.hole.r[k], b.hole.r[k], 1e-9 * a.hole.resolution);
      EXPECT_NEAR(a.hole.area, b.hole.area, 1e-9 * a.hole.area);
      EXPECT_NEAR(a.hole.eccentricity, b.hole.eccentricity, 1e-9);
    }
  }
}

// An intact plug sitting in the hole but torn off (2 mm below the sheet, its own cluster) is not
// part of the sheet: the hole is the same as without it. Counting it would close the hole.
TEST(Hole, DetachedPiecesAreLeftOut) {
  ParticleData p = plate(half, h, 2, circle(1.5 * mm));
  const ParticleData plug = plate(1.0 * mm, h, 2, {}, false, 0, -2 * mm, 1'000'000);
  for (std::size_t k = 0; k < plug.size(); ++k) {
    p.position.insert(p.position.end(), plug.position.begin() + 3 * k,
                      plug.position.begin() + 3 * k + 3);
    p.id.push_back(plug.id[k]);
    p.body.push_back(0);
    p.volume.push_back(plug.volume[k]);
    p.mass.push_back(plug.mass[k]);
    p.failed.push_back(0);
    p.spacing.push_back(h);
  }
  const auto without =
      measure(plate(half, h, 2, circle(1.5 * mm)), options(DiameterRule::two_chords));
  const auto with = measure(p, options(DiameterRule::two_chords));
  EXPECT_EQ(with.detached, plug.size());
  EXPECT_EQ(with.hole.r, without.hole.r);
  FacesheetOptions all = options(DiameterRule::two_chords);
  all.link_factor = 0;
  EXPECT_FALSE(measure(p, all).hole.perforated);
}

// A sheet stretched by 40% in its plane (no hole) leaves gaps of 0.4 h (1.6 pixels) between
// fixed-size footprints: without gap closing the impact point falls in a spurious "hole"; with the
// default closing (radius 0.375 h) it is NP. A real gap of one missing column (h wide) survives.
TEST(Hole, GapClosingFillsStretchGapsOnly) {
  ParticleData p = plate(half, h, 2, {});
  for (std::size_t k = 0; k < p.size(); ++k) {
    p.position[3 * k] *= 1.4;
    p.position[3 * k + 1] *= 1.4;
  }
  // The impact point (0, 0) is in a gap: footprints now span |x| in [0.2 h, 1.2 h], ...
  FacesheetOptions o = options(DiameterRule::two_chords);
  o.view.gap_closing = 0;
  EXPECT_TRUE(measure(p, o).hole.perforated);
  EXPECT_FALSE(measure(p, options(DiameterRule::two_chords)).hole.perforated);

  // One column of particles missing along x = h/2 .. a slot one footprint wide through the sheet.
  const ParticleData slot =
      plate(half, h, 2, [](double x, double) { return std::abs(x - h / 2) < h / 4; });
  FacesheetOptions at_slot = options(DiameterRule::two_chords);
  at_slot.axis = {h / 2, 0};
  const auto f = measure(slot, at_slot);
  EXPECT_TRUE(f.hole.perforated);
  EXPECT_NEAR(f.hole.r[0] + f.hole.r[6], h, f.hole.resolution);  // the slot's width
}

// A hole reaching the edge of the sheet is flagged open (its sizes are lower bounds).
TEST(Hole, HoleToTheEdgeIsOpen) {
  const auto f =
      measure(plate(half, h, 1, ellipse(6 * mm, 1 * mm)), options(DiameterRule::two_chords));
  EXPECT_TRUE(f.hole.perforated);
  EXPECT_TRUE(f.hole.open);
}

}  // namespace
}  // namespace hvi::analysis
