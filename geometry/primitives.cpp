#include "geometry/primitives.hpp"

#include <numbers>

namespace hvi::geometry {

bool Sphere::contains(const Point& x) const {
  double r2 = 0.0;
  for (int d = 0; d < 3; ++d) r2 += (x[d] - center_[d]) * (x[d] - center_[d]);
  return r2 < radius_ * radius_;
}
double Sphere::volume() const { return 4.0 / 3.0 * std::numbers::pi * radius_ * radius_ * radius_; }
Bounds Sphere::bounds() const {
  Bounds b;
  for (int d = 0; d < 3; ++d) {
    b.lower[d] = center_[d] - radius_;
    b.upper[d] = center_[d] + radius_;
  }
  return b;
}

bool Box::contains(const Point& x) const {
  for (int d = 0; d < 3; ++d)
    if (x[d] < lower_[d] || x[d] >= upper_[d]) return false;
  return true;
}
double Box::volume() const {
  return (upper_[0] - lower_[0]) * (upper_[1] - lower_[1]) * (upper_[2] - lower_[2]);
}
Bounds Box::bounds() const { return {lower_, upper_}; }

bool Cylinder::contains(const Point& x) const {
  const double along = x[axis_] - base_[axis_];
  if (along < 0.0 || along >= length_) return false;
  double r2 = 0.0;
  for (int d = 0; d < 3; ++d)
    if (d != axis_) r2 += (x[d] - base_[d]) * (x[d] - base_[d]);
  return r2 < radius_ * radius_;
}
double Cylinder::volume() const { return std::numbers::pi * radius_ * radius_ * length_; }
Bounds Cylinder::bounds() const {
  Bounds b;
  for (int d = 0; d < 3; ++d) {
    b.lower[d] = d == axis_ ? base_[d] : base_[d] - radius_;
    b.upper[d] = d == axis_ ? base_[d] + length_ : base_[d] + radius_;
  }
  return b;
}

}  // namespace hvi::geometry
