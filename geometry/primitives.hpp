#pragma once
// Analytic solids with an exact inside test and exact volume: the projectile shapes (sphere,
// cylinder, cube) and plates. Their surface() is for output and clipping: exact for the box, an
// inscribed polyhedron for the curved ones, symmetric about the coordinate planes through the
// centre so that a symmetry cut halves its volume exactly (see clipped_solid.hpp).
#include "geometry/solid.hpp"

namespace hvi::geometry {

class Sphere : public Solid {
 public:
  Sphere(Point center, double radius) : center_(center), radius_(radius) {}
  bool contains(const Point& x) const override;
  double volume() const override;
  Bounds bounds() const override;
  TriangleMesh surface() const override;
  bool convex() const override { return true; }

 private:
  Point center_;
  double radius_;
};

// Axis-aligned box [lower, upper).
class Box : public Solid {
 public:
  Box(Point lower, Point upper) : lower_(lower), upper_(upper) {}
  bool contains(const Point& x) const override;
  double volume() const override;
  Bounds bounds() const override;
  TriangleMesh surface() const override;
  std::unique_ptr<Solid> exact_clip(const Bounds& box) const override;
  bool convex() const override { return true; }

 private:
  Point lower_, upper_;
};

// Circular cylinder along a coordinate axis: base centre, axis (0, 1, 2), radius, length.
class Cylinder : public Solid {
 public:
  Cylinder(Point base_center, int axis, double radius, double length)
      : base_(base_center), axis_(axis), radius_(radius), length_(length) {}
  bool contains(const Point& x) const override;
  double volume() const override;
  Bounds bounds() const override;
  TriangleMesh surface() const override;
  bool convex() const override { return true; }

 private:
  Point base_;
  int axis_;
  double radius_, length_;
};

// The closed surface of an axis-aligned box (12 triangles, outward).
TriangleMesh box_surface(const Point& lower, const Point& upper);

}  // namespace hvi::geometry
