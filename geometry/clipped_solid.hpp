#pragma once
// clip(solid, box): the part of a solid inside an axis-aligned box, for half and quarter models
// cut on the symmetry planes of the MPM grid.
//
// Its exact volume: a solid that can cut itself exactly does so (Box, HoneycombCore). Otherwise
//   V_clipped = V_solid * V(S ∩ box) / V(S),
// with S the solid's closed surface and S ∩ box cut by CGAL (PMP::clip, clip_volume), or, for
// convex solids, plane by plane without new points where S already has them. For a
// polyhedral solid (a CAD surface) S is the solid and this is exact. For a sphere or a cylinder S
// is an inscribed polyhedron that is mirror symmetric about the coordinate planes through the
// centre (primitives.cpp), so a cut on such a plane gives exactly 1/2 (two cuts 1/4) to
// round-off; any other cut is as accurate as the polyhedron (64 segments around).
#include <memory>

#include "geometry/solid.hpp"

namespace hvi::geometry {

class ClippedSolid : public Solid {
 public:
  ClippedSolid(std::unique_ptr<Solid> solid, const Bounds& box);
  bool contains(const Point& x) const override { return box_.contains(x) && solid_->contains(x); }
  double volume() const override { return volume_; }
  Bounds bounds() const override { return intersection(solid_->bounds(), box_); }
  TriangleMesh surface() const override { return surface_; }

 private:
  std::unique_ptr<Solid> solid_;
  Bounds box_;
  TriangleMesh surface_;
  double volume_ = 0.0;
};

std::unique_ptr<Solid> clip(std::unique_ptr<Solid> solid, const Bounds& box);

}  // namespace hvi::geometry
