// The real scene declaration: a valid scene resolves with every default filled in, and each class
// of scene error names the file, line, column and key.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "cases/scene/scene.hpp"
#include "tests/driver/scene_errors.hpp"

namespace hvi::scene {
namespace {

const std::string valid = R"(
[run]
end_time = "10 us"

[grid]
lower = ["0 mm", "0 mm", "0 mm"]
upper = ["10.2 mm", "5 mm", "5 mm"]
cell_size = "0.5 mm"

[[boundary]]
face = "z-"
type = "symmetry"

[[material]]
name = "al"
density = "2.7 g/cm^3"
youngs_modulus = "70 GPa"
poisson_ratio = 0.33

[[body]]
name = "ball"
material = "al"
velocity = ["0 m/s", "0 m/s", "-1 km/s"]
sphere = { center = ["5 mm", "2.5 mm", "2.5 mm"], radius = "2 mm" }
)";

// The first diagnostic of a scene that must fail.
Diagnostic first_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, "scene.toml", overrides);
  } catch (const SceneError& e) {
    return e.diagnostics().front();
  }
  ADD_FAILURE() << "scene was accepted";
  return {};
}

using test::error_for;

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// A cell size that divides the extent but for round-off (0.4 mm / sqrt(2)^2, a level of
// `hvi convergence --ratio 1.41421`) keeps the requested bound rather than falling a hair short,
// so a body flush with it still fits.
TEST(Scene, GridBoundStaysPutUnderRoundOffOfTheCellSize) {
  const Scene s = parse_scene(
      valid, "scene.toml",
      {"grid.upper=[\"18 mm\", \"5 mm\", \"5 mm\"]", "grid.cell_size=0.00019999999999999996 m"});
  EXPECT_EQ(s.grid.cells[0], 90);
  EXPECT_EQ(s.grid.upper[0], 18e-3);
}

// Every scene shipped in cases/ resolves without error (the studies there are checked by
// Sweep.ShippedPaperStudiesResolve; a study file names its `scene = ...`).
TEST(Scene, EveryShippedSceneResolves) {
  int scenes = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(std::string(HVI_SOURCE_DIR) + "/cases")) {
    if (entry.path().extension() != ".toml") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    if (text.str().find("\nscene = ") != std::string::npos) continue;
    EXPECT_NO_THROW(load_scene(entry.path().string(), {})) << entry.path();
    ++scenes;
  }
  EXPECT_GE(scenes, 12);  // demo, verification, stability, hybrid and the paper panels
}

TEST(Scene, ResolvesDefaultsAndUnits) {
  const Scene s = parse_scene(valid, "scene.toml");
  EXPECT_DOUBLE_EQ(s.end_time, 10e-6);
  EXPECT_DOUBLE_EQ(s.output_interval, 1e-6);      // end_time / 10
  EXPECT_DOUBLE_EQ(s.checkpoint_interval, 1e-6);  // the snapshot interval
  EXPECT_EQ(s.grid.cells[0], 21);                 // 10.2 mm rounds up to 21 cells of 0.5 mm
  EXPECT_DOUBLE_EQ(s.grid.upper[0], 10.5e-3);
  EXPECT_EQ(s.grid.shape_function, "cpgimp");
  EXPECT_EQ(s.grid.scheme, "musl");
  EXPECT_DOUBLE_EQ(s.materials[0].models.poisson_ratio, 0.33);
  EXPECT_DOUBLE_EQ(s.materials[0].models.density, 2700.0);
  EXPECT_TRUE(s.materials[0].elastic_only());
  EXPECT_DOUBLE_EQ(s.bodies[0].velocity[2], -1000.0);
  EXPECT_EQ(s.bodies[0].particles_per_cell, 2);
  ASSERT_EQ(s.boundaries.size(), 1u);
  EXPECT_EQ(s.boundaries[0].axis, 2);
  EXPECT_EQ(s.boundaries[0].plane, 0);
  // The resolved table holds the computed values too, so the run can be repeated from it.
  EXPECT_DOUBLE_EQ(s.resolved["output"]["interval"].value<double>().value(), 1e-6);
  EXPECT_DOUBLE_EQ(s.resolved["grid"]["upper"][0].value<double>().value(), 10.5e-3);
  EXPECT_DOUBLE_EQ(s.resolved["boundary"][0]["position"].value<double>().value(), 0.0);
  const Scene again = parse_scene(resolved_text(s), "scene.resolved.toml");
  EXPECT_EQ(again.grid.cells, s.grid.cells);
  EXPECT_DOUBLE_EQ(again.output_interval, s.output_interval);
}

TEST(Scene, UnknownKeySuggestsTheNearestOne) {
  // Both the unknown key and the now-missing cell_size are reported.
  const Diagnostic d = error_for(replace(valid, "cell_size =", "cel_size ="), "grid.cel_size");
  EXPECT_EQ(d.line, 8);
  EXPECT_EQ(d.column, 1);
  EXPECT_TRUE(contains(d.text(), "grid.cel_size")) << d.text();
  EXPECT_TRUE(contains(d.text(), "did you mean 'cell_size'")) << d.text();
}

TEST(Scene, WrongUnitNamesWhatWasExpected) {
  const Diagnostic d = first_error(replace(valid, "\"0.5 mm\"", "\"0.5 kg\""));
  EXPECT_EQ(d.line, 8);
  EXPECT_EQ(d.key, "grid.cell_size");
  EXPECT_TRUE(contains(d.text(), "scene.toml:8:")) << d.text();
  EXPECT_TRUE(contains(d.text(), "\"0.5 kg\"")) << d.text();
  EXPECT_TRUE(contains(d.text(), "length")) << d.text();
}

TEST(Scene, OutOfRangeValueNamesTheRange) {
  const Diagnostic d =
      first_error(replace(valid, "cell_size = \"0.5 mm\"", "cell_size = \"0.5 mm\"\ncfl = 1.5"));
  EXPECT_EQ(d.line, 9);
  EXPECT_EQ(d.key, "grid.cfl");
  EXPECT_TRUE(contains(d.text(), "(0, 0.9]")) << d.text();
}

// A time step at the CFL limit is refused, with the reason in the key's description.
TEST(Scene, CflAtTheStabilityLimitIsRefused) {
  const Diagnostic d = first_error(valid, {"grid.cfl=1.0"});
  EXPECT_EQ(d.key, "grid.cfl");
  EXPECT_TRUE(contains(d.text(), "expected a number in (0, 0.9]")) << d.text();
  EXPECT_NO_THROW(parse_scene(valid, "scene.toml", {"grid.cfl=0.9"}));
}

TEST(Scene, MissingRequiredKeyIsNamedAtItsTable) {
  const Diagnostic d = first_error(replace(valid, "end_time = \"10 us\"", ""));
  EXPECT_EQ(d.key, "run.end_time");
  EXPECT_EQ(d.line, 2);  // the [run] header
  EXPECT_TRUE(contains(d.text(), "missing")) << d.text();
}

TEST(Scene, UnknownMaterialIsNamedAtTheBody) {
  const Diagnostic d = first_error(replace(valid, "material = \"al\"", "material = \"steel\""));
  EXPECT_EQ(d.key, "body.ball.material");
  EXPECT_EQ(d.line, 22);
  EXPECT_TRUE(contains(d.text(), "no [[material]] named 'steel'")) << d.text();
}

TEST(Scene, BoundaryPlaneMustLieOnGridNodes) {
  const Diagnostic d = first_error(
      replace(valid, "type = \"symmetry\"", "type = \"symmetry\"\nposition = \"0.3 mm\""));
  EXPECT_EQ(d.key, "boundary.0.position");
  EXPECT_EQ(d.line, 13);
  EXPECT_TRUE(contains(d.text(), "does not lie on grid nodes")) << d.text();
}

TEST(Scene, BodyOutsideTheGridIsRefused) {
  const Diagnostic d = first_error(replace(valid, "radius = \"2 mm\"", "radius = \"3 mm\""));
  EXPECT_EQ(d.key, "body.ball");
  EXPECT_TRUE(contains(d.text(), "outside the grid")) << d.text();
}

TEST(Scene, TomlSyntaxErrorHasItsLine) {
  const Diagnostic d = first_error(replace(valid, "[grid]", "[grid"));
  EXPECT_EQ(d.line, 5);
  EXPECT_TRUE(contains(d.text(), "not valid TOML")) << d.text();
}

TEST(Scene, BadOverrideNamesTheCommandLine) {
  const Diagnostic d = first_error(valid, {"grid.cell_size=0.5 s"});
  EXPECT_EQ(d.key, "grid.cell_size");
  EXPECT_TRUE(contains(d.text(), "--set grid.cell_size=0.5 s")) << d.text();
  EXPECT_TRUE(contains(d.text(), "length")) << d.text();
}

TEST(Scene, OverrideAddressesBodiesByName) {
  const Scene s =
      parse_scene(valid, "scene.toml", {"body.ball.velocity=[0, 0, -4500]", "grid.scheme=usl"});
  EXPECT_DOUBLE_EQ(s.bodies[0].velocity[2], -4500.0);
  EXPECT_EQ(s.grid.scheme, "usl");
}

// [contact]: the impactor's bodies by name, resolved to body indices; a name that is no body, or
// every body (no second field), is refused at the key, and the table needs its bodies.
TEST(Scene, ContactNamesTheImpactorsBodies) {
  const std::string two = valid + R"(
[[body]]
name = "plate"
material = "al"
box = { lower = ["0 mm", "0 mm", "0 mm"], upper = ["10 mm", "5 mm", "0.5 mm"] }

[contact]
bodies = ["ball"]
friction = 0.2
)";
  const Scene s = parse_scene(two, "scene.toml");
  ASSERT_TRUE(s.contact.has_value());
  EXPECT_EQ(s.contact->bodies, std::vector<std::size_t>{0});
  EXPECT_DOUBLE_EQ(s.contact->friction, 0.2);
  EXPECT_FALSE(parse_scene(valid, "scene.toml").contact.has_value());

  Diagnostic d = error_for(two, "contact.bodies", {"contact.bodies=[\"bal\"]"});
  EXPECT_TRUE(contains(d.text(), "no body named 'bal'; bodies: 'ball', 'plate'")) << d.text();
  d = error_for(two, "contact.bodies", {"contact.bodies=[\"ball\", \"plate\"]"});
  EXPECT_TRUE(contains(d.text(), "every body is named")) << d.text();
  d = error_for(replace(two, "bodies = [\"ball\"]", "bodies = []"), "contact.bodies");
  EXPECT_EQ(d.line, 32);  // bodies = []
  EXPECT_TRUE(contains(d.text(), "at least one of 'ball', 'plate'")) << d.text();
  d = error_for(replace(two, "bodies = [\"ball\"]\n", ""), "contact.bodies");
  EXPECT_TRUE(contains(d.text(), "missing")) << d.text();
  d = error_for(two, "contact.friction", {"contact.friction=-0.1"});
  EXPECT_TRUE(contains(d.text(), "-0.1")) << d.text();
}

TEST(Scene, EveryErrorIsReportedNotJustTheFirst) {
  std::string text = replace(valid, "\"0.5 mm\"", "\"0.5 kg\"");
  text = replace(text, "name = \"al\"", "name = \"al\"\ncolour = \"grey\"");
  try {
    parse_scene(text, "scene.toml");
    FAIL() << "scene was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.diagnostics().size(), 2u);
  }
}

// Named override sets: [resolutions.<name>] tables of "key.path" = value entries, chosen by
// `resolution` in the file or on the command line; the command line wins over the set.
const std::string with_resolutions = "resolution = \"coarse\"\n" + valid + R"(
[resolutions.coarse]
"grid.cell_size" = "1 mm"
"body.ball.particles_per_cell" = 1

[resolutions.fine]
"grid.cell_size" = "0.25 mm"
"body.ball.velocity" = ["0 m/s", "0 m/s", "-2 km/s"]
)";

TEST(Scene, ResolutionSetsApplyTheirOverrides) {
  const Scene coarse = parse_scene(with_resolutions, "scene.toml");
  EXPECT_DOUBLE_EQ(coarse.grid.cell_size, 1e-3);
  EXPECT_EQ(coarse.bodies[0].particles_per_cell, 1);
  EXPECT_EQ(coarse.resolved["resolution"].value<std::string>().value(), "coarse");
  // The resolved scene holds the values, and the chosen set emptied, so that it reads back.
  EXPECT_EQ(coarse.resolved["resolutions"].as_table()->size(), 1u);
  EXPECT_TRUE(coarse.resolved["resolutions"]["coarse"].as_table()->empty());

  const Scene fine = parse_scene(with_resolutions, "scene.toml", {"resolution=fine"});
  EXPECT_DOUBLE_EQ(fine.grid.cell_size, 0.25e-3);
  EXPECT_DOUBLE_EQ(fine.bodies[0].velocity[2], -2000.0);
  EXPECT_EQ(fine.bodies[0].particles_per_cell, 2);  // the default: "fine" does not set it

  const Scene mixed =
      parse_scene(with_resolutions, "scene.toml", {"resolution=fine", "grid.cell_size=0.5 mm"});
  EXPECT_DOUBLE_EQ(mixed.grid.cell_size, 0.5e-3);  // the command line wins
}

// A run's scene.resolved.toml with a resolution chosen reads back to the same scene (a resumed run
// and `hvi measure` read it; it once named a set it no longer held and was refused).
TEST(Scene, ResolvedSceneWithAResolutionReadsBack) {
  const Scene fine = parse_scene(with_resolutions, "scene.toml", {"resolution=fine"});
  const Scene again = parse_scene(resolved_text(fine), "scene.resolved.toml");
  EXPECT_EQ(resolved_text(again), resolved_text(fine));
  EXPECT_DOUBLE_EQ(again.grid.cell_size, 0.25e-3);
}

TEST(Scene, HolesMeasureNeedsAPanelOrAPlate) {
  const std::string holes = "\n[[measure]]\nname = \"holes\"\nkind = \"holes\"\n";
  const Diagnostic d = error_for(valid + holes, "measure.holes");
  EXPECT_TRUE(contains(d.message, "[[panel]]")) << d.text();
  const Scene s =
      parse_scene(valid + holes + "body = \"ball\"\n", "scene.toml");  // the plate named
  EXPECT_EQ(s.measures.at(0).body, "ball");
}

// Stopping once settled is judged on the holes history: without it the key is refused at its line,
// with it the window and tolerance read back in SI.
TEST(Scene, StoppingWhenSettledNeedsTheHoleHistory) {
  const std::string holes =
      "\n[[measure]]\nname = \"holes\"\nkind = \"holes\"\nbody = \"ball\"\n"
      "stop_when_settled = \"3 us\"\n";
  const Diagnostic d = error_for(valid + holes, "measure.holes.stop_when_settled");
  EXPECT_TRUE(contains(d.message, "needs history = true")) << d.text();
  const Scene s =
      parse_scene(valid + holes + "history = true\nsettle_tolerance = 0.01\n", "scene.toml");
  EXPECT_EQ(s.measures.at(0).stop_when_settled, 3e-6);
  EXPECT_EQ(s.measures.at(0).settle_tolerance, 0.01);
}

TEST(Scene, UnknownResolutionNamesTheOnesDefined) {
  const Diagnostic d = first_error(with_resolutions, {"resolution=paper"});
  EXPECT_EQ(d.key, "resolution");
  EXPECT_TRUE(contains(d.message, "coarse, fine")) << d.text();
}

TEST(Scene, BadValueInAResolutionSetNamesTheSet) {
  const Diagnostic d = first_error(replace(with_resolutions, "\"1 mm\"", "\"1 kg\""));
  EXPECT_EQ(d.key, "grid.cell_size");
  EXPECT_TRUE(contains(d.text(), "[resolutions.coarse]")) << d.text();
}

}  // namespace
}  // namespace hvi::scene
