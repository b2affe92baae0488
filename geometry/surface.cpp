#include "geometry/surface.hpp"

#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "geometry/cgal_mesh.hpp"

namespace hvi::geometry {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace cgal {

Mesh to_cgal(const TriangleMesh& m) {
  std::vector<Point3> points;
  points.reserve(m.vertices.size());
  for (const auto& v : m.vertices) points.emplace_back(v[0], v[1], v[2]);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(m.triangles.size());
  for (const auto& t : m.triangles) polygons.push_back({t[0], t[1], t[2]});
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  return mesh;
}

TriangleMesh from_cgal(const Mesh& input) {
  Mesh m = input;
  if (!CGAL::is_triangle_mesh(m)) PMP::triangulate_faces(m);
  m.collect_garbage();
  TriangleMesh out;
  out.vertices.reserve(m.number_of_vertices());
  for (auto v : m.vertices()) {
    const Point3& p = m.point(v);
    out.vertices.push_back({p.x(), p.y(), p.z()});
  }
  for (auto f : m.faces()) {
    std::array<std::uint32_t, 3> t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m))
      t[k++] = static_cast<std::uint32_t>(v.idx());
    out.triangles.push_back(t);
  }
  return out;
}

}  // namespace cgal

namespace {
// "1 edge", "3 edges".
std::string count(std::size_t n, const char* noun) {
  return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}
}  // namespace

std::string SurfaceCheck::problem() const {
  if (triangles == 0) return "the surface has no triangles";
  if (border_edges > 0)
    return fmt::format(
        "the surface is not closed: {} (edges with a triangle on one side only: "
        "a hole or a missing face)",
        count(border_edges, "border edge"));
  if (non_manifold_edges > 0)
    return fmt::format("the surface is not a manifold: {} shared by more than two triangles",
                       count(non_manifold_edges, "edge"));
  if (misoriented_edges > 0)
    return fmt::format(
        "the surface is not consistently oriented: {} where the two triangles run "
        "the same way (some triangles are flipped)",
        count(misoriented_edges, "edge"));
  if (non_manifold_vertex)
    return "the surface is not a manifold: a vertex joins triangles that do not form one fan";
  if (degenerate_triangles > 0)
    return "the surface has " + count(degenerate_triangles, "degenerate (zero-area) triangle");
  if (self_intersections > 0)
    return fmt::format("the surface intersects itself: {} of triangles intersect",
                       count(self_intersections, "pair"));
  if (!outward)
    return fmt::format(
        "the surface is inside-out: its triangles face inward (enclosed volume {:.6g} m^3)",
        volume);
  if (!bounds_volume)
    return "the surface does not bound a volume (its shells are nested with inconsistent "
           "orientation)";
  return "";
}

SurfaceCheck check_surface(const TriangleMesh& mesh) {
  SurfaceCheck c;
  c.triangles = mesh.triangles.size();
  if (c.triangles == 0) return c;
  // Edge use from the index triangles: each undirected edge must be used exactly twice, once in
  // each direction, for a closed, manifold, consistently oriented surface.
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::array<int, 2>> edges;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      auto& use = edges[{std::min(a, b), std::max(a, b)}];
      ++use[a < b ? 0 : 1];
    }
  for (const auto& [edge, use] : edges) {
    const int n = use[0] + use[1];
    if (n == 1)
      ++c.border_edges;
    else if (n > 2)
      ++c.non_manifold_edges;
    else if (use[0] != 1)
      ++c.misoriented_edges;
  }
  if (c.border_edges || c.non_manifold_edges || c.misoriented_edges) return c;

  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : mesh.triangles) polygons.push_back({t[0], t[1], t[2]});
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    c.non_manifold_vertex = true;
    return c;
  }
  const cgal::Mesh m = cgal::to_cgal(mesh);
  for (auto f : m.faces())
    if (PMP::is_degenerate_triangle_face(f, m)) ++c.degenerate_triangles;
  if (c.degenerate_triangles) return c;
  if (PMP::does_self_intersect(m)) {
    std::vector<std::pair<cgal::Mesh::Face_index, cgal::Mesh::Face_index>> pairs;
    PMP::self_intersections(m, std::back_inserter(pairs));
    c.self_intersections = pairs.size();
    return c;
  }
  c.volume = PMP::volume(m);
  c.outward = PMP::is_outward_oriented(m);
  c.bounds_volume = PMP::does_bound_a_volume(m);
  return c;
}

TriangleMesh clip_surface(const TriangleMesh& mesh, const Bounds& box) {
  cgal::Mesh m = cgal::to_cgal(mesh);
  const cgal::Kernel::Iso_cuboid_3 cuboid(cgal::Point3(box.lower[0], box.lower[1], box.lower[2]),
                                          cgal::Point3(box.upper[0], box.upper[1], box.upper[2]));
  if (!PMP::clip(m, cuboid, CGAL::parameters::clip_volume(true)))
    throw std::runtime_error("CGAL could not clip the surface to a manifold");
  return cgal::from_cgal(m);
}

namespace {

// Keeps the part of a closed convex surface where side * (x[axis] - value) >= 0.
TriangleMesh clip_convex_half(const TriangleMesh& m, int axis, double value, double side) {
  std::vector<double> s(m.vertices.size());
  for (std::size_t v = 0; v < s.size(); ++v) s[v] = side * (m.vertices[v][axis] - value);
  TriangleMesh out;
  out.vertices = m.vertices;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> cut;  // edge -> new vertex
  auto crossing = [&](std::uint32_t a, std::uint32_t b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    if (auto it = cut.find(key); it != cut.end()) return it->second;
    const auto [u, v] = key;
    const double f = s[u] / (s[u] - s[v]);
    Point p;
    for (int d = 0; d < 3; ++d) p[d] = m.vertices[u][d] + f * (m.vertices[v][d] - m.vertices[u][d]);
    p[axis] = value;
    out.vertices.push_back(p);
    return cut[key] = static_cast<std::uint32_t>(out.vertices.size() - 1);
  };
  for (const auto& t : m.triangles) {
    if (s[t[0]] == 0 && s[t[1]] == 0 && s[t[2]] == 0)
      continue;  // in the plane: the cap replaces it
    // Sutherland-Hodgman against one plane; a triangle gives at most a quadrilateral.
    std::vector<std::uint32_t> polygon;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      if (s[a] >= 0) polygon.push_back(a);
      if ((s[a] > 0 && s[b] < 0) || (s[a] < 0 && s[b] > 0)) polygon.push_back(crossing(a, b));
    }
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      out.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
  }
  // Border edges (used once) outline the cut; the cap uses each in the opposite direction.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> use;
  for (const auto& t : out.triangles)
    for (int k = 0; k < 3; ++k) ++use[{t[k], t[(k + 1) % 3]}];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> border;
  for (const auto& [edge, n] : use)
    if (!use.count({edge.second, edge.first})) border.push_back(edge);
  if (border.empty()) return out;
  Point centre{0, 0, 0};
  for (const auto& [a, b] : border)
    for (int d = 0; d < 3; ++d)
      centre[d] += out.vertices[a][d] / static_cast<double>(border.size());
  centre[axis] = value;
  out.vertices.push_back(centre);
  const auto c = static_cast<std::uint32_t>(out.vertices.size() - 1);
  for (const auto& [a, b] : border) out.triangles.push_back({c, b, a});
  // Drop the vertices no triangle uses any more.
  std::vector<std::uint32_t> index(out.vertices.size(), UINT32_MAX);
  TriangleMesh compact;
  for (auto& t : out.triangles)
    for (auto& v : t) {
      if (index[v] == UINT32_MAX) {
        index[v] = static_cast<std::uint32_t>(compact.vertices.size());
        compact.vertices.push_back(out.vertices[v]);
      }
      v = index[v];
    }
  compact.triangles = std::move(out.triangles);
  return compact;
}

}  // namespace

TriangleMesh clip_convex_surface(const TriangleMesh& mesh, const Bounds& box) {
  TriangleMesh m = mesh;
  for (int axis = 0; axis < 3; ++axis) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& v : m.vertices) {
      lo = std::min(lo, v[axis]);
      hi = std::max(hi, v[axis]);
    }
    if (box.lower[axis] > lo) m = clip_convex_half(m, axis, box.lower[axis], +1.0);
    if (box.upper[axis] < hi) m = clip_convex_half(m, axis, box.upper[axis], -1.0);
  }
  return m;
}

double enclosed_volume(const TriangleMesh& mesh) {
  // Divergence theorem: V = sum over triangles of det(a, b, c) / 6 (relative to a reference
  // point, here the first vertex, to limit cancellation).
  if (mesh.vertices.empty()) return 0.0;
  const Point& o = mesh.vertices.front();
  double six_v = 0.0;
  for (const auto& t : mesh.triangles) {
    Point a, b, c;
    for (int d = 0; d < 3; ++d) {
      a[d] = mesh.vertices[t[0]][d] - o[d];
      b[d] = mesh.vertices[t[1]][d] - o[d];
      c[d] = mesh.vertices[t[2]][d] - o[d];
    }
    six_v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return six_v / 6.0;
}

void write_stl(const TriangleMesh& mesh, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  char header[80] = "binary STL written by hvi (units: m)";
  out.write(header, sizeof header);
  const auto n = static_cast<std::uint32_t>(mesh.triangles.size());
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : mesh.triangles) {
    const Point &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                 v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double normal[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                        u[0] * v[1] - u[1] * v[0]};
    const double length =
        std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    float record[12];
    for (int d = 0; d < 3; ++d) {
      record[d] = static_cast<float>(length > 0 ? normal[d] / length : 0.0);
      record[3 + d] = static_cast<float>(a[d]);
      record[6 + d] = static_cast<float>(b[d]);
      record[9 + d] = static_cast<float>(c[d]);
    }
    out.write(reinterpret_cast<const char*>(record), sizeof record);
    const std::uint16_t attribute = 0;
    out.write(reinterpret_cast<const char*>(&attribute), 2);
  }
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace hvi::geometry
