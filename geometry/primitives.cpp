#include "geometry/primitives.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace hvi::geometry {

namespace {

// Resolution of the inscribed polyhedra: a multiple of 4 around (so that the coordinate planes
// through the centre are mirror planes of the mesh) and an even number of latitude bands (so is
// the equator plane). Volume deficit of the 64 x 32 sphere mesh: about 0.5 %.
constexpr int kAround = 64;
constexpr int kBands = 32;

// cos and sin of 2 pi i / n (n a multiple of 4), computed in the first octant and mirrored, so that
// the points are exactly symmetric about both axes and the quarter points are exactly (0, +-1).
std::array<double, 2> unit_circle(int i, int n) {
  i = ((i % n) + n) % n;
  const int q = n / 4;
  if (i > 2 * q) {
    const auto p = unit_circle(n - i, n);
    return {p[0], -p[1]};
  }
  if (i > q) {
    const auto p = unit_circle(2 * q - i, n);
    return {-p[0], p[1]};
  }
  if (2 * i > q) {
    const auto p = unit_circle(q - i, n);
    return {p[1], p[0]};
  }
  const double phi = 2.0 * std::numbers::pi * i / n;
  return {std::cos(phi), std::sin(phi)};
}

void add_quad(TriangleMesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

}  // namespace

Bounds intersection(const Bounds& a, const Bounds& b) {
  Bounds r;
  for (int d = 0; d < 3; ++d) {
    r.lower[d] = std::max(a.lower[d], b.lower[d]);
    r.upper[d] = std::min(a.upper[d], b.upper[d]);
  }
  return r;
}

bool is_empty(const Bounds& b) {
  for (int d = 0; d < 3; ++d)
    if (!(b.upper[d] > b.lower[d])) return true;
  return false;
}

TriangleMesh box_surface(const Point& lower, const Point& upper) {
  TriangleMesh m;
  for (int c = 0; c < 8; ++c)  // corner c: bit 0 -> x, bit 1 -> y, bit 2 -> z at the upper side
    m.vertices.push_back(
        {c & 1 ? upper[0] : lower[0], c & 2 ? upper[1] : lower[1], c & 4 ? upper[2] : lower[2]});
  // Each face counter-clockwise seen from outside.
  add_quad(m, 0, 2, 3, 1);  // z-
  add_quad(m, 4, 5, 7, 6);  // z+
  add_quad(m, 0, 1, 5, 4);  // y-
  add_quad(m, 2, 6, 7, 3);  // y+
  add_quad(m, 0, 4, 6, 2);  // x-
  add_quad(m, 1, 3, 7, 5);  // x+
  return m;
}

bool Sphere::contains(const Point& x) const {
  double r2 = 0.0;
  for (int d = 0; d < 3; ++d) r2 += (x[d] - center_[d]) * (x[d] - center_[d]);
  return r2 < radius_ * radius_;
}
double Sphere::volume() const {
  return 4.0 / 3.0 * std::numbers::pi * radius_ * radius_ * radius_;
}
Bounds Sphere::bounds() const {
  Bounds b;
  for (int d = 0; d < 3; ++d) {
    b.lower[d] = center_[d] - radius_;
    b.upper[d] = center_[d] + radius_;
  }
  return b;
}

// A latitude-longitude sphere: poles on the z axis, kBands - 1 rings of kAround vertices. Each
// band quad is a planar isosceles trapezoid, so how it is split into triangles does not change
// the volume, and the mesh volume is mirror symmetric about x, y and z through the centre.
TriangleMesh Sphere::surface() const {
  TriangleMesh m;
  const auto& c = center_;
  m.vertices.push_back({c[0], c[1], c[2] + radius_});  // north pole: 0
  for (int j = 1; j < kBands; ++j) {
    const auto polar = unit_circle(j, 2 * kBands);  // cos, sin of the polar angle pi j / kBands
    for (int i = 0; i < kAround; ++i) {
      const auto around = unit_circle(i, kAround);
      m.vertices.push_back({c[0] + radius_ * polar[1] * around[0],
                            c[1] + radius_ * polar[1] * around[1], c[2] + radius_ * polar[0]});
    }
  }
  const auto south = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.push_back({c[0], c[1], c[2] - radius_});
  auto ring = [](int j, int i) {
    return static_cast<std::uint32_t>(1 + (j - 1) * kAround + (i % kAround));
  };
  for (int i = 0; i < kAround; ++i) {
    m.triangles.push_back({0, ring(1, i), ring(1, i + 1)});
    for (int j = 1; j + 1 < kBands; ++j)
      add_quad(m, ring(j, i), ring(j + 1, i), ring(j + 1, i + 1), ring(j, i + 1));
    m.triangles.push_back({south, ring(kBands - 1, i + 1), ring(kBands - 1, i)});
  }
  return m;
}

bool Box::contains(const Point& x) const {
  for (int d = 0; d < 3; ++d)
    if (x[d] < lower_[d] || x[d] >= upper_[d]) return false;
  return true;
}
double Box::volume() const {
  return (upper_[0] - lower_[0]) * (upper_[1] - lower_[1]) * (upper_[2] - lower_[2]);
}
Bounds Box::bounds() const {
  return {lower_, upper_};
}
TriangleMesh Box::surface() const {
  return box_surface(lower_, upper_);
}
std::unique_ptr<Solid> Box::exact_clip(const Bounds& box) const {
  const Bounds r = intersection(bounds(), box);
  Point upper = r.upper;
  for (int d = 0; d < 3; ++d) upper[d] = std::max(upper[d], r.lower[d]);  // empty: zero volume
  return std::make_unique<Box>(r.lower, upper);
}

bool Cylinder::contains(const Point& x) const {
  const double along = x[axis_] - base_[axis_];
  if (along < 0.0 || along >= length_) return false;
  double r2 = 0.0;
  for (int d = 0; d < 3; ++d)
    if (d != axis_) r2 += (x[d] - base_[d]) * (x[d] - base_[d]);
  return r2 < radius_ * radius_;
}
double Cylinder::volume() const {
  return std::numbers::pi * radius_ * radius_ * length_;
}
Bounds Cylinder::bounds() const {
  Bounds b;
  for (int d = 0; d < 3; ++d) {
    b.lower[d] = d == axis_ ? base_[d] : base_[d] - radius_;
    b.upper[d] = d == axis_ ? base_[d] + length_ : base_[d] + radius_;
  }
  return b;
}

// A prism on a regular kAround-gon inscribed in the circle; (u, v, axis) is right-handed.
TriangleMesh Cylinder::surface() const {
  const int u = (axis_ + 1) % 3, v = (axis_ + 2) % 3;
  TriangleMesh m;
  auto point = [&](double cu, double cv, double along) {
    Point p = base_;
    p[u] += cu;
    p[v] += cv;
    p[axis_] += along;
    return p;
  };
  for (int end = 0; end < 2; ++end)
    for (int i = 0; i < kAround; ++i) {
      const auto around = unit_circle(i, kAround);
      m.vertices.push_back(point(radius_ * around[0], radius_ * around[1], end * length_));
    }
  const auto bottom_center = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.push_back(point(0, 0, 0));
  m.vertices.push_back(point(0, 0, length_));
  const std::uint32_t top_center = bottom_center + 1;
  auto b = [](int i) { return static_cast<std::uint32_t>(i % kAround); };
  auto t = [](int i) { return static_cast<std::uint32_t>(kAround + i % kAround); };
  for (int i = 0; i < kAround; ++i) {
    add_quad(m, b(i), b(i + 1), t(i + 1), t(i));
    m.triangles.push_back({top_center, t(i), t(i + 1)});
    m.triangles.push_back({bottom_center, b(i + 1), b(i)});
  }
  return m;
}

}  // namespace hvi::geometry
