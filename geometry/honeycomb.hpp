#pragma once
// The honeycomb sandwich panel of the paper (Section 2.1, Fig. 1; Section 2.4, eqs. (6)-(7)):
// a front facesheet, a hexagonal-cell core and a rear facesheet.
//
// Conventions (SI): the panel lies in the x-y plane and the projectile travels along -z. With
// `top` the z of the front face,
//   front facesheet  z in [top - t_f, top]
//   core             z in [top - t_f - S, top - t_f]
//   rear facesheet   z in [top - t_f - S - t_r, top - t_f - S]
// and every part spans the in-plane extent [lower, upper].
//
// Cell pattern. In the pattern frame (x', y') the hexagon centres are, by eq. (6),
//   (x_c, y_c) = (n D/2, m sqrt(3) D/2)  with n + m even,
// so that neighbouring centres are D = D_hc apart and the wall mid-surfaces lie D/2 from each
// centre: D_hc is the inscribed-circle diameter measured between wall mid-surfaces (flat to
// flat). The hexagon sides have outward normals at 0, 60, ..., 300 degrees; the wall edge is
// a = D/sqrt(3). The pattern frame is rotated by `rotation` about z and placed so that a cell
// centre (or a wall vertex, or the middle of a wall) sits at `pattern_origin`.
//
// Walls. The core is the extent minus the cell interiors, each cell being its hexagon shrunk by
// half the wall thickness on each side, so the walls meet at exact 120-degree joins. With
// `double_walls`, the walls normal to x' (parallel to y': the ribbon direction of expanded
// honeycomb, where the foils are bonded) are 2 t_hc thick.
#include <array>
#include <vector>

#include "geometry/solid.hpp"

namespace hvi::geometry {

enum class PatternOrigin { cell_center, vertex, wall };

struct HoneycombPanel {
  double front_thickness = 0.0;  // t_f
  double rear_thickness = 0.0;   // t_r
  double wall_thickness = 0.0;   // t_hc
  double cell_diameter = 0.0;    // D_hc
  double core_height = 0.0;      // S
  Point2 lower{}, upper{};       // in-plane extent
  double top = 0.0;              // z of the front face
  double rotation = 0.0;         // of the cell pattern about z, rad
  Point2 pattern_origin{0.0, 0.0};
  PatternOrigin origin_at = PatternOrigin::cell_center;
  bool double_walls = false;
  double rear_gap = 0.0;  // the core ends this far above the rear facesheet

  Bounds front_box() const;
  Bounds core_box() const;
  Bounds rear_box() const;
};

// A wall in plan, clipped to a rectangle: its mid-line a-b and thickness. A junction end is a
// vertex where three walls meet (not a cut by the rectangle). A wall cut obliquely by the
// rectangle keeps its thickness (a strip cut by a line has the area of its mid-line times its
// width); a wall parallel to an edge of the rectangle and cut along its length (e.g. lying on a
// symmetry plane) keeps only the part of its thickness inside, with the mid-line moved to the
// middle of that part.
struct WallLine {
  Point2 a, b;
  int family;  // 0: normal to x' (the ribbon walls), 1: normal at 60 degrees, 2: at 120 degrees
  bool junction_a, junction_b;
  double thickness;
};

// The hexagonal cell pattern of a panel.
class HexPattern {
 public:
  explicit HexPattern(const HoneycombPanel& panel);
  double cell_diameter() const { return D_; }
  double half_thickness(int family) const { return w_[family]; }
  // Pattern frame <-> scene frame (in plan).
  Point2 to_pattern(const Point2& p) const;
  Point2 to_scene(const Point2& q) const;
  // Centres (scene frame) of every cell whose hexagon meets the rectangle, eq. (6).
  std::vector<Point2> centers(const Point2& lower, const Point2& upper) const;
  // The lattice indices (n, m) of those centres (x' = n D/2, y' = m sqrt(3) D/2).
  std::vector<std::array<long, 2>> center_indices(const Point2& lower, const Point2& upper) const;
  // Every wall mid-line that meets the rectangle, clipped to it, each wall once.
  std::vector<WallLine> walls(const Point2& lower, const Point2& upper) const;
  // Is the plan point in a wall (outside every shrunk cell)?
  bool in_wall(const Point2& p) const;
  // The family of the wall nearest the plan point (as WallLine's): the side of its nearest cell
  // centre c whose outward normal, at a multiple of 60 degrees, is closest in angle to p - c.
  int wall_family(const Point2& p) const;
  // A wall of `family`'s unit mid-line direction in plan (scene frame; its sign is arbitrary).
  Point2 wall_direction(int family) const;
  // The corners (scene frame, counter-clockwise) of the shrunk cell around centre (n, m).
  std::array<Point2, 6> cell_interior(long n, long m) const;
  // Volume trimmed off a wall end of `family` at a junction, as a length: see walls().
  double junction_trim(int family) const { return trim_[family]; }

 private:
  Point2 local_center(long n, long m) const;
  // p - c in the pattern frame, c the nearest cell centre (the cell holding p).
  Point2 offset_from_center(const Point2& p) const;
  // |n_k . (p - c)| for the three side normals n_k (0, 60, 120 degrees): the distance from the
  // centre towards each pair of sides.
  std::array<double, 3> side_distances(const Point2& p) const;
  double D_;
  std::array<double, 3> w_;  // half wall thickness per family
  std::array<double, 3> trim_;
  double cos_, sin_;
  Point2 origin_;  // scene position of the lattice point (0, 0)
};

// Closed-form area fraction of the core in plan for an unbounded pattern (the honeycomb
// solidity): per cell, hexagon area (sqrt(3)/2) D^2 minus the shrunk interior. For single walls
// this is (2 t / D)(1 - t / (2 D)) (Gibson & Ashby's rho*/rho_s with l = D/sqrt(3)).
double honeycomb_solidity(double cell_diameter, double wall_thickness, bool double_walls);

// The core within `region` (the panel's extent and core z-range, possibly cut further by a clip
// box): exact inside test, exact volume (plan area from CGAL 2D polygon booleans times height),
// closed surface (the plan triangulated and extruded), and its walls for point-type sampling.
class HoneycombCore : public Solid {
 public:
  HoneycombCore(const HoneycombPanel& panel, const Bounds& region);
  bool contains(const Point& x) const override;
  double volume() const override { return plan_area_ * (region_.upper[2] - region_.lower[2]); }
  Bounds bounds() const override { return region_; }
  TriangleMesh surface() const override;
  std::unique_ptr<Solid> exact_clip(const Bounds& box) const override;
  std::vector<ThinWall> walls() const override;
  double plan_area() const { return plan_area_; }
  double wall_thickness() const override { return panel_.wall_thickness; }
  const HexPattern& pattern() const { return pattern_; }

 private:
  HoneycombPanel panel_;
  HexPattern pattern_;
  Bounds region_;
  // The plan region triangulated: vertices (x, y), triangles counter-clockwise, and the boundary
  // edges (vertex pairs with the region on their left).
  std::vector<Point2> plan_vertices_;
  std::vector<std::array<std::uint32_t, 3>> plan_triangles_;
  std::vector<std::array<std::uint32_t, 2>> plan_boundary_;
  double plan_area_ = 0.0;
};

// The three parts of a panel, each cut to `clip` when given.
struct PanelSolids {
  std::unique_ptr<Solid> front, core, rear;
};
PanelSolids make_panel(const HoneycombPanel& panel, const Bounds* clip = nullptr);

}  // namespace hvi::geometry
