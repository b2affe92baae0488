// Inputs a hostile user (or a fuzzer) gave hvi that once crashed it, hung it or were read wrongly:
// each is now refused with the file, line, key and what was expected, before anything is built.
// Scenes: a honeycomb cell larger than its panel (was SIGSEGV in the core's triangulation), keys
// and table headers 50,000 levels deep (stack overflow in parsing), a clip at -1e300 m (a lattice
// range past its integer: a hang), a modulus whose wave speed is infinite (no time step at step
// 0), an angle given as a length. Surface files: OFF and PLY headers declaring more than the file
// holds or negative counts, a face list count of 4e9 (std::bad_alloc; now refused before the reader
// allocates), the texture variant STOFF (a CGAL read past its buffer under AddressSanitizer), a NaN
// vertex in a binary STL (mass nan), and a directory, FIFO, device or a NUL in the path given as
// the file. Bodies that overlap at the start (the overlap's mass counted twice) are named in a
// warning.
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <tuple>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cases/run/build_solver.hpp"
#include "cases/scene/scene.hpp"
#include "geometry/mesh_solid.hpp"
#include "tests/driver/scene_errors.hpp"
#include "tests/support/scene_text.hpp"

namespace hvi {
namespace {

namespace fs = std::filesystem;
using scene::test::error_for;

const std::string head = test::run_and_grid("1 us", R"(["-6 mm", "-6 mm", "-18 mm"])",
                                            R"(["6 mm", "6 mm", "4 mm"])", "0.5 mm") +
                         test::library_material("Al", "Al6061");

const std::string panel = test::PanelText{.front = "Al",
                                          .core = "Al",
                                          .rear = "Al",
                                          .core_height = "10 mm",
                                          .lower = R"(["-5 mm", "-5 mm"])",
                                          .upper = R"(["5 mm", "5 mm"])",
                                          .more = "top = \"0 mm\"\n"}
                              .text();

std::string with(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

bool says(const scene::Diagnostic& d, const std::string& words) {
  return d.message.find(words) != std::string::npos;
}

TEST(HostileScene, ACellLargerThanItsPanelIsRefusedAtItsKey) {
  const auto d = error_for(head + with(panel, "\"3 mm\"", "\"30 mm\""), "panel.p.cell_diameter");
  EXPECT_EQ(d.line, 20);  // head (10 lines and a blank), then the panel's tenth
  EXPECT_TRUE(says(d, "cells of 0.03 m do not fit in the panel, 0.01 m across")) << d.text();
}

TEST(HostileScene, KeysNestedThousandsDeepAreRefusedBeforeParsing) {
  std::string deep;
  for (int k = 0; k < 50000; ++k) deep += k ? ".a" : "a";
  for (const std::string& line : {deep + " = 1", "[" + deep + "]"}) {
    try {
      scene::parse_scene("title = \"x\"\n" + line + "\n", "deep.toml");
      ADD_FAILURE() << "accepted";
    } catch (const scene::SceneError& e) {
      const auto& d = e.diagnostics().front();
      EXPECT_EQ(d.line, 2);
      EXPECT_TRUE(says(d, "a key nested 50000 levels deep; scene keys nest at most 32"))
          << d.text();
    }
  }
}

// An upper bound at -1e300 m (the lattice range once overflowed its integer: a hang), and a clip
// that misses the grid.
TEST(HostileScene, AnEmptyOrFarClipIsRefused) {
  const std::string body = R"(
[[body]]
name = "ball"
material = "Al"
sphere = { center = [0, 0, 0], radius = "1 mm" }
clip = { lower = ["0 mm", "0 mm", LOWER], upper = ["1 mm", "1 mm", UPPER] }
)";
  const auto empty = with(with(body, "LOWER", "\"-1 mm\""), "UPPER", "\"-1e300 m\"");
  auto d = error_for(head + empty, "body.ball.clip");
  EXPECT_TRUE(says(d, "expected clip upper > lower on every axis; on z")) << d.text();
  const auto far = with(with(body, "LOWER", "\"1 m\""), "UPPER", "\"2 m\"");
  d = error_for(head + far, "body.ball.clip");
  EXPECT_TRUE(says(d, "misses the grid")) << d.text();
}

// A base value that the chosen resolution replaces is checked all the same.
TEST(HostileScene, ABaseValueAResolutionReplacesIsChecked) {
  const std::string scene = with(head, "\"0.5 mm\"", "\"nan mm\"") +
                            "[[body]]\nname = \"ball\"\nmaterial = \"Al\"\nsphere = { center = "
                            "[0, 0, 0], radius = \"1 mm\" }\n[resolutions.coarse]\n"
                            "\"grid.cell_size\" = \"1 mm\"\n";
  const auto d = error_for("resolution = \"coarse\"\n" + scene, "grid.cell_size");
  EXPECT_TRUE(says(d, "(the base value, which [resolutions.coarse] replaces)")) << d.text();
}

TEST(HostileScene, AnInfiniteWaveSpeedIsRefusedByCheck) {
  const auto d = error_for(
      with(head, "library = \"Al6061\"", "library = \"Al6061\"\nyoungs_modulus = 1.7e308"),
      "material.Al");
  EXPECT_TRUE(says(d, "its wave speed at the reference density is inf m/s")) << d.text();
}

TEST(HostileScene, AnAngleIsNoLength) {
  const auto d = error_for(with(head, "\"0.5 mm\"", "\"3.0 rad\""), "grid.cell_size");
  EXPECT_TRUE(says(d, "expected a length")) << d.text();
}

// A surface file in a fresh folder.
fs::path surface(const std::string& name, const std::string& bytes) {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_hostile_surfaces";
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << bytes;
  return dir / name;
}

std::string refusal(const fs::path& file) {
  try {
    geometry::read_surface(file.string(), {});
  } catch (const geometry::SurfaceError& e) {
    return e.what();
  }
  return "accepted";
}

// Box a is [0, 2] mm cubed and b [1, 3] x [0, 2] x [0, 2] mm, on
// 0.5 mm cells with 2 points per cell and axis: a's points at x = 1.125 ... 1.875 mm (4 layers of
// 8 x 8) lie in b, 4 mm^3 exactly; c, [3, 5] x [0, 2] x [0, 2] mm, only touches b.
TEST(HostileScene, BodiesThatOverlapAreNamed) {
  std::string text = test::run_and_grid("1 us", R"(["0 mm", "0 mm", "0 mm"])",
                                        R"(["5 mm", "3 mm", "3 mm"])", "0.5 mm") +
                     test::elastic_aluminium("al");
  for (const auto& [name, x0, x1] : {std::tuple{"a", 0, 2}, {"b", 1, 3}, {"c", 3, 5}})
    text += fmt::format(
        "[[body]]\nname = \"{}\"\nmaterial = \"al\"\nbox = {{ lower = [\"{} mm\", \"0 mm\", "
        "\"0 mm\"], upper = [\"{} mm\", \"2 mm\", \"2 mm\"] }}\n",
        name, x0, x1);
  const scene::Scene s = scene::parse_scene(text, "scene.toml", {});
  auto solver = driver::make_solver(s);
  std::vector<std::string> warnings;
  driver::add_bodies(s, *solver, 0, &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "bodies 'a' and 'b' overlap at the start: 256 points of 'a' (4e-09 m^3, 1.08e-05 kg) "
            "lie inside 'b', which has points of its own there; the overlap's mass counts twice");
}

TEST(HostileSurface, HeadersThatDeclareMoreThanTheFileHoldsAreRefused) {
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_NE(refusal(surface("big.off", "OFF\n1000000000 1 0\n" + tri + "3 0 1 2\n"))
                .find("declares 1000000000 vertices and 1 faces, more than its 45 bytes"),
            std::string::npos);
  EXPECT_NE(refusal(surface("neg.off", "OFF\n3 -1 0\n" + tri + "3 0 1 2\n"))
                .find("declares 3 vertices and -1 faces"),
            std::string::npos);
  EXPECT_NE(refusal(surface("list.off", "OFF\n3 1 0\n" + tri + "4000000000 0 1 2\n"))
                .find("face 1 declares 4000000000 corners, of 3 vertices"),
            std::string::npos);
  EXPECT_NE(refusal(surface("st.off", "STOFF\n3 1 0\n" + tri + "3 0 1 2\n"))
                .find("an OFF file starts with OFF (or COFF, NOFF, CNOFF), not 'STOFF'"),
            std::string::npos);
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 1000000000\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_NE(refusal(surface("big.ply", ply + tri + "3 0 1 2\n")).find("declares 1000000000"),
            std::string::npos);
}

// A closed 2 mm cube as binary STL, with one coordinate NaN.
TEST(HostileSurface, ANonFiniteVertexIsRefused) {
  const float V[8][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0},
                         {0, 0, 2}, {2, 0, 2}, {2, 2, 2}, {0, 2, 2}};
  const int F[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                        {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  std::string stl(80, '\0');
  const std::uint32_t n = 12;
  stl.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& f : F) {
    const float normal[3] = {0, 0, 0};
    stl.append(reinterpret_cast<const char*>(normal), 12);
    for (const int v : f) {
      float x[3] = {V[v][0], V[v][1], V[v][2]};
      if (v == 6) x[0] = std::numeric_limits<float>::quiet_NaN();
      stl.append(reinterpret_cast<const char*>(x), 12);
    }
    stl.append(2, '\0');
  }
  EXPECT_NE(refusal(surface("nan.stl", stl)).find("vertex 6 has a coordinate that is not a finite"),
            std::string::npos);
}

TEST(HostileSurface, ADirectoryFifoOrDeviceIsNotAFile) {
  const fs::path dir = fs::path(testing::TempDir()) / "hvi_hostile_kinds";
  fs::remove_all(dir);
  fs::create_directories(dir / "folder.stl");
  ASSERT_EQ(mkfifo((dir / "pipe.stl").c_str(), 0600), 0);
  for (const std::string& file :
       {(dir / "folder.stl").string(), (dir / "pipe.stl").string(), std::string("/dev/null")}) {
    const auto d =
        error_for(head + "[[body]]\nname = \"cad\"\nmaterial = \"Al\"\nmesh = { file = \"" + file +
                      "\", unit = \"mm\" }\n",
                  "body.cad.mesh.file");
    EXPECT_TRUE(says(d, "not a regular file (a directory, device or pipe)")) << d.text();
    EXPECT_NE(refusal(file).find("not a regular file"), std::string::npos) << file;
  }
  const auto d = error_for(head +
                               "[[body]]\nname = \"cad\"\nmaterial = \"Al\"\nmesh = { file = "
                               "\"cube\\u0000.stl\", unit = \"mm\" }\n",
                           "body.cad.mesh.file");
  EXPECT_TRUE(says(d, "the path holds a NUL character")) << d.text();
}

}  // namespace
}  // namespace hvi
