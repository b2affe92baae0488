#include "cases/scene/run_info.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

#include <fmt/format.h>

#include "cases/scene/scene.hpp"

namespace hvi::driver {

int RunInfo::body(const std::string& name) const {
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (bodies[b].name == name) return static_cast<int>(b);
  return -1;
}

double RunInfo::spacing(int b, double v0) const {
  const RunBody& body = bodies.at(b);
  double best = body.spacing;
  const double h = std::cbrt(v0);
  for (const int f : body.refinements) {
    const double candidate = body.spacing / f;
    if (std::abs(std::log(h / candidate)) < std::abs(std::log(h / best))) best = candidate;
  }
  return best;
}

namespace {

// Each material's bulk sound speed: its EOS's at the reference state (the Mie-Grüneisen c0),
// else sqrt(K / rho) of its elasticity.
double bulk_sound_speed(const scene::MaterialSettings& m) {
  const mpm::HydroModels& h = m.models;
  if (m.eos != "none" && h.eos) return materials::reference_sound_speed(*h.eos);
  return std::sqrt(h.youngs_modulus / (3 * (1 - 2 * h.poisson_ratio)) / h.density);
}

// A body's size along z where measures need it: a box's thickness, a panel facesheet's or core's.
std::optional<double> thickness(const scene::Scene& s, const scene::BodySettings& b) {
  if (const auto* box = std::get_if<scene::BoxShape>(&b.shape))
    return box->upper[2] - box->lower[2];
  if (const auto* part = std::get_if<scene::PanelPart>(&b.shape)) {
    const scene::PanelSettings& p = s.panels[part->panel];
    return part->part == scene::PanelPart::front  ? p.front_thickness
           : part->part == scene::PanelPart::core ? p.core_height
                                                  : p.rear_thickness;
  }
  return std::nullopt;
}

RunBody run_body(const scene::Scene& s, std::size_t index) {
  const scene::BodySettings& b = s.bodies[index];
  RunBody r;
  r.name = b.name;
  r.material = s.materials[b.material].name;
  r.spacing = s.grid.cell_size / b.particles_per_cell;
  for (const auto& zone : s.refinements)
    if (std::find(zone.bodies.begin(), zone.bodies.end(), index) != zone.bodies.end())
      r.refinements.push_back(zone.factor);
  if (const auto* sphere = std::get_if<scene::SphereShape>(&b.shape))
    r.sphere_radius = sphere->radius;
  r.thickness = thickness(s, b);
  return r;
}

RunPanel run_panel(const scene::Scene& s, const scene::PanelSettings& p) {
  const auto material = [&](scene::PanelPart::Part part) {
    for (const auto& b : s.bodies)
      if (const auto* q = std::get_if<scene::PanelPart>(&b.shape);
          q && q->part == part && s.panels[q->panel].name == p.name)
        return s.materials[b.material].name;
    return std::string{};
  };
  return {p.name,
          p.front_thickness,
          p.rear_thickness,
          p.wall_thickness,
          p.cell_diameter,
          p.core_height,
          material(scene::PanelPart::front),
          material(scene::PanelPart::core),
          material(scene::PanelPart::rear)};
}

}  // namespace

RunInfo read_run_info(const std::filesystem::path& path) {
  scene::Scene s;
  try {
    s = scene::load_scene(path.string(), {}, scene::MeshFiles::may_be_missing);
  } catch (const scene::SceneError& e) {
    throw std::invalid_argument(fmt::format("cannot read the resolved scene: {}", e.what()));
  }
  RunInfo info;
  for (const auto& m : s.materials) info.sound_speed[m.name] = bulk_sound_speed(m);
  for (std::size_t b = 0; b < s.bodies.size(); ++b) info.bodies.push_back(run_body(s, b));
  for (const auto& p : s.panels) info.panels.push_back(run_panel(s, p));
  // The symmetry planes on x and y, the planes a half or quarter model is mirrored across.
  for (const auto& b : s.boundaries) {
    if (b.type != "symmetry") continue;
    if (b.axis == 0) info.mirror.x = b.position;
    if (b.axis == 1) info.mirror.y = b.position;
  }
  return info;
}

}  // namespace hvi::driver
