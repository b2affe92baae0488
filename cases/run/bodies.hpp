#pragma once
// The scene's bodies as geometry: each [[body]] or panel part becomes a geometry::Solid (cut to its
// clip box) and is sampled into material points with its particles per cell and the refinement
// zones that name it. Shared by `hvi check`, `hvi run` and `hvi geometry`.
#include <memory>

#include "cases/scene/scene.hpp"
#include "geometry/honeycomb.hpp"
#include "geometry/point_set.hpp"
#include "geometry/sampler.hpp"
#include "geometry/solid.hpp"

namespace hvi::driver {

// The geometry of a scene's [[panel]] (without its clip).
geometry::HoneycombPanel panel_geometry(const scene::PanelSettings& panel);

// The body's solid, cut to its clip box. A surface file that is refused (not closed,
// self-intersecting, inside-out, unreadable) or reaches outside the grid throws
// scene::SceneError located at the body's mesh.file key: a scene error, nothing is run.
std::unique_ptr<geometry::Solid> make_body_solid(const scene::Scene& scene, std::size_t body);
// The body's solid cut to `box` instead of its clip (a hybrid's panel over the ring its MPM zone
// grows by).
std::unique_ptr<geometry::Solid> make_body_solid(const scene::Scene& scene, std::size_t body,
                                                 const geometry::Bounds& box);

// Lattice spacing (cell size / particles per cell) anchored at the grid origin, the zones of the
// [[refinement]] entries that apply to the body, and the panel's thin-wall model.
geometry::SamplingSettings sampling_settings(const scene::Scene& scene, std::size_t body);

// Samples the body (sampler.hpp); errors name the body. Volumes sum to the solid's exact volume.
geometry::PointSet sample_body(const scene::Scene& scene, std::size_t body,
                               const geometry::Solid& solid,
                               geometry::SampleReport* report = nullptr);

}  // namespace hvi::driver
