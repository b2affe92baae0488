#include "cases/scene/run_info.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <toml++/toml.h>

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

struct Reader {
  std::string file;
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument(fmt::format("{}: {}", file, what));
  }
  double number(const toml::table& t, const std::string& key, const std::string& where) const {
    const auto v = t[key].value<double>();
    if (!v) fail(fmt::format("no number '{}' in {}", key, where));
    return *v;
  }
  std::string text(const toml::table& t, const std::string& key, const std::string& where) const {
    const auto v = t[key].value<std::string>();
    if (!v) fail(fmt::format("no string '{}' in {}", key, where));
    return *v;
  }
};

// Each material's bulk sound speed: the Mie-Grüneisen c0, else sqrt(K / rho) of its elasticity.
void read_sound_speeds(const Reader& r, const toml::table& doc, RunInfo& info) {
  const toml::array* materials = doc["material"].as_array();
  if (!materials) return;
  for (const auto& node : *materials) {
    const toml::table& m = *node.as_table();
    const std::string name = r.text(m, "name", "[[material]]");
    if (const auto c0 = m["mie_gruneisen"]["c0"].value<double>();
        c0 && m["eos"].value_or(std::string{}) == "mie-gruneisen") {
      info.sound_speed[name] = *c0;
    } else if (const auto E = m["youngs_modulus"].value<double>()) {
      const double nu = m["poisson_ratio"].value_or(0.0), rho = m["density"].value_or(0.0);
      if (rho > 0) info.sound_speed[name] = std::sqrt(*E / (3 * (1 - 2 * nu)) / rho);
    }
  }
}

// The bodies, and each panel's three (front, core, rear) after them, in the solver's order.
void read_bodies(const Reader& r, const toml::table& doc, double cell, RunInfo& info) {
  if (const toml::array* bodies = doc["body"].as_array())
    for (const auto& node : *bodies) {
      const toml::table& t = *node.as_table();
      RunBody b;
      b.name = r.text(t, "name", "[[body]]");
      b.material = r.text(t, "material", "body." + b.name);
      b.spacing = cell / t["particles_per_cell"].value_or(std::int64_t{2});
      if (const auto radius = t["sphere"]["radius"].value<double>()) b.sphere_radius = *radius;
      if (const toml::array* lo = t["box"]["lower"].as_array(); lo && t["box"]["upper"].as_array())
        b.thickness = t["box"]["upper"][2].value_or(0.0) - (*lo)[2].value_or(0.0);
      info.bodies.push_back(b);
    }
  if (const toml::array* panels = doc["panel"].as_array())
    for (const auto& node : *panels) {
      const toml::table& t = *node.as_table();
      RunPanel p;
      p.name = r.text(t, "name", "[[panel]]");
      const std::string where = "panel." + p.name;
      p.front_thickness = r.number(t, "front_thickness", where);
      p.rear_thickness = r.number(t, "rear_thickness", where);
      p.wall_thickness = r.number(t, "wall_thickness", where);
      p.cell_diameter = r.number(t, "cell_diameter", where);
      p.core_height = r.number(t, "core_height", where);
      p.front_material = r.text(t, "front_material", where);
      p.core_material = r.text(t, "core_material", where);
      p.rear_material = r.text(t, "rear_material", where);
      const double spacing = cell / t["particles_per_cell"].value_or(std::int64_t{2});
      info.bodies.push_back(
          {p.name + ".front", p.front_material, spacing, {}, {}, p.front_thickness});
      info.bodies.push_back({p.name + ".core", p.core_material, spacing, {}, {}, p.core_height});
      info.bodies.push_back({p.name + ".rear", p.rear_material, spacing, {}, {}, p.rear_thickness});
      info.panels.push_back(p);
    }
  if (info.bodies.empty()) r.fail("no [[body]] or [[panel]]");
}

// The refinement factors that apply to each body.
void read_refinements(const toml::table& doc, RunInfo& info) {
  const toml::array* zones = doc["refinement"].as_array();
  if (!zones) return;
  for (const auto& node : *zones) {
    const toml::table& t = *node.as_table();
    const int factor = static_cast<int>(t["factor"].value_or(std::int64_t{2}));
    const toml::array* names = t["bodies"].as_array();
    for (auto& b : info.bodies) {
      bool applies = !names || names->empty();
      if (names)
        for (const auto& n : *names) applies = applies || n.value_or(std::string{}) == b.name;
      if (applies) b.refinements.push_back(factor);
    }
  }
}

// The symmetry planes on x and y, the planes a half or quarter model is mirrored across.
void read_mirror_planes(const Reader& r, const toml::table& doc, const toml::table& grid,
                        RunInfo& info) {
  const toml::array* boundaries = doc["boundary"].as_array();
  if (!boundaries) return;
  for (const auto& node : *boundaries) {
    const toml::table& t = *node.as_table();
    if (t["type"].value_or(std::string{}) != "symmetry") continue;
    const std::string face = r.text(t, "face", "[[boundary]]");
    // No position: the domain face.
    const int axis = face[0] - 'x';
    const double position = t["position"].value<double>().value_or(
        grid[face[1] == '-' ? "lower" : "upper"][axis].value_or(0.0));
    if (axis == 0) info.mirror.x = position;
    if (axis == 1) info.mirror.y = position;
  }
}

}  // namespace

RunInfo read_run_info(const std::filesystem::path& path) {
  const Reader r{path.string()};
  toml::table doc;
  try {
    doc = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    r.fail(fmt::format("cannot read the resolved scene: {}", e.description()));
  }
  RunInfo info;
  const toml::table* grid = doc["grid"].as_table();
  if (!grid) r.fail("no [grid]");
  const double cell = r.number(*grid, "cell_size", "[grid]");
  read_sound_speeds(r, doc, info);
  read_bodies(r, doc, cell, info);
  read_refinements(doc, info);
  read_mirror_planes(r, doc, *grid, info);
  return info;
}

}  // namespace hvi::driver
