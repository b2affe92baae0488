#include "cases/run/bodies.hpp"

#include <fmt/format.h>

#include "geometry/clipped_solid.hpp"
#include "geometry/honeycomb.hpp"
#include "geometry/mesh_solid.hpp"
#include "geometry/primitives.hpp"

namespace hvi::driver {

geometry::HoneycombPanel panel_geometry(const scene::PanelSettings& p) {
  geometry::HoneycombPanel g;
  g.front_thickness = p.front_thickness;
  g.rear_thickness = p.rear_thickness;
  g.wall_thickness = p.wall_thickness;
  g.cell_diameter = p.cell_diameter;
  g.core_height = p.core_height;
  g.lower = p.lower;
  g.upper = p.upper;
  g.top = p.top;
  g.rotation = p.rotation;
  g.pattern_origin = p.pattern_origin;
  g.origin_at = p.origin_at == "vertex" ? geometry::PatternOrigin::vertex
                : p.origin_at == "wall" ? geometry::PatternOrigin::wall
                                        : geometry::PatternOrigin::cell_center;
  g.double_walls = p.double_walls;
  g.rear_gap = p.rear_gap;
  return g;
}

namespace {

[[noreturn]] void scene_error(const scene::BodySettings& body, const std::string& message) {
  scene::Diagnostic d = body.origin;
  d.message = message;
  throw scene::SceneError({d});
}

std::unique_ptr<geometry::Solid> uncut_solid(const scene::Scene& scene,
                                             const scene::BodySettings& body) {
  return std::visit(
      [&](const auto& s) -> std::unique_ptr<geometry::Solid> {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, scene::SphereShape>) {
          return std::make_unique<geometry::Sphere>(s.center, s.radius);
        } else if constexpr (std::is_same_v<T, scene::BoxShape>) {
          return std::make_unique<geometry::Box>(s.lower, s.upper);
        } else if constexpr (std::is_same_v<T, scene::CylinderShape>) {
          return std::make_unique<geometry::Cylinder>(s.base_center, s.axis, s.radius, s.length);
        } else if constexpr (std::is_same_v<T, scene::MeshShape>) {
          try {
            auto solid = std::make_unique<geometry::MeshSolid>(geometry::read_surface(
                s.file, {.scale = s.scale, .rotate = s.rotate, .translate = s.translate}));
            const geometry::Bounds b = solid->bounds();
            for (int d = 0; d < 3; ++d)
              if (b.lower[d] < scene.grid.lower[d] || b.upper[d] > scene.grid.upper[d])
                scene_error(
                    body,
                    fmt::format(
                        "the surface reaches [{}, {}] m along {}, outside the grid [{}, {}] m",
                        b.lower[d], b.upper[d], "xyz"[d], scene.grid.lower[d],
                        scene.grid.upper[d]));
            return solid;
          } catch (const geometry::SurfaceError& e) {
            scene_error(body, fmt::format("{}: {}; nothing is sampled from it", s.file, e.what()));
          }
        } else {
          const geometry::HoneycombPanel panel = panel_geometry(scene.panels[s.panel]);
          if (s.part == scene::PanelPart::core)
            return std::make_unique<geometry::HoneycombCore>(panel, panel.core_box());
          const geometry::Bounds b =
              s.part == scene::PanelPart::front ? panel.front_box() : panel.rear_box();
          return std::make_unique<geometry::Box>(b.lower, b.upper);
        }
      },
      body.shape);
}

}  // namespace

std::unique_ptr<geometry::Solid> make_body_solid(const scene::Scene& scene, std::size_t b) {
  const scene::BodySettings& body = scene.bodies[b];
  auto solid = uncut_solid(scene, body);
  if (!body.clip) return solid;
  return geometry::clip(std::move(solid), {body.clip->lower, body.clip->upper});
}

std::unique_ptr<geometry::Solid> make_body_solid(const scene::Scene& scene, std::size_t b,
                                                 const geometry::Bounds& box) {
  return geometry::clip(uncut_solid(scene, scene.bodies[b]), box);
}

geometry::SamplingSettings sampling_settings(const scene::Scene& scene, std::size_t b) {
  const scene::BodySettings& body = scene.bodies[b];
  geometry::SamplingSettings s;
  s.spacing = scene.grid.cell_size / body.particles_per_cell;
  s.anchor = scene.grid.lower;
  for (const auto& r : scene.refinements) {
    if (std::find(r.bodies.begin(), r.bodies.end(), b) == r.bodies.end()) continue;
    geometry::RefinementZone zone;
    zone.factor = r.factor;
    if (const auto* box = std::get_if<scene::BoxShape>(&r.shape)) {
      zone.box = {box->lower, box->upper};
    } else {
      const auto& c = std::get<scene::CylinderShape>(r.shape);
      zone.shape = geometry::RefinementZone::Shape::cylinder;
      zone.base = c.base_center;
      zone.axis = c.axis;
      zone.radius = c.radius;
      zone.length = c.length;
    }
    s.zones.push_back(zone);
  }
  if (const auto* part = std::get_if<scene::PanelPart>(&body.shape)) {
    const std::string& model = scene.panels[part->panel].thin_walls;
    s.thin_walls = model == "lattice"      ? geometry::ThinWallModel::lattice
                   : model == "point-type" ? geometry::ThinWallModel::point_type
                                           : geometry::ThinWallModel::automatic;
  }
  return s;
}

geometry::PointSet sample_body(const scene::Scene& scene, std::size_t b,
                               const geometry::Solid& solid, geometry::SampleReport* report) {
  try {
    return geometry::sample(solid, sampling_settings(scene, b), report);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(fmt::format("body '{}': {}", scene.bodies[b].name, e.what()));
  }
}

}  // namespace hvi::driver
