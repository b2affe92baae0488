#pragma once
// What every body of a scene is to geometry/: a solid with an exact volume, bounds, an inside test
// and a closed outward triangle surface (for STL output and validation). Plain types only: no CGAL
// type appears in this header or in any header that mpm/ or cases/ include.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace hvi::geometry {

using Point = std::array<double, 3>;
using Point2 = std::array<double, 2>;

struct Bounds {
  Point lower, upper;
  bool contains(const Point& x) const {  // half-open [lower, upper), as the lattice cells
    for (int d = 0; d < 3; ++d)
      if (x[d] < lower[d] || x[d] >= upper[d]) return false;
    return true;
  }
};
Bounds intersection(const Bounds& a, const Bounds& b);  // may be empty (upper <= lower)
bool is_empty(const Bounds& b);

// An indexed triangle surface; each triangle counter-clockwise seen from outside.
struct TriangleMesh {
  std::vector<Point> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// A wall of a thin-walled structure (the honeycomb core): a vertical slab whose mid-surface is the
// segment a-b in plan, extruded over [z0, z1], of thickness `thickness`. `trim` is the length at
// each end (at a and at b) that overlaps the junction with the other walls: the wall's own volume
// is thickness x (|b - a| - trim[0] - trim[1]) x (z1 - z0), so that summed over all walls the
// junctions are counted once (see honeycomb.hpp).
struct ThinWall {
  Point2 a, b;
  double z0, z1;
  double thickness;
  std::array<double, 2> trim{0.0, 0.0};
};

class Solid {
 public:
  virtual ~Solid() = default;
  virtual bool contains(const Point& x) const = 0;
  virtual double volume() const = 0;  // exact, m^3
  virtual Bounds bounds() const = 0;
  // Closed, outward-oriented surface. Polyhedral solids give their exact surface; curved ones
  // (sphere, cylinder) an inscribed polyhedron fine enough for viewing and clipping ratios.
  virtual TriangleMesh surface() const = 0;
  // The part of the solid inside `box` when the solid can cut itself exactly (boxes, honeycomb
  // cores); nullptr otherwise, and clip() wraps it (clipped_solid.hpp).
  virtual std::unique_ptr<Solid> exact_clip(const Bounds& /*box*/) const { return nullptr; }
  // Convex solids are clipped without CGAL (surface.hpp: clip_convex_surface).
  virtual bool convex() const { return false; }
  // The mid-surface walls of a thin-walled solid, for the single-layer (point-type) sampling of
  // walls thinner than the point spacing; empty for ordinary solids.
  virtual std::vector<ThinWall> walls() const { return {}; }
  // The nominal thickness of its thinnest walls (0 for ordinary solids): decides whether the
  // walls are resolved by the lattice or sampled as single layers.
  virtual double wall_thickness() const { return 0.0; }
};

}  // namespace hvi::geometry
