// `hvi geometry` end to end: a half-model panel with a refined zone and a projectile is built,
// checked and sampled; the STL surfaces, the points (HDF5/XDMF) and bodies.csv are written, and
// every body's mass is density x exact volume. A refused surface file stops it with exit code 2
// before anything is written. The paper's scenes stay valid (`hvi check`, coarsened).
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "mpm/io/hdf5_file.hpp"
#include "tests/support/run_hvi.hpp"
#include "tests/support/scene_text.hpp"

namespace {

namespace fs = std::filesystem;

const std::string source = HVI_SOURCE_DIR;

using hvi::test::run;

// A small study panel (half model, 12 x 6 mm) with a refined zone and a 3 mm sphere.
const std::string scene_text = hvi::test::run_and_grid("1 us", R"(["-6 mm", "0 mm", "-16 mm"])",
                                                       R"(["6 mm", "6 mm", "4 mm"])", "0.25 mm") +
                               R"([[boundary]]
face = "y-"
type = "symmetry"
)" + hvi::test::study_materials() +
                               R"([[body]]
name = "projectile"
material = "Al6061"
velocity = [0, 0, -4500]
sphere = { center = ["0 mm", "0 mm", "1.75 mm"], radius = "1.5 mm" }
clip = { lower = ["-6 mm", "0 mm", "-16 mm"], upper = ["6 mm", "6 mm", "4 mm"] }
)" +
                               hvi::test::PanelText{.name = "panel", .more = R"(top = "0 mm"
clip = { lower = ["-6 mm", "0 mm", "-16 mm"], upper = ["6 mm", "6 mm", "4 mm"] }
)"}
                                   .text() +
                               R"([[refinement]]
factor = 2
box = { lower = ["-3 mm", "0 mm", "-16 mm"], upper = ["3 mm", "3 mm", "4 mm"] }
)";

fs::path write_scene(const std::string& name, const std::string& text) {
  const fs::path p = fs::path(testing::TempDir()) / name;
  std::ofstream(p) << text;
  return p;
}

TEST(GeometryCommand, WritesSurfacesPointsAndTable) {
  const fs::path out = fs::path(testing::TempDir()) / "hvi_geometry_out";
  fs::remove_all(out);
  std::string stdout_text;
  ASSERT_EQ(run("geometry " + write_scene("panel.toml", scene_text).string() + " --out " +
                    out.string() + " --threads 2",
                nullptr, &stdout_text),
            0);
  EXPECT_NE(stdout_text.find("closed, outward, no self-intersection"), std::string::npos)
      << stdout_text;
  EXPECT_NE(stdout_text.find("peak memory"), std::string::npos);
  for (const char* body : {"projectile", "panel.front", "panel.core", "panel.rear"})
    EXPECT_GT(fs::file_size(out / (std::string(body) + ".stl")), 84u)
        << body;  // header + triangles
  ASSERT_TRUE(fs::exists(out / "points.xmf"));

  // bodies.csv: body, material, points, refined, sampling, exact, sampled, error, mass, triangles.
  std::ifstream csv(out / "bodies.csv");
  std::string line;
  std::getline(csv, line);
  const std::map<std::string, double> density{{"Al6061", 2770.0}, {"Al5052", 2680.0}};
  long total = 0;
  std::map<std::string, double> mass;
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) f.push_back(cell);
    ASSERT_EQ(f.size(), 10u) << line;
    total += std::stol(f[2]);
    mass[f[0]] = std::stod(f[8]);
    // The sampled mass is density x exact volume (to summation round-off); the raw lattice volume
    // resolves the exact one within 0.5 % (the 3 mm sphere at h = 0.0625 mm: 48 points across).
    EXPECT_NEAR(std::stod(f[8]) / (density.at(f[1]) * std::stod(f[5])), 1.0, 1e-12) << f[0];
    EXPECT_LT(std::fabs(std::stod(f[7])), 5e-3) << f[0];
  }
  EXPECT_EQ(mass.size(), 4u);
  EXPECT_EQ(mass.count("panel.core"), 1u);

  hvi::mpm::io::Hdf5File h5((out / "points.h5").string(), hvi::mpm::io::Hdf5File::Mode::read);
  const auto body = h5.read_integers("body");
  const auto m = h5.read_doubles("mass");
  ASSERT_EQ(static_cast<long>(body.size()), total);
  EXPECT_EQ(h5.shape("half_width").second, 3u);
  double core = 0;
  for (std::size_t p = 0; p < body.size(); ++p) core += body[p] == 2 ? m[p] : 0.0;
  EXPECT_NEAR(core / mass["panel.core"], 1.0, 1e-12);
}

TEST(GeometryCommand, RefusedSurfaceWritesNothing) {
  std::string text = scene_text;
  text.replace(text.find("sphere = {"),
               text.find('\n', text.find("sphere = {")) - text.find("sphere = {"),
               "mesh = { file = \"" + std::string(HVI_GEOMETRY_DATA) +
                   "/open_cube.stl\", unit = \"mm\", scale = 0.1 }");
  const fs::path out = fs::path(testing::TempDir()) / "hvi_geometry_refused";
  fs::remove_all(out);
  std::string err;
  EXPECT_EQ(run("geometry " + write_scene("refused.toml", text).string() + " --out " + out.string(),
                &err),
            2);
  EXPECT_NE(err.find("key 'body.projectile.mesh.file'"), std::string::npos) << err;
  EXPECT_NE(err.find("not closed: 4 border edges"), std::string::npos) << err;
  EXPECT_NE(err.find("nothing was run or written"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(out));
}

// The paper's scenes, coarsened so that the check is quick (the full ones: test_geometry_scale).
TEST(GeometryCommand, PaperScenesAreValid) {
  std::string err;
  EXPECT_EQ(run("check " + source +
                    "/cases/paper/study/panel.toml --set grid.cell_size=\"1 mm\" --set "
                    "refinement.impact.factor=2",
                &err),
            0)
      << err;
  EXPECT_EQ(
      run("check " + source + "/cases/paper/validation/panel.toml --set grid.cell_size=\"0.5 mm\"",
          &err),
      0)
      << err;
}

}  // namespace
