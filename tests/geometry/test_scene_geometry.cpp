// The geometry keys of a scene: a [[panel]] becomes three bodies, [[refinement]] zones name the
// bodies they refine, a [[body]] mesh file is found next to the scene and recorded with its
// absolute path, angles take "deg"; mistakes are located diagnostics, and a refused surface file
// is a scene error located at its mesh.file key.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "cases/run/bodies.hpp"
#include "cases/scene/run_info.hpp"
#include "cases/scene/scene.hpp"
#include "geometry/primitives.hpp"
#include "geometry/surface.hpp"
#include "tests/support/scene_text.hpp"

namespace hvi {
namespace {

namespace fs = std::filesystem;

const std::string head = test::run_and_grid("1 us", R"(["-6 mm", "-6 mm", "-18 mm"])",
                                            R"(["6 mm", "6 mm", "4 mm"])", "0.25 mm") +
                         test::study_materials();

const std::string panel = test::PanelText{.more = R"(top = "0 mm"
rotation = "30 deg"
clip = { lower = ["-6 mm", "0 mm", "-18 mm"], upper = ["6 mm", "6 mm", "4 mm"] }
)"}
                              .text();

const std::string cad = R"(
[[body]]
name = "cad"
material = "Al6061"
mesh = { file = "cube.stl", unit = "mm", translate = ["-1 mm", "-1 mm", "1 mm"] }
)";

// A scene file in a fresh folder next to a 2 mm cube (binary STL in mm).
fs::path scene_dir() {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_scene_geometry";
  fs::create_directories(dir);
  geometry::write_stl(geometry::box_surface({0, 0, 0}, {2, 2, 2}), (dir / "cube.stl").string());
  return dir;
}

scene::Diagnostic first_error(const std::string& text, const std::string& file = "scene.toml") {
  try {
    scene::parse_scene(text, file);
  } catch (const scene::SceneError& e) {
    return e.diagnostics().front();
  }
  ADD_FAILURE() << "scene was accepted";
  return {};
}

TEST(SceneGeometry, PanelRefinementAndSurfaceFile) {
  const fs::path dir = scene_dir();
  const std::string text = head + cad + panel + R"(
[[refinement]]
name = "impact"
factor = 3
bodies = ["p.core", "cad"]
cylinder = { base_center = ["0 mm", "0 mm", "-16 mm"], axis = "z", radius = "3 mm", length = "20 mm" }
)";
  const scene::Scene s = scene::parse_scene(text, (dir / "scene.toml").string());
  ASSERT_EQ(s.bodies.size(), 4u);
  EXPECT_EQ(s.bodies[0].name, "cad");
  EXPECT_EQ(s.bodies[1].name, "p.front");
  EXPECT_EQ(s.bodies[2].name, "p.core");
  EXPECT_EQ(s.bodies[3].name, "p.rear");
  EXPECT_EQ(s.bodies[2].material, 1u);  // Al5052
  EXPECT_NEAR(s.panels[0].rotation, std::acos(-1.0) / 6, 1e-15);
  ASSERT_EQ(s.refinements.size(), 1u);
  EXPECT_EQ(s.refinements[0].bodies, (std::vector<std::size_t>{2, 0}));
  // The surface file is recorded with its absolute path (a resumed run reads the resolved scene
  // from the run directory).
  const auto& mesh = std::get<scene::MeshShape>(s.bodies[0].shape);
  EXPECT_EQ(fs::path(mesh.file), fs::weakly_canonical(dir / "cube.stl"));
  EXPECT_NE(scene::resolved_text(s).find(mesh.file), std::string::npos);
  EXPECT_DOUBLE_EQ(mesh.scale, 1e-3);

  // Built: the cube is (2 mm)^3 at [-1, 1] x [-1, 1] x [1, 3] mm; the panel parts are cut to y >=
  // 0.
  const auto cube = driver::make_body_solid(s, 0);
  EXPECT_NEAR(cube->volume(), 8e-9, 1e-21);
  EXPECT_TRUE(cube->contains({0.0, 0.0, 2e-3}));
  const auto front = driver::make_body_solid(s, 1);
  EXPECT_NEAR(front->volume(), 12e-3 * 6e-3 * 0.5e-3, 1e-18);
  const auto settings = driver::sampling_settings(s, 2);
  EXPECT_DOUBLE_EQ(settings.spacing, 0.125e-3);
  ASSERT_EQ(settings.zones.size(), 1u);
  EXPECT_EQ(settings.zones[0].factor, 3);
  EXPECT_TRUE(driver::sampling_settings(s, 1).zones.empty());  // p.front is not listed
}

TEST(SceneGeometry, MistakesAreLocated) {
  std::string bad = panel;
  bad.replace(bad.find("core_material = \"Al5052\""), 24, "core_material = \"Al5O52\"");
  scene::Diagnostic d = first_error(head + bad);
  EXPECT_EQ(d.key, "panel.p.core_material");
  EXPECT_NE(d.message.find("no [[material]] named 'Al5O52'"), std::string::npos) << d.text();

  bad = panel;
  bad.replace(bad.find("wall_thickness = \"0.05 mm\""), 26, "wall_thickness = \"2 mm\"");
  d = first_error(head + bad);
  EXPECT_EQ(d.key, "panel.p.wall_thickness");

  d = first_error(head + panel +
                  "[[refinement]]\nbodies = [\"p.cor\"]\nbox = { lower = [0, 0, 0], upper = [1e-3, "
                  "1e-3, 1e-3] }\n");
  EXPECT_EQ(d.key, "refinement.0.bodies");
  EXPECT_NE(d.message.find("no body named 'p.cor'"), std::string::npos) << d.text();

  d = first_error(head + cad, (fs::path(testing::TempDir()) / "nowhere" / "scene.toml").string());
  EXPECT_EQ(d.key, "body.cad.mesh.file");
  EXPECT_NE(d.message.find("no such file"), std::string::npos) << d.text();

  d = first_error(head);
  EXPECT_NE(d.message.find("at least one [[body]] or [[panel]]"), std::string::npos) << d.text();
}

// A run moved without its surface files (from a cluster to a workstation) is still read for its
// bodies (hvi measure), while a scene to run needs them.
TEST(SceneGeometry, AMovedRunIsReadWithoutItsMeshFiles) {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_moved_run";
  fs::create_directories(dir);
  fs::remove(dir / "cube.stl");
  const fs::path file = dir / "scene.resolved.toml";
  std::ofstream(file) << head + cad;
  EXPECT_THROW(scene::load_scene(file.string()), scene::SceneError);
  const scene::Scene s = scene::load_scene(file.string(), {}, scene::MeshFiles::may_be_missing);
  ASSERT_EQ(s.bodies.size(), 1u);
  const driver::RunInfo info = driver::read_run_info(file);
  ASSERT_EQ(info.body("cad"), 0);
  EXPECT_EQ(info.bodies[0].material, "Al6061");
  EXPECT_DOUBLE_EQ(info.bodies[0].spacing, 0.25e-3 / s.bodies[0].particles_per_cell);
}

// tests/geometry/data/open_cube.stl lacks a face: building the body is a scene error at the
// body's mesh.file key that counts the border edges; nothing is sampled.
TEST(SceneGeometry, RefusedSurfaceIsASceneError) {
  std::string text = head + cad;
  text.replace(text.find("cube.stl"), 8, std::string(HVI_GEOMETRY_DATA) + "/open_cube.stl");
  const scene::Scene s = scene::parse_scene(text, "scene.toml");
  try {
    driver::make_body_solid(s, 0);
    ADD_FAILURE() << "the open surface was accepted";
  } catch (const scene::SceneError& e) {
    const scene::Diagnostic& d = e.diagnostics().front();
    EXPECT_EQ(d.key, "body.cad.mesh.file");
    EXPECT_GT(d.line, 0);
    EXPECT_NE(d.message.find("not closed: 4 border edges"), std::string::npos) << d.text();
    EXPECT_NE(d.message.find("nothing is sampled"), std::string::npos) << d.text();
  }
}

}  // namespace
}  // namespace hvi
