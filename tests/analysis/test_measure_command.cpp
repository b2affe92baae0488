// hvi measure end to end on a synthetic run directory: a resolved scene with a [[panel]] and a
// symmetry plane (a half model), and two snapshots written in the solver's format, with a front
// hole, a rear bulge or hole, and debris of known size. Checks the reading of the scene (bodies,
// spacings, panel, sound speeds, mirror plane), the projectile axis, the mirroring and the files.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <numbers>

#include <gtest/gtest.h>

#include "analysis/table.hpp"
#include "cases/run/measure_command.hpp"
#include "mpm/io/hdf5_file.hpp"
#include "synthetic.hpp"

namespace hvi::driver {
namespace {

namespace fs = std::filesystem;
using analysis::ParticleData;

constexpr double mm = 1e-3;
constexpr double h = 0.1 * mm;  // cell 0.2 mm, 2 points per cell

const char* scene = R"(
title = 'synthetic'
refinement = []
[run]
end_time = 1.0e-5
[grid]
cell_size = 0.0002
lower = [-0.005, 0.0, -0.008]
upper = [0.005, 0.005, 0.002]
[[boundary]]
face = 'y-'
position = 0.0
type = 'symmetry'
[[material]]
name = 'Al'
density = 2700.0
eos = 'mie-gruneisen'
youngs_modulus = 7.0e10
poisson_ratio = 0.33
  [material.mie_gruneisen]
  c0 = 5350.0
  s = 1.34
  gamma0 = 2.0
[[body]]
name = 'projectile'
material = 'Al'
particles_per_cell = 2
velocity = [0.0, 0.0, -3000.0]
  [body.sphere]
  center = [0.0, 0.0, 0.001]
  radius = 0.0005
  [body.clip]
  lower = [-0.005, 0.0, -0.008]
  upper = [0.005, 0.005, 0.002]
[[panel]]
name = 'panel'
front_material = 'Al'
core_material = 'Al'
rear_material = 'Al'
front_thickness = 0.0004
rear_thickness = 0.0002
wall_thickness = 5.0e-5
cell_diameter = 0.003
core_height = 0.005
particles_per_cell = 2
lower = [-0.004, -0.004]
upper = [0.004, 0.004]
top = 0.0
  [panel.clip]
  lower = [-0.005, 0.0, -0.008]
  upper = [0.005, 0.005, 0.002]
)";

// Bodies: 0 projectile, 1 panel.front, 2 panel.core, 3 panel.rear (the [[body]]s, then the panel).
struct Frame {
  ParticleData p;
  std::vector<double> velocity;
};

void append(Frame& f, const ParticleData& part, std::int64_t body, double speed = 0) {
  for (std::size_t k = 0; k < part.size(); ++k) {
    f.p.position.insert(f.p.position.end(), part.position.begin() + 3 * k,
                        part.position.begin() + 3 * k + 3);
    f.p.id.push_back(static_cast<std::int64_t>(f.p.id.size()));
    f.p.body.push_back(body);
    f.p.mass.push_back(part.mass[k]);
    f.p.volume.push_back(part.volume[k]);
    f.p.failed.push_back(part.failed[k]);
    f.velocity.insert(f.velocity.end(), {0.0, 0.0, -speed});
  }
}

// The half model (y > 0) of: a projectile (a block of 10 x 5 x 4 points of 0.1 mm at z ~ 1 mm),
// a front facesheet z in [-0.4, 0] mm, a few core points, a rear facesheet z in [-5.6, -5.4] mm.
Frame initial_frame() {
  Frame f;
  auto half = [](const ParticleData& full) {
    return analysis::test::cut(full.view(), false, true);
  };
  ParticleData projectile = half(analysis::test::plate(0.5 * mm, h, 4, {}, false, 0, 1.2 * mm));
  append(f, projectile, 0, 3000);
  append(f, half(analysis::test::plate(4 * mm, h, 4, {}, false, 1, 0.0)), 1);
  append(f, half(analysis::test::plate(0.2 * mm, h, 1, {}, false, 2, -2.0 * mm)), 2);
  append(f, half(analysis::test::plate(4 * mm, h, 2, {}, false, 3, -5.4 * mm)), 3);
  return f;
}

void write(const fs::path& file, const Frame& f, double time, std::int64_t step) {
  fs::create_directories(file.parent_path());
  mpm::io::Hdf5File h5(file.string(), mpm::io::Hdf5File::Mode::create);
  h5.write_attribute("time", time);
  h5.write_attribute("step", step);
  const std::size_t n = f.p.size();
  h5.write("position", f.p.position.data(), n, 3);
  h5.write("velocity", f.velocity.data(), n, 3);
  h5.write("mass", f.p.mass.data(), n, 1);
  h5.write("volume", f.p.volume.data(), n, 1);
  const std::vector<double> ratio(n, 1.0);
  h5.write("volume_ratio", ratio.data(), n, 1);
  h5.write("failed", f.p.failed.data(), n, 1);
  h5.write("id", f.p.id.data(), n, 1);
  h5.write("body", f.p.body.data(), n, 1);
}

// A run: the front has a hole of radius 1 mm (failed), the rear is pushed by a Gaussian bump of
// 0.25 mm (width 1 mm) or, with `rear_hole`, has an elliptic hole 1.6 x 1.2 mm; the projectile sits
// 2 mm behind the rear face as debris, spread 0.5 mm off the axis.
// `last` may change the last frame before it is written.
fs::path make_run(const std::string& name, bool rear_hole,
                  const std::function<void(Frame&)>& last = {}) {
  const fs::path dir = fs::path(testing::TempDir()) / ("hvi_measure_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "scene.resolved.toml") << scene;
  Frame f = initial_frame();
  write(dir / "snapshots" / "particles_000000.h5", f, 0.0, 0);
  for (std::size_t k = 0; k < f.p.size(); ++k) {
    double* x = &f.p.position[3 * k];
    const double r2 = x[0] * x[0] + x[1] * x[1];
    if (f.p.body[k] == 0) x[2] -= 8.8 * mm;  // the block from z in [0.8, 1.2] mm to [-8, -7.6] mm
    if (f.p.body[k] == 1 && r2 < 1 * mm * mm) f.p.failed[k] = 1;
    if (f.p.body[k] == 3) {
      if (rear_hole && x[0] * x[0] / (1.6 * 1.6) + x[1] * x[1] / (1.2 * 1.2) < mm * mm)
        f.p.failed[k] = 1;
      if (!rear_hole) x[2] -= 0.25 * mm * std::exp(-r2 / (mm * mm));
    }
  }
  if (last) last(f);
  write(dir / "snapshots" / "particles_000001.h5", f, 10e-6, 1000);
  return dir;
}

TEST(MeasureCommand, PanelHalfModelNotPerforatedRear) {
  const fs::path dir = make_run("np", false);
  MeasureOptions o;
  o.run = dir;
  const Measurements m = measure_run(o);
  EXPECT_EQ(m.time, 10e-6);
  ASSERT_TRUE(m.mirror.y.has_value());
  EXPECT_EQ(*m.mirror.y, 0.0);
  EXPECT_FALSE(m.mirror.x.has_value());
  // The projectile's half block mirrored: its centroid is on the axis.
  EXPECT_EQ(m.axis[0], 0.0);
  EXPECT_EQ(m.axis[1], 0.0);
  ASSERT_TRUE(m.front && m.rear);
  EXPECT_EQ(m.front->body, "panel.front");
  EXPECT_DOUBLE_EQ(m.front->spacing, h);
  EXPECT_DOUBLE_EQ(m.front->hole.resolution, h / 4);
  EXPECT_TRUE(m.front->hole.perforated);
  EXPECT_EQ(m.front->hole.rule, analysis::DiameterRule::two_chords);
  // Circle of radius 1 mm on a lattice of h: within h/sqrt(2) + a cell + the closing's rounding
  // per radius (test_hole.cpp), twice that for a diameter.
  const double tolerance = 2 * (h / std::sqrt(2.0) + h / 4 + (std::sqrt(2.0) - 1) * 0.375 * h);
  EXPECT_NEAR(m.front->hole.D, 2 * mm, tolerance);
  EXPECT_FALSE(m.rear->hole.perforated);
  EXPECT_FALSE(m.taper.has_value());
  // Bulge: the nearest lattice column to the axis is h/sqrt(2) away.
  ASSERT_TRUE(m.bulge.has_value());
  EXPECT_NEAR(m.bulge->displacement, 0.25 * mm * std::exp(-0.5 * h * h / (mm * mm)), 1e-15);
  // Debris: the whole projectile (mirrored: both halves); its deepest particle centre at
  // z = -8 mm + h/2, 2.35 mm behind the back face at -5.6 mm; its farthest column from the axis at
  // (0.45, 0.45) mm.
  double mass = 0;
  const Frame f = initial_frame();
  for (std::size_t k = 0; k < f.p.size(); ++k)
    if (f.p.body[k] == 0) mass += 2 * f.p.mass[k];
  EXPECT_NEAR(m.debris.mass, mass, 1e-12 * mass);
  EXPECT_EQ(m.debris_behind, "panel.rear");
  EXPECT_NEAR(m.debris_back_face, -5.6 * mm, 1e-12);
  EXPECT_NEAR(m.debris.axial_extent, 7.95 * mm - 5.6 * mm, 1e-12);
  EXPECT_NEAR(m.debris.radial_extent, std::hypot(0.45, 0.45) * mm, 1e-12);
  // Its kinetic energy: the projectile still moves at 3000 m/s, 1/2 m v^2 over both halves.
  EXPECT_NEAR(m.debris.kinetic_energy, 0.5 * mass * 3000.0 * 3000.0, 1e-12 * mass * 9e6);
  // The dimensional-analysis variables from the scene.
  std::map<std::string, double> v(m.variables.begin(), m.variables.end());
  EXPECT_NEAR(v.at("v_p"), 3000, 1e-9);  // a mass-weighted mean: round-off
  EXPECT_DOUBLE_EQ(v.at("d_p"), 1 * mm);
  EXPECT_DOUBLE_EQ(v.at("t_f"), 0.4 * mm);
  EXPECT_DOUBLE_EQ(v.at("t_r"), 0.2 * mm);
  EXPECT_DOUBLE_EQ(v.at("c_f"), 5350);
  EXPECT_DOUBLE_EQ(v.at("c_hc"), 5350);
  EXPECT_DOUBLE_EQ(v.at("t_hc"), 0.05 * mm);
  EXPECT_DOUBLE_EQ(v.at("D_hc"), 3 * mm);
  EXPECT_DOUBLE_EQ(v.at("S"), 5 * mm);

  // The files: JSON, and a CSV whose one row hvi fit reads.
  write_measurements(m, dir);
  EXPECT_TRUE(fs::exists(dir / "measurements.json"));
  const analysis::Table t = analysis::read_csv(dir / "measurements.csv");
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.rows[0][t.column("front_perforated")], "true");
  EXPECT_EQ(t.rows[0][t.column("rear_perforated")], "false");
  EXPECT_NEAR(t.number(0, t.column("D_f")), m.front->hole.D, 1e-12);
  EXPECT_TRUE(std::isnan(t.number(0, t.column("D_r"))));
  EXPECT_NEAR(t.number(0, t.column("bulge")), m.bulge->displacement, 1e-12);
}

// Detached spall: a disc of the rear sheet (r < 0.6 mm) cut free by a failed ring (0.6 mm <= r <
// 0.8 mm) and moved 1 mm behind the sheet is counted, whole and mirrored, as the rear sheet's
// spall; the bulge of the other run has none.
TEST(MeasureCommand, DetachedSpallIsTheRearSheetsMaterialCutFreeBehindIt) {
  double disc_mass = 0;
  std::size_t disc = 0;
  const fs::path dir = make_run("spall", false, [&](Frame& f) {
    for (std::size_t k = 0; k < f.p.size(); ++k) {
      if (f.p.body[k] != 3) continue;
      double* x = &f.p.position[3 * k];
      const double r = std::hypot(x[0], x[1]);
      if (r < 0.6 * mm) {
        x[2] -= 1 * mm;
        disc_mass += f.p.mass[k];
        ++disc;
      } else if (r < 0.8 * mm) {
        f.p.failed[k] = 1;
      }
    }
  });
  MeasureOptions o;
  o.run = dir;
  const Measurements m = measure_run(o);
  ASSERT_TRUE(m.spall.has_value());
  ASSERT_GT(disc, 0u);
  EXPECT_EQ(m.spall->particles, 2 * disc);  // both halves of the half model
  EXPECT_NEAR(m.spall->mass, 2 * disc_mass, 1e-12 * disc_mass);
  write_measurements(m, dir);
  const analysis::Table t = analysis::read_csv(dir / "measurements.csv");
  EXPECT_EQ(t.number(0, t.column("rear_spall_particles")), static_cast<double>(2 * disc));

  MeasureOptions plain;
  plain.run = make_run("no_spall", false);
  const Measurements bulge = measure_run(plain);
  ASSERT_TRUE(bulge.spall.has_value());
  EXPECT_EQ(bulge.spall->particles, 0u);
}

// The rear hole, an ellipse of semi-axes 1.6 and 1.2 mm: perforated, measured by the six-
// direction rule, with the taper of eq. (12) from the panel's core height.
TEST(MeasureCommand, PanelPerforatedRearAndTaper) {
  const fs::path dir = make_run("perforated", true);
  MeasureOptions o;
  o.run = dir;
  const Measurements m = measure_run(o);
  ASSERT_TRUE(m.rear && m.rear->hole.perforated);
  EXPECT_EQ(m.rear->hole.rule, analysis::DiameterRule::six_directions);
  EXPECT_FALSE(m.bulge.has_value());
  // Six-direction averages of r(theta) = AB / sqrt((B cos)^2 + (A sin)^2); off the axes the ray
  // meets the ellipse at alpha >= asin(B/A): per radius h/(sqrt(2) B/A) + a cell + rounding.
  const double A = 1.6 * mm, B = 1.2 * mm, deg = std::numbers::pi / 180;
  double D_h = 0, D_v = 0;
  for (int k = 0; k < 6; ++k) {
    D_h += 2 * A * B / std::hypot(B * std::cos(60 * k * deg), A * std::sin(60 * k * deg)) / 6;
    D_v += 2 * A * B /
           std::hypot(B * std::cos((90 + 60 * k) * deg), A * std::sin((90 + 60 * k) * deg)) / 6;
  }
  const double tolerance =
      2 * (h / (std::sqrt(2.0) * B / A) + h / 4 + (std::sqrt(2.0) - 1) * 0.375 * h);
  EXPECT_NEAR(m.rear->hole.D_h, D_h, tolerance);
  EXPECT_NEAR(m.rear->hole.D_v, D_v, tolerance);
  ASSERT_TRUE(m.taper.has_value());
  EXPECT_DOUBLE_EQ(*m.taper, (m.rear->hole.D - m.front->hole.D) / (5 * mm));
  // The debris excludes the rear sheet's own material; the projectile is all of it.
  EXPECT_NEAR(m.debris.axial_extent, 7.95 * mm - 5.6 * mm, 1e-12);

  // What a run's summary gets from a kind = "holes" measure: the same numbers.
  std::map<std::string, double> q;
  for (const auto& [name, value] : headline_quantities(m)) q[name] = value;
  EXPECT_EQ(q.at("front_perforated"), 1.0);
  EXPECT_EQ(q.at("rear_perforated"), 1.0);
  EXPECT_EQ(q.at("D_f"), m.front->hole.D);
  EXPECT_EQ(q.at("D_r"), m.rear->hole.D);
  EXPECT_EQ(q.at("e_r"), m.rear->hole.eccentricity);
  EXPECT_EQ(q.at("taper"), *m.taper);
  EXPECT_EQ(q.at("debris_mass"), m.debris.mass);
  EXPECT_EQ(q.count("bulge"), 0u);         // perforated: no bulge
  EXPECT_EQ(q.at("rear_hole_open"), 0.0);  // closed inside the sheet: D_r is the hole's size

  // Without mirroring the half sheet's hole reaches the cut at y = 0: open, and the axis is the
  // half projectile's centroid (off the plane) unless given.
  o.mirror = false;
  o.axis = std::array<double, 2>{0.0, 0.0};
  const Measurements half = measure_run(o);
  EXPECT_TRUE(half.rear->hole.open);
  std::map<std::string, double> q_half;
  for (const auto& [name, value] : headline_quantities(half)) q_half[name] = value;
  EXPECT_EQ(q_half.at("rear_hole_open"), 1.0);  // the summary says D_r is a lower bound
}

// --snapshot all: one row per snapshot, each the measure of that snapshot alone; the CSV has the
// columns of measurements.csv. At t = 0 nothing is perforated, the bulge is exactly zero and the
// projectile is in front of the panel (no debris).
TEST(MeasureCommand, HistoryMeasuresEverySnapshot) {
  const fs::path dir = make_run("history", true);
  MeasureOptions o;
  o.run = dir;
  const std::vector<Measurements> history = measure_history(o);
  ASSERT_EQ(history.size(), 2u);
  EXPECT_EQ(history[0].step, 0);
  EXPECT_FALSE(history[0].front->hole.perforated);
  EXPECT_FALSE(history[0].rear->hole.perforated);
  ASSERT_TRUE(history[0].bulge.has_value());
  EXPECT_EQ(history[0].bulge->displacement, 0.0);
  EXPECT_EQ(history[0].debris.mass, 0.0);
  const Measurements last = measure_run(o);
  EXPECT_EQ(history[1].step, 1000);
  EXPECT_EQ(history[1].rear->hole.D, last.rear->hole.D);
  EXPECT_EQ(history[1].front->hole.D, last.front->hole.D);
  EXPECT_EQ(history[1].debris.mass, last.debris.mass);

  write_history(history, dir);
  write_measurements(last, dir);
  const analysis::Table t = analysis::read_csv(dir / "measurements_history.csv");
  const analysis::Table one = analysis::read_csv(dir / "measurements.csv");
  EXPECT_EQ(t.columns, one.columns);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0][t.column("rear_perforated")], "false");
  EXPECT_EQ(t.rows[1], one.rows[0]);
}

// --out: the files go to a directory of their own (created), the run's is left as it was, and
// they are the ones a measure into the run's directory writes, to the byte.
TEST(MeasureCommand, OutWritesElsewhereAndLeavesTheRunAlone) {
  const fs::path dir = make_run("out", true);
  const fs::path out = fs::path(testing::TempDir()) / "hvi_measure_out_elsewhere" / "so_far";
  fs::remove_all(out.parent_path());
  auto read = [](const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  MeasureOptions o;
  o.run = dir;
  o.out = out;
  for (const char* which : {"all", "last"}) {
    o.snapshot = which;
    ASSERT_EQ(measure_command(o), 0);
  }
  for (const char* f : {"measurements.json", "measurements.csv", "measurements_history.csv"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
    EXPECT_FALSE(fs::exists(dir / f)) << f;
  }
  o.out.clear();
  for (const char* which : {"all", "last"}) {
    o.snapshot = which;
    ASSERT_EQ(measure_command(o), 0);
  }
  for (const char* f : {"measurements.json", "measurements.csv", "measurements_history.csv"}) {
    const std::string here = read(out / f);
    EXPECT_GT(here.size(), 100u) << f;
    EXPECT_EQ(here, read(dir / f)) << f;
  }
}

// Snapshots are named by index: a run pruned by hand keeps its numbering, and one without the
// state at step 0 (which gives the initial positions) is refused rather than measured against a
// later state.
TEST(MeasureCommand, SnapshotsAreFoundByTheirIndex) {
  const fs::path dir = make_run("pruned", true);
  fs::rename(dir / "snapshots" / "particles_000001.h5", dir / "snapshots" / "particles_000007.h5");
  MeasureOptions o;
  o.run = dir;
  EXPECT_EQ(measure_run(o).step, 1000);  // last = 7
  o.snapshot = "7";
  EXPECT_EQ(measure_run(o).step, 1000);
  o.snapshot = "1";
  EXPECT_THROW(measure_run(o), std::invalid_argument);
  o.snapshot = "last";
  fs::remove(dir / "snapshots" / "particles_000000.h5");
  EXPECT_THROW(measure_run(o), std::invalid_argument);
  EXPECT_THROW(measure_history(o), std::invalid_argument);
}

TEST(MeasureCommand, BadInputIsReported) {
  const fs::path dir = make_run("bad", false);
  MeasureOptions o;
  o.run = dir;
  o.front = "nope";
  EXPECT_THROW(measure_run(o), std::invalid_argument);
  o.front = "";
  o.snapshot = "2";
  EXPECT_THROW(measure_run(o), std::invalid_argument);
  o.snapshot = "all";  // measure_history's, not measure_run's
  EXPECT_THROW(measure_run(o), std::invalid_argument);
  o.snapshot = "-1";
  EXPECT_THROW(measure_run(o), std::invalid_argument);
  o.run = dir / "missing";
  EXPECT_THROW(measure_run(o), std::invalid_argument);
}

// A hybrid's growing zone adds points after t = 0, with ids beyond every id of the first
// snapshot. Such a point is mirrored with the rest (a larger id offset) and, having no state at
// t = 0, takes its layer's: a core point that flew behind the rear face is debris, it and its
// image, and nothing else the measure reads moves.
TEST(MeasureCommand, APointAGrowingZoneAddsIsMirroredAndCountedByItsLayer) {
  MeasureOptions o;
  o.run = make_run("grown_before", true);
  const Measurements before = measure_run(o);
  const double m = 1e-9;
  o.run = make_run("grown", true, [&](Frame& f) {
    f.p.position.insert(f.p.position.end(), {0.3 * mm, 0.2 * mm, -7.0 * mm});
    f.p.id.push_back(static_cast<std::int64_t>(f.p.id.size()) + 100);
    f.p.body.push_back(2);  // panel.core
    f.p.mass.push_back(m);
    f.p.volume.push_back(m / 2700);
    f.p.failed.push_back(1);
    f.velocity.insert(f.velocity.end(), {0.0, 0.0, -500.0});
  });
  const Measurements after = measure_run(o);
  EXPECT_EQ(after.debris.particles, before.debris.particles + 2);
  EXPECT_NEAR(after.debris.mass, before.debris.mass + 2 * m, 1e-12 * before.debris.mass);
  EXPECT_NEAR(after.debris.kinetic_energy, before.debris.kinetic_energy + m * 500.0 * 500.0,
              1e-12 * before.debris.kinetic_energy);
  EXPECT_EQ(after.debris.axial_extent,
            before.debris.axial_extent);  // 1.4 mm behind, the block 2.35
  EXPECT_EQ(after.axis, before.axis);
  EXPECT_EQ(after.front->hole.D, before.front->hole.D);
  EXPECT_EQ(after.rear->hole.D, before.rear->hole.D);
}

}  // namespace
}  // namespace hvi::driver
