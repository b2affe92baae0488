#include "geometry/mesh_solid.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "geometry/cgal_mesh.hpp"
#include "geometry/surface.hpp"

namespace hvi::geometry {

namespace PMP = CGAL::Polygon_mesh_processing;
namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw SurfaceError("cannot read '" + path + "': " + why);
}

// The counts an OFF or PLY header declares, checked against what the file can hold before the
// reader allocates for them: an ASCII vertex takes at least 6 bytes ("0 0 0\n"), a face 4.
void check_counts(const std::string& path, long long vertices, long long faces,
                  std::uintmax_t bytes) {
  if (vertices < 0 || faces < 0)
    refuse(path, fmt::format("the header declares {} vertices and {} faces", vertices, faces));
  if (static_cast<long double>(vertices) * 6 + static_cast<long double>(faces) * 4 >
      static_cast<long double>(bytes))
    refuse(path, fmt::format("the header declares {} vertices and {} faces, more than its {} "
                             "bytes can hold (a truncated or damaged file)",
                             vertices, faces, bytes));
}

// The next line of an OFF file that holds data (not blank, not a # comment); false at the end.
bool next_data_line(std::istream& in, std::string& line) {
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first != std::string::npos && line[first] != '#') return true;
  }
  return false;
}

// Each OFF face line starts with its number of corners, which the reader allocates before it
// reads them (a count of 4e9 once took 32 GB): at least 1 and at most the vertices. A file that
// ends early is left to the reader, which says so.
void check_off_faces(const std::string& path, std::istream& in, long long vertices,
                     long long faces) {
  std::string line;
  std::getline(in, line);  // the rest of the counts line
  for (long long v = 0; v < vertices; ++v)
    if (!next_data_line(in, line)) return;
  for (long long f = 0; f < faces; ++f) {
    if (!next_data_line(in, line)) return;
    std::istringstream words(line);
    long long corners = 0;
    if (words >> corners && (corners < 1 || corners > vertices))
      refuse(path, fmt::format("face {} declares {} corners, of {} vertices (a damaged file)",
                               f + 1, corners, vertices));
  }
}

// OFF: the plain "OFF" header (or COFF, NOFF, CNOFF) and its counts; texture and binary variants
// are refused (CGAL's scanner of the "ST" variant reads past its buffer).
void check_off_header(const std::string& path, std::istream& in, std::uintmax_t bytes) {
  std::string magic;
  in >> magic;
  if (magic != "OFF" && magic != "COFF" && magic != "NOFF" && magic != "CNOFF")
    refuse(path, fmt::format("an OFF file starts with OFF (or COFF, NOFF, CNOFF), not '{}'",
                             magic.substr(0, 16)));
  long long vertices = 0, faces = 0;
  if (!(in >> vertices >> faces)) refuse(path, "no vertex and face counts after OFF");
  check_counts(path, vertices, faces, bytes);
  check_off_faces(path, in, vertices, faces);
}

// PLY: the counts of its "element vertex" and "element face" lines.
void check_ply_header(const std::string& path, std::istream& in, std::uintmax_t bytes) {
  long long vertices = 0, faces = 0;
  std::string line;
  for (int n = 0; std::getline(in, line) && line.rfind("end_header", 0) != 0; ++n) {
    if (n > 1000) refuse(path, "no end_header in the first 1000 lines");
    std::istringstream words(line);
    std::string keyword, element;
    long long count = 0;
    if (words >> keyword >> element >> count && keyword == "element")
      (element == "vertex" ? vertices : faces) += count;
  }
  check_counts(path, vertices, faces, bytes);
}

// What a reader must not meet: a file that is not a regular file, and OFF or PLY headers that
// declare more than the file holds.
void check_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) refuse(path, "not a regular file");
  const std::uintmax_t bytes = fs::file_size(path, ec);
  std::ifstream in(path, std::ios::binary);
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == ".off") check_off_header(path, in, bytes);
  if (extension == ".ply") check_ply_header(path, in, bytes);
}

}  // namespace

TriangleMesh read_surface(const std::string& path, const Placement& placement) {
  check_file(path);
  std::vector<cgal::Point3> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool read = false;
  try {
    read = CGAL::IO::read_polygon_soup(path, points, polygons);
  } catch (const std::bad_alloc&) {
    refuse(path, "a count in it is larger than the file can hold (a damaged file)");
  } catch (const std::length_error&) {
    refuse(path, "a count in it is larger than the file can hold (a damaged file)");
  }
  if (!read || polygons.empty())
    throw SurfaceError(
        "cannot read '" + path +
        "' as a triangle surface (STL ASCII or binary, OFF, OBJ, PLY; the format is taken from the "
        "file extension)");
  for (std::size_t k = 0; k < points.size(); ++k)
    if (!(std::isfinite(points[k].x()) && std::isfinite(points[k].y()) &&
          std::isfinite(points[k].z())))
      refuse(path, fmt::format("vertex {} has a coordinate that is not a finite number", k));
  for (const auto& polygon : polygons)
    for (const std::size_t v : polygon)
      if (v >= points.size())
        refuse(path, fmt::format("a face names vertex {} of {}", v, points.size()));
  // STL stores each triangle's corners separately; OFF/OBJ/PLY may repeat points too.
  PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  const Point& r = placement.rotate;
  const double cx = std::cos(r[0]), sx = std::sin(r[0]), cy = std::cos(r[1]), sy = std::sin(r[1]),
               cz = std::cos(r[2]), sz = std::sin(r[2]);
  // R = Rz Ry Rx.
  const double R[3][3] = {{cz * cy, cz * sy * sx - sz * cx, cz * sy * cx + sz * sx},
                          {sz * cy, sz * sy * sx + cz * cx, sz * sy * cx - cz * sx},
                          {-sy, cy * sx, cy * cx}};
  TriangleMesh mesh;
  mesh.vertices.reserve(points.size());
  for (const auto& p : points) {
    const double x[3] = {placement.scale * p.x(), placement.scale * p.y(), placement.scale * p.z()};
    Point y;
    for (int i = 0; i < 3; ++i)
      y[i] = R[i][0] * x[0] + R[i][1] * x[1] + R[i][2] * x[2] + placement.translate[i];
    mesh.vertices.push_back(y);
  }
  // Polygons with more than three corners are split into a fan (planar convex faces of OFF/OBJ).
  for (const auto& polygon : polygons)
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      mesh.triangles.push_back({static_cast<std::uint32_t>(polygon[0]),
                                static_cast<std::uint32_t>(polygon[k]),
                                static_cast<std::uint32_t>(polygon[k + 1])});
  return mesh;
}

struct MeshSolid::Impl {
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<cgal::Mesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<cgal::Kernel, Primitive>>;
  cgal::Mesh mesh;
  Tree tree;
  std::unique_ptr<CGAL::Side_of_triangle_mesh<cgal::Mesh, cgal::Kernel>> side;
};

MeshSolid::MeshSolid(TriangleMesh surface) : surface_(std::move(surface)) {
  const SurfaceCheck check = check_surface(surface_);
  if (!check.ok()) throw SurfaceError(check.problem());
  volume_ = check.volume;
  impl_ = std::make_unique<Impl>();
  impl_->mesh = cgal::to_cgal(surface_);
  impl_->tree.insert(faces(impl_->mesh).first, faces(impl_->mesh).second, impl_->mesh);
  impl_->tree.build();
  impl_->side =
      std::make_unique<CGAL::Side_of_triangle_mesh<cgal::Mesh, cgal::Kernel>>(impl_->tree);
  for (int d = 0; d < 3; ++d) {
    bounds_.lower[d] = std::numeric_limits<double>::infinity();
    bounds_.upper[d] = -std::numeric_limits<double>::infinity();
  }
  for (const auto& v : surface_.vertices)
    for (int d = 0; d < 3; ++d) {
      bounds_.lower[d] = std::min(bounds_.lower[d], v[d]);
      bounds_.upper[d] = std::max(bounds_.upper[d], v[d]);
    }
}

MeshSolid::~MeshSolid() = default;
MeshSolid::MeshSolid(MeshSolid&&) noexcept = default;

bool MeshSolid::contains(const Point& x) const {
  for (int d = 0; d < 3; ++d)
    if (x[d] < bounds_.lower[d] || x[d] > bounds_.upper[d]) return false;
  return (*impl_->side)(cgal::Point3(x[0], x[1], x[2])) == CGAL::ON_BOUNDED_SIDE;
}

}  // namespace hvi::geometry
