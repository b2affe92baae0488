#pragma once
// Analytic solids with an exact inside test and exact volume: the projectile shapes and simple
// plates. (Honeycomb panels and CAD surfaces come as meshes, see the geometry issue.)
#include <array>
#include <memory>

namespace hvi::geometry {

using Point = std::array<double, 3>;

struct Bounds {
  Point lower, upper;
};

class Solid {
 public:
  virtual ~Solid() = default;
  virtual bool contains(const Point& x) const = 0;
  virtual double volume() const = 0;  // exact, m^3
  virtual Bounds bounds() const = 0;
};

class Sphere : public Solid {
 public:
  Sphere(Point center, double radius) : center_(center), radius_(radius) {}
  bool contains(const Point& x) const override;
  double volume() const override;
  Bounds bounds() const override;

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

 private:
  Point base_;
  int axis_;
  double radius_, length_;
};

}  // namespace hvi::geometry
