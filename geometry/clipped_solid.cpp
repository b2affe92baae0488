#include "geometry/clipped_solid.hpp"

#include "geometry/surface.hpp"

namespace hvi::geometry {

namespace {

bool inside(const Bounds& inner, const Bounds& outer) {
  for (int d = 0; d < 3; ++d)
    if (inner.lower[d] < outer.lower[d] || inner.upper[d] > outer.upper[d]) return false;
  return true;
}

}  // namespace

ClippedSolid::ClippedSolid(std::unique_ptr<Solid> solid, const Bounds& box)
    : solid_(std::move(solid)), box_(box) {
  const Bounds b = solid_->bounds();
  TriangleMesh whole = solid_->surface();
  if (inside(b, box_)) {
    surface_ = std::move(whole);
    volume_ = solid_->volume();
  } else if (!is_empty(intersection(b, box_))) {
    surface_ = solid_->convex() ? clip_convex_surface(whole, box_) : clip_surface(whole, box_);
    volume_ = solid_->volume() * enclosed_volume(surface_) / enclosed_volume(whole);
  }
}

std::unique_ptr<Solid> clip(std::unique_ptr<Solid> solid, const Bounds& box) {
  if (auto exact = solid->exact_clip(box)) return exact;
  return std::make_unique<ClippedSolid>(std::move(solid), box);
}

}  // namespace hvi::geometry
