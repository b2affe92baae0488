#include "geometry/mesh_solid.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/cgal_mesh.hpp"
#include "geometry/surface.hpp"

namespace hvi::geometry {

namespace PMP = CGAL::Polygon_mesh_processing;

TriangleMesh read_surface(const std::string& path, const Placement& placement) {
  std::vector<cgal::Point3> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons) || polygons.empty())
    throw SurfaceError(
        "cannot read '" + path +
        "' as a triangle surface (STL ASCII or binary, OFF, OBJ, PLY; the format is taken from the "
        "file extension)");
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
