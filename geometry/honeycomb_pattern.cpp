// The hexagonal cell pattern (eq. (6)), its walls and the closed-form solidity.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "geometry/honeycomb.hpp"

namespace hvi::geometry {

namespace {

const double kSqrt3 = std::sqrt(3.0);

// Exact values for rotations by multiples of 30 degrees where they are representable, so that a
// pattern at 0 or 90 degrees is exactly mirror symmetric (a symmetry cut then halves it exactly).
double snap(double v) {
  for (const double exact : {-1.0, -0.5, 0.0, 0.5, 1.0})
    if (std::fabs(v - exact) < 1e-15) return exact;
  return v;
}

// Liang-Barsky: clips the segment a + s (b - a), s in [0, 1], to the closed rectangle; returns
// false when nothing (or a round-off sliver) is left.
bool clip_segment(const Point2& a, const Point2& b, const Point2& lower, const Point2& upper,
                  double& s0, double& s1) {
  s0 = 0.0;
  s1 = 1.0;
  for (int d = 0; d < 2; ++d) {
    const double delta = b[d] - a[d];
    for (const auto& [p, q] :
         {std::pair{-delta, a[d] - lower[d]}, std::pair{delta, upper[d] - a[d]}}) {
      if (p == 0.0) {
        if (q < 0.0) return false;
      } else {
        const double r = q / p;
        if (p < 0.0)
          s0 = std::max(s0, r);
        else
          s1 = std::min(s1, r);
      }
    }
  }
  return s1 - s0 > 1e-12;  // a wall that only touches the rectangle (round-off) is not in it
}

}  // namespace

Bounds HoneycombPanel::front_box() const {
  return {{lower[0], lower[1], top - front_thickness}, {upper[0], upper[1], top}};
}
Bounds HoneycombPanel::core_box() const {
  const double z1 = top - front_thickness;
  return {{lower[0], lower[1], z1 - core_height + rear_gap}, {upper[0], upper[1], z1}};
}
Bounds HoneycombPanel::rear_box() const {
  const double z1 = top - front_thickness - core_height;
  return {{lower[0], lower[1], z1 - rear_thickness}, {upper[0], upper[1], z1}};
}

HexPattern::HexPattern(const HoneycombPanel& panel)
    : D_(panel.cell_diameter),
      cos_(snap(std::cos(panel.rotation))),
      sin_(snap(std::sin(panel.rotation))) {
  const double t = panel.wall_thickness;
  w_ = {panel.double_walls ? t : t / 2, t / 2, t / 2};
  // Where the lattice point (0, 0) goes: the chosen feature of the cell at (0, 0) sits at
  // pattern_origin. The vertex is the one at 90 degrees, (0, a); the wall middle (D/2, 0).
  Point2 feature{0.0, 0.0};
  if (panel.origin_at == PatternOrigin::vertex) feature = {0.0, D_ / kSqrt3};
  if (panel.origin_at == PatternOrigin::wall) feature = {D_ / 2, 0.0};
  origin_ = {panel.pattern_origin[0] - (cos_ * feature[0] - sin_ * feature[1]),
             panel.pattern_origin[1] - (sin_ * feature[0] + cos_ * feature[1])};

  // Junction trims. At a vertex one wall of each family meets; with e_i the three wall
  // directions (120 degrees apart) and w_i their half-thicknesses, the shrunk cell corners are
  // c_ij = (2/sqrt 3)(w_j e_i + w_i e_j). The walls cover the triangle T = (c_01, c_12, c_20)
  // plus, for wall i, the strip beyond the segment c_ij-c_ki, which starts on average
  // m_i = (w_j + w_k - w_i)/sqrt 3 from the vertex. Giving each wall a third-by-thickness share
  // of T, wall i counts as if it started trim_i = m_i - |T| / (6 w_i) from the vertex
  // (t / (4 sqrt 3) for equal walls: the junction deficit (sqrt 3 / 4) t^2 of the solidity).
  const std::array<Point2, 3> e{Point2{1.0, 0.0}, Point2{-0.5, kSqrt3 / 2},
                                Point2{-0.5, -kSqrt3 / 2}};
  std::array<Point2, 3> c;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    for (int d = 0; d < 2; ++d) c[i][d] = 2.0 / kSqrt3 * (w_[j] * e[i][d] + w_[i] * e[j][d]);
  }
  const double area_T = 0.5 * std::fabs((c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) -
                                        (c[2][0] - c[0][0]) * (c[1][1] - c[0][1]));
  for (int i = 0; i < 3; ++i) {
    const double m = (w_[(i + 1) % 3] + w_[(i + 2) % 3] - w_[i]) / kSqrt3;
    trim_[i] = t > 0 ? m - area_T / (6.0 * w_[i]) : 0.0;
  }
}

Point2 HexPattern::to_pattern(const Point2& p) const {
  const double x = p[0] - origin_[0], y = p[1] - origin_[1];
  return {cos_ * x + sin_ * y, -sin_ * x + cos_ * y};
}
Point2 HexPattern::to_scene(const Point2& q) const {
  return {origin_[0] + cos_ * q[0] - sin_ * q[1], origin_[1] + sin_ * q[0] + cos_ * q[1]};
}
Point2 HexPattern::local_center(long n, long m) const {
  return {static_cast<double>(n) * (D_ / 2), static_cast<double>(m) * (kSqrt3 * D_ / 2)};
}

std::vector<std::array<long, 2>> HexPattern::center_indices(const Point2& lower,
                                                            const Point2& upper) const {
  // The rectangle's corners in the pattern frame, widened by D (every wall of a cell lies within
  // a = D/sqrt 3 < D of its centre).
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  for (const Point2& corner :
       {lower, upper, Point2{lower[0], upper[1]}, Point2{upper[0], lower[1]}}) {
    const Point2 q = to_pattern(corner);
    for (int d = 0; d < 2; ++d) {
      lo[d] = std::min(lo[d], q[d] - D_);
      hi[d] = std::max(hi[d], q[d] + D_);
    }
  }
  const double dx = D_ / 2, dy = kSqrt3 * D_ / 2;
  std::vector<std::array<long, 2>> out;
  for (auto m = static_cast<long>(std::floor(lo[1] / dy));
       m <= static_cast<long>(std::ceil(hi[1] / dy)); ++m)
    for (auto n = static_cast<long>(std::floor(lo[0] / dx));
         n <= static_cast<long>(std::ceil(hi[0] / dx)); ++n) {
      if ((n + m) % 2 != 0) continue;  // eq. (6): n and m of the same parity
      // Keep the cell if its hexagon (circumradius a) can meet the rectangle.
      const Point2 c = to_scene(local_center(n, m));
      const double a = D_ / kSqrt3;
      if (c[0] + a < lower[0] || c[0] - a > upper[0] || c[1] + a < lower[1] || c[1] - a > upper[1])
        continue;
      out.push_back({n, m});
    }
  return out;
}

std::vector<Point2> HexPattern::centers(const Point2& lower, const Point2& upper) const {
  std::vector<Point2> out;
  for (const auto& [n, m] : center_indices(lower, upper))
    out.push_back(to_scene(local_center(n, m)));
  return out;
}

std::vector<WallLine> HexPattern::walls(const Point2& lower, const Point2& upper) const {
  // Each cell owns three of its six walls (normals at 0, 60 and 120 degrees); the other three
  // belong to the neighbours at 180, 240 and 300 degrees, so every wall is listed once.
  const double a = D_ / kSqrt3;
  const std::array<std::array<Point2, 2>, 3> owned{{{Point2{D_ / 2, -a / 2}, Point2{D_ / 2, a / 2}},
                                                    {Point2{D_ / 2, a / 2}, Point2{0.0, a}},
                                                    {Point2{0.0, a}, Point2{-D_ / 2, a / 2}}}};
  std::vector<WallLine> out;
  for (const auto& [n, m] : center_indices(lower, upper)) {
    const Point2 c = local_center(n, m);
    for (int family = 0; family < 3; ++family) {
      Point2 a0 = to_scene({c[0] + owned[family][0][0], c[1] + owned[family][0][1]});
      Point2 b0 = to_scene({c[0] + owned[family][1][0], c[1] + owned[family][1][1]});
      double thickness = 2 * w_[family];
      // A wall along a coordinate axis: cut its thickness across to the rectangle.
      for (int across = 0; across < 2; ++across) {
        if (std::fabs(b0[across] - a0[across]) > 1e-12 * a) continue;
        const double from = std::max(a0[across] - w_[family], lower[across]);
        const double to = std::min(a0[across] + w_[family], upper[across]);
        thickness = to - from;
        a0[across] = b0[across] = (from + to) / 2;
      }
      double s0, s1;
      if (!(thickness > 0.0) || !clip_segment(a0, b0, lower, upper, s0, s1)) continue;
      WallLine w;
      w.a = {a0[0] + s0 * (b0[0] - a0[0]), a0[1] + s0 * (b0[1] - a0[1])};
      w.b = {a0[0] + s1 * (b0[0] - a0[0]), a0[1] + s1 * (b0[1] - a0[1])};
      w.family = family;
      w.junction_a = s0 == 0.0;
      w.junction_b = s1 == 1.0;
      w.thickness = thickness;
      out.push_back(w);
    }
  }
  return out;
}

Point2 HexPattern::offset_from_center(const Point2& p) const {
  const Point2 q = to_pattern(p);
  const double dx = D_ / 2, dy = kSqrt3 * D_ / 2;
  // The nearest centre is the cell containing q (the hexagons are the Voronoi cells of the
  // lattice); it lies within a = D/sqrt 3 < dy of q, so in one of the three nearest rows.
  const auto m0 = static_cast<long>(std::lround(q[1] / dy));
  double best = std::numeric_limits<double>::infinity();
  Point2 d{};
  for (long m = m0 - 1; m <= m0 + 1; ++m) {
    // The n of parity m nearest to q[0] / dx.
    const long n = 2 * static_cast<long>(std::lround((q[0] / dx - static_cast<double>(m)) / 2)) + m;
    const Point2 c = local_center(n, m);
    const double r2 = (q[0] - c[0]) * (q[0] - c[0]) + (q[1] - c[1]) * (q[1] - c[1]);
    if (r2 < best) {
      best = r2;
      d = {q[0] - c[0], q[1] - c[1]};
    }
  }
  return d;
}

std::array<double, 3> HexPattern::side_distances(const Point2& p) const {
  const Point2 d = offset_from_center(p);
  return {std::fabs(d[0]), std::fabs(0.5 * d[0] + kSqrt3 / 2 * d[1]),
          std::fabs(-0.5 * d[0] + kSqrt3 / 2 * d[1])};
}

bool HexPattern::in_wall(const Point2& p) const {
  const std::array<double, 3> s = side_distances(p);
  // Outside the shrunk cell when past any of its three pairs of sides.
  for (int k = 0; k < 3; ++k)
    if (s[k] >= D_ / 2 - w_[k]) return true;
  return false;
}

int HexPattern::wall_family(const Point2& p) const {
  const std::array<double, 3> s = side_distances(p);
  return static_cast<int>(std::max_element(s.begin(), s.end()) - s.begin());
}

Point2 HexPattern::wall_direction(int family) const {
  // Family k's normal is at 60 k degrees in the pattern frame; its mid-line at 60 k + 90.
  const double angle = std::numbers::pi / 3 * family + std::numbers::pi / 2;
  const double c = std::cos(angle), s = std::sin(angle);
  return {cos_ * c - sin_ * s, sin_ * c + cos_ * s};
}

std::array<Point2, 6> HexPattern::cell_interior(long n, long m) const {
  // Sides at distance r_k = D/2 - w_k from the centre (families 1 and 2 are equal); corners from
  // the intersections of consecutive side lines, written with explicit signs so that the
  // hexagon is exactly mirror symmetric.
  const double r0 = D_ / 2 - w_[0], r1 = D_ / 2 - w_[1];
  const double y0 = (2 * r1 - r0) / kSqrt3, y1 = 2 * r1 / kSqrt3;
  const Point2 c = local_center(n, m);
  const std::array<Point2, 6> local{Point2{r0, -y0}, Point2{r0, y0},   Point2{0.0, y1},
                                    Point2{-r0, y0}, Point2{-r0, -y0}, Point2{0.0, -y1}};
  std::array<Point2, 6> out;
  for (int k = 0; k < 6; ++k) out[k] = to_scene({c[0] + local[k][0], c[1] + local[k][1]});
  return out;
}

double honeycomb_solidity(double D, double t, bool double_walls) {
  // Cell area (sqrt 3 / 2) D^2; the interior is the hexagon with side lines at r0 (the two
  // ribbon sides) and r1 (the four others), corners as in cell_interior().
  const double w0 = double_walls ? t : t / 2, w1 = t / 2;
  const double r0 = D / 2 - w0, r1 = D / 2 - w1;
  const double y0 = (2 * r1 - r0) / kSqrt3, y1 = 2 * r1 / kSqrt3;
  // Interior: rectangle 2 r0 x 2 y0 plus two triangles of base 2 r0 and height y1 - y0.
  const double interior = 4 * r0 * y0 + 2 * r0 * (y1 - y0);
  const double cell = kSqrt3 / 2 * D * D;
  return 1.0 - interior / cell;
}

}  // namespace hvi::geometry
