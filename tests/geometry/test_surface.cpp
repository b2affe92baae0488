// Surfaces: a broken or inside-out or self-intersecting surface is refused with a message that
// counts the problem; STL (ASCII and binary), OFF and OBJ files are read in a stated unit with a
// placement; a cut on a symmetry plane halves (quarters) a body's exact volume.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include "geometry/clipped_solid.hpp"
#include "geometry/mesh_solid.hpp"
#include "geometry/primitives.hpp"
#include "geometry/surface.hpp"

namespace hvi::geometry {
namespace {

namespace fs = std::filesystem;
constexpr double mm = 1e-3;

std::string temp_file(const std::string& name) {
  return (fs::path(testing::TempDir()) / name).string();
}

// The problem MeshSolid refuses `mesh` with ("" if accepted).
std::string refusal(TriangleMesh mesh) {
  try {
    MeshSolid solid(std::move(mesh));
  } catch (const SurfaceError& e) {
    return e.what();
  }
  return "";
}

TEST(Surface, BrokenStlFixtureIsRefusedWithItsBorderEdges) {
  // tests/geometry/data/open_cube.stl: a 10 mm cube, ASCII STL, without its top face (two
  // triangles): the four edges of the missing square are border edges.
  const TriangleMesh open =
      read_surface(std::string(HVI_GEOMETRY_DATA) + "/open_cube.stl", {.scale = mm});
  EXPECT_EQ(open.triangles.size(), 10u);
  EXPECT_EQ(open.vertices.size(), 8u);  // STL corners merged
  const SurfaceCheck check = check_surface(open);
  EXPECT_EQ(check.border_edges, 4u);
  EXPECT_EQ(refusal(open),
            "the surface is not closed: 4 border edges (edges with a triangle on one side only: a "
            "hole or a missing "
            "face)");
}

TEST(Surface, InsideOutAndSelfIntersectingSurfacesAreRefused) {
  TriangleMesh inverted = box_surface({0, 0, 0}, {1, 1, 1});
  for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
  const std::string inside_out = refusal(inverted);
  EXPECT_NE(inside_out.find("inside-out"), std::string::npos) << inside_out;
  EXPECT_NE(inside_out.find("-1 m^3"), std::string::npos) << inside_out;

  // Two overlapping cubes in one surface: closed and outward, but intersecting itself.
  TriangleMesh two = box_surface({0, 0, 0}, {1, 1, 1});
  const TriangleMesh other = box_surface({0.5, 0.5, 0.5}, {1.5, 1.5, 1.5});
  const auto offset = static_cast<std::uint32_t>(two.vertices.size());
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (auto t : other.triangles)
    two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const std::string crossing = refusal(two);
  EXPECT_NE(crossing.find("intersects itself"), std::string::npos) << crossing;

  // One flipped triangle.
  TriangleMesh flipped = box_surface({0, 0, 0}, {1, 1, 1});
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_EQ(check_surface(flipped).misoriented_edges, 3u);
  EXPECT_NE(refusal(flipped).find("not consistently oriented: 3 edges"), std::string::npos);

  EXPECT_EQ(refusal(box_surface({0, 0, 0}, {1, 2, 3})), "");
}

TEST(Surface, BinaryStlRoundTripWithPlacement) {
  const Sphere sphere({1 * mm, 2 * mm, 3 * mm}, 4 * mm);
  const std::string path = temp_file("sphere.stl");
  write_stl(sphere.surface(), path);
  const MeshSolid read(read_surface(path));
  // float32 coordinates: relative volume change ~1e-7.
  EXPECT_NEAR(read.volume() / enclosed_volume(sphere.surface()), 1.0, 1e-6);
  EXPECT_TRUE(read.contains({1 * mm, 2 * mm, 3 * mm}));
  EXPECT_FALSE(read.contains({1 * mm, 2 * mm, 7.5 * mm}));

  // The same file in mm, scaled x2, turned 90 degrees about z and moved.
  Placement placement{
      .scale = 2.0 * 1e3 * mm, .rotate = {0, 0, std::numbers::pi / 2}, .translate = {0, 0, 1}};
  const MeshSolid moved(read_surface(path, placement));
  EXPECT_NEAR(moved.volume() / (8 * read.volume()), 1.0, 1e-6);
  // Centre (1, 2, 3) mm x 2 -> (2, 4, 6) mm, turned -> (-4, 2, 6) mm, moved +1 m in z.
  EXPECT_TRUE(moved.contains({-4 * mm, 2 * mm, 1 + 6 * mm}));
  EXPECT_NEAR(moved.bounds().upper[2], 1 + 6 * mm + 8 * mm, 1e-6 * mm);
}

TEST(Surface, OffAndObjWithQuadFaces) {
  // A unit cube with quadrilateral faces, counter-clockwise from outside.
  const char* corners = "0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n";
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  {
    std::ofstream off(temp_file("cube.off"));
    off << "OFF\n8 6 0\n" << corners;
    for (const auto& f : faces)
      off << "4 " << f[0] << " " << f[1] << " " << f[2] << " " << f[3] << "\n";
    std::ofstream obj(temp_file("cube.obj"));
    std::string text = corners;
    for (std::size_t p = 0; p < text.size();) {  // "v x y z" lines
      obj << "v " << text.substr(p, text.find('\n', p) - p) << "\n";
      p = text.find('\n', p) + 1;
    }
    for (const auto& f : faces)
      obj << "f " << f[0] + 1 << " " << f[1] + 1 << " " << f[2] + 1 << " " << f[3] + 1 << "\n";
  }
  for (const char* name : {"cube.off", "cube.obj"}) {
    const MeshSolid cube(read_surface(temp_file(name), {.scale = 10 * mm}));
    EXPECT_NEAR(cube.volume(), 1e-6, 1e-18) << name;  // (10 mm)^3, exact in doubles to round-off
    EXPECT_TRUE(cube.contains({5 * mm, 5 * mm, 5 * mm}));
    EXPECT_FALSE(cube.contains({5 * mm, 5 * mm, 11 * mm}));
  }
  EXPECT_THROW(read_surface(temp_file("missing.stl")), SurfaceError);
}

TEST(ClippedSolid, SymmetryCutHalvesAndQuartersTheExactVolume) {
  const double R = 4.405 * mm;  // the 1 g projectile
  const Bounds half{{-1, 0, -1}, {1, 1, 1}}, quarter{{0, 0, -1}, {1, 1, 1}};
  auto sphere = [&] { return std::make_unique<Sphere>(Point{0, 0, 0}, R); };
  const double V = sphere()->volume();
  // Round-off of the two mesh volumes: 1e-13.
  EXPECT_NEAR(clip(sphere(), half)->volume() / (V / 2), 1.0, 1e-13);
  EXPECT_NEAR(clip(sphere(), quarter)->volume() / (V / 4), 1.0, 1e-13);
  const auto halved = clip(sphere(), half);
  EXPECT_TRUE(check_surface(halved->surface()).ok()) << check_surface(halved->surface()).problem();
  // A cylinder cut along its axis, and a CAD (mesh) body: the cut mesh itself is exact.
  auto cylinder = std::make_unique<Cylinder>(Point{0, 0, 0}, 2, R, 2 * R);
  const double Vc = cylinder->volume();
  EXPECT_NEAR(clip(std::move(cylinder), half)->volume() / (Vc / 2), 1.0, 1e-13);
  auto cube =
      std::make_unique<MeshSolid>(box_surface({-1 * mm, -1 * mm, 0}, {1 * mm, 1 * mm, 2 * mm}));
  EXPECT_NEAR(clip(std::move(cube), quarter)->volume() / 2e-9, 1.0, 1e-12);
  // A cut off the symmetry planes: the sphere cap of height R/2 has volume pi h^2 (3R - h)/3;
  // the 64 x 32 polyhedron gets the ratio to about 1e-3.
  const Bounds cap{{-1, -1, R / 2}, {1, 1, 1}};
  const double h = R / 2;
  EXPECT_NEAR(clip(sphere(), cap)->volume() / (std::numbers::pi * h * h * (3 * R - h) / 3), 1.0,
              2e-3);
  // Boxes cut themselves.
  EXPECT_DOUBLE_EQ(clip(std::make_unique<Box>(Point{-1, -1, -1}, Point{1, 1, 1}), half)->volume(),
                   4.0);
}

}  // namespace
}  // namespace hvi::geometry
