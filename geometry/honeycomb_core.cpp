// The honeycomb core as a solid: its plan (the extent minus the shrunk cells) is built with CGAL
// 2D polygon booleans on exact coordinates, measured exactly, triangulated (constrained
// Delaunay) and extruded over the core height into a closed surface.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <list>
#include <stdexcept>

#include "geometry/honeycomb.hpp"
#include "geometry/primitives.hpp"

namespace hvi::geometry {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Polygon = CGAL::Polygon_2<K>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<K>;

struct FaceInfo {
  int nesting = -1;
  bool in_domain() const { return nesting % 2 == 1; }
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, K>;
using Fbb = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbb>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_intersections_tag>;

// Nesting level of each face: 0 outside, 1 inside a boundary, 2 inside a hole, ... (the
// flood fill of CGAL's polygon triangulation example); the region is the odd levels.
void mark_domains(Cdt& cdt) {
  std::list<Cdt::Edge> border;
  auto fill = [&](Cdt::Face_handle start, int level) {
    if (start->info().nesting != -1) return;
    std::list<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      const Cdt::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info().nesting != -1) continue;
      f->info().nesting = level;
      for (int i = 0; i < 3; ++i) {
        const Cdt::Face_handle n = f->neighbor(i);
        if (n->info().nesting != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(f, i)))
          border.push_back(Cdt::Edge(f, i));
        else
          queue.push_back(n);
      }
    }
  };
  fill(cdt.infinite_face(), 0);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    fill(e.first->neighbor(e.second), e.first->info().nesting + 1);
  }
}

Polygon polygon_of(const std::array<Point2, 6>& corners) {
  Polygon p;
  for (const auto& c : corners) p.push_back(K::Point_2(c[0], c[1]));
  return p;
}

}  // namespace

HoneycombCore::HoneycombCore(const HoneycombPanel& panel, const Bounds& region)
    : panel_(panel), pattern_(panel), region_(region) {
  for (int d = 0; d < 3; ++d) region_.upper[d] = std::max(region_.upper[d], region_.lower[d]);
  if (is_empty(region_)) return;
  const Point2 lo{region_.lower[0], region_.lower[1]}, hi{region_.upper[0], region_.upper[1]};
  Polygon rectangle;
  rectangle.push_back(K::Point_2(lo[0], lo[1]));
  rectangle.push_back(K::Point_2(hi[0], lo[1]));
  rectangle.push_back(K::Point_2(hi[0], hi[1]));
  rectangle.push_back(K::Point_2(lo[0], hi[1]));

  // Cells strictly inside the rectangle are holes as they are; cells crossing its boundary are
  // cut from it with a boolean difference (the cells are disjoint: walls t > 0 separate them).
  std::vector<Polygon> inner;
  CGAL::Polygon_set_2<K> cut(rectangle);
  for (const auto& [n, m] : pattern_.center_indices(lo, hi)) {
    const auto corners = pattern_.cell_interior(n, m);
    bool all_inside = true, all_outside_one_side[4] = {true, true, true, true};
    for (const auto& c : corners) {
      all_inside &= c[0] > lo[0] && c[0] < hi[0] && c[1] > lo[1] && c[1] < hi[1];
      all_outside_one_side[0] &= c[0] <= lo[0];
      all_outside_one_side[1] &= c[0] >= hi[0];
      all_outside_one_side[2] &= c[1] <= lo[1];
      all_outside_one_side[3] &= c[1] >= hi[1];
    }
    if (std::any_of(std::begin(all_outside_one_side), std::end(all_outside_one_side),
                    [](bool b) { return b; }))
      continue;
    if (all_inside)
      inner.push_back(polygon_of(corners));
    else
      cut.difference(polygon_of(corners));
  }
  std::vector<PolygonWithHoles> parts;
  cut.polygons_with_holes(std::back_inserter(parts));

  // Exact plan area: the cut rectangle minus the inner cells.
  K::FT area = 0;
  for (const auto& part : parts) {
    area += part.outer_boundary().area();
    for (auto h = part.holes_begin(); h != part.holes_end(); ++h) area -= CGAL::abs(h->area());
  }
  for (const auto& hole : inner) area -= hole.area();
  // Rounded from the exact value (not the lazy interval): a cut on a mirror plane of the pattern
  // then gives exactly half of the double.
  plan_area_ = CGAL::to_double(CGAL::exact(area));

  // Triangulate the plan: every boundary is a constraint; the region is the odd nesting levels.
  if (parts.empty() && inner.empty())
    throw std::invalid_argument(
        "the honeycomb core has no wall inside its region (its cells are larger than the region "
        "the panel or its clip leaves)");
  Cdt cdt;
  auto insert = [&](const Polygon& p) {
    cdt.insert_constraint(p.vertices_begin(), p.vertices_end(), true);
  };
  for (const auto& part : parts) {
    insert(part.outer_boundary());
    for (auto h = part.holes_begin(); h != part.holes_end(); ++h) insert(*h);
  }
  for (const auto& hole : inner) insert(hole);
  mark_domains(cdt);
  constexpr auto unset = std::numeric_limits<std::uint32_t>::max();
  for (auto v : cdt.finite_vertex_handles()) v->info() = unset;
  auto index = [&](Cdt::Vertex_handle v) {
    if (v->info() == unset) {
      v->info() = static_cast<std::uint32_t>(plan_vertices_.size());
      plan_vertices_.push_back({CGAL::to_double(v->point().x()), CGAL::to_double(v->point().y())});
    }
    return v->info();
  };
  for (auto f : cdt.finite_face_handles()) {
    if (!f->info().in_domain()) continue;
    plan_triangles_.push_back({index(f->vertex(0)), index(f->vertex(1)), index(f->vertex(2))});
    for (int i = 0; i < 3; ++i)
      if (!f->neighbor(i)->info().in_domain())  // a boundary edge, the region on its left
        plan_boundary_.push_back({index(f->vertex(Cdt::ccw(i))), index(f->vertex(Cdt::cw(i)))});
  }
}

bool HoneycombCore::contains(const Point& x) const {
  return region_.contains(x) && pattern_.in_wall({x[0], x[1]});
}

TriangleMesh HoneycombCore::surface() const {
  // Bottom copy of the plan vertices at z0 (indices k), top copy at z1 (N + k).
  TriangleMesh m;
  const auto N = static_cast<std::uint32_t>(plan_vertices_.size());
  for (int level = 0; level < 2; ++level)
    for (const auto& p : plan_vertices_)
      m.vertices.push_back({p[0], p[1], level ? region_.upper[2] : region_.lower[2]});
  for (const auto& t : plan_triangles_) {
    m.triangles.push_back({N + t[0], N + t[1], N + t[2]});  // top, facing +z
    m.triangles.push_back({t[0], t[2], t[1]});              // bottom, facing -z
  }
  for (const auto& [p, q] : plan_boundary_) {  // side quads, facing away from the region
    m.triangles.push_back({p, q, N + q});
    m.triangles.push_back({p, N + q, N + p});
  }
  return m;
}

std::unique_ptr<Solid> HoneycombCore::exact_clip(const Bounds& box) const {
  return std::make_unique<HoneycombCore>(panel_, intersection(region_, box));
}

std::vector<ThinWall> HoneycombCore::walls() const {
  std::vector<ThinWall> out;
  if (is_empty(region_)) return out;
  for (const auto& w :
       pattern_.walls({region_.lower[0], region_.lower[1]}, {region_.upper[0], region_.upper[1]})) {
    const double trim = pattern_.junction_trim(w.family);
    out.push_back({w.a,
                   w.b,
                   region_.lower[2],
                   region_.upper[2],
                   w.thickness,
                   {w.junction_a ? trim : 0.0, w.junction_b ? trim : 0.0}});
  }
  return out;
}

PanelSolids make_panel(const HoneycombPanel& panel, const Bounds* clip) {
  auto cut = [clip](Bounds b) {
    if (clip) b = intersection(b, *clip);
    for (int d = 0; d < 3; ++d) b.upper[d] = std::max(b.upper[d], b.lower[d]);
    return b;
  };
  const Bounds front = cut(panel.front_box()), rear = cut(panel.rear_box());
  return {std::make_unique<Box>(front.lower, front.upper),
          std::make_unique<HoneycombCore>(panel, cut(panel.core_box())),
          std::make_unique<Box>(rear.lower, rear.upper)};
}

}  // namespace hvi::geometry
