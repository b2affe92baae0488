#include "cases/scene/scene_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>

#include <fmt/format.h>

namespace hvi::scene::detail {

std::optional<std::size_t> find_material(const Scene& s, const std::string& name,
                                         std::string* problem) {
  for (std::size_t m = 0; m < s.materials.size(); ++m)
    if (s.materials[m].name == name) return m;
  std::string names;
  for (const auto& m : s.materials) names += (names.empty() ? "'" : ", '") + m.name + "'";
  *problem = fmt::format("no [[material]] named '{}'; defined: {}", name, names);
  return std::nullopt;
}

namespace {

namespace fs = std::filesystem;

double number(const toml::table& t, const char* key) {
  return t[key].value<double>().value();
}
std::string text(const toml::table& t, const char* key) {
  return t[key].value<std::string>().value();
}
template <std::size_t N>
std::array<double, N> vec(const toml::table& t, const char* key) {
  const toml::array& a = *t[key].as_array();
  std::array<double, N> v{};
  for (std::size_t d = 0; d < N; ++d) v[d] = a[d].value<double>().value();
  return v;
}
std::string element_path(const char* array, const toml::table& element, std::size_t index) {
  if (auto name = element["name"].value<std::string>()) return fmt::format("{}.{}", array, *name);
  return fmt::format("{}.{}", array, index);
}
std::optional<BoxShape> clip_of(const toml::table& t) {
  if (const auto* c = t["clip"].as_table())
    return BoxShape{vec<3>(*c, "lower"), vec<3>(*c, "upper")};
  return std::nullopt;
}

}  // namespace

std::string clip_problem(const BoxShape& clip, const GridSettings& grid) {
  for (int d = 0; d < 3; ++d) {
    if (!(clip.upper[d] > clip.lower[d]))
      return fmt::format(
          "expected clip upper > lower on every axis; on {} upper = {} m, lower = {} m", "xyz"[d],
          clip.upper[d], clip.lower[d]);
    if (!(clip.upper[d] > grid.lower[d] && clip.lower[d] < grid.upper[d]))
      return fmt::format("the clip [{}, {}] m along {} misses the grid [{}, {}] m", clip.lower[d],
                         clip.upper[d], "xyz"[d], grid.lower[d], grid.upper[d]);
  }
  return {};
}

namespace {}  // namespace

void resolve_mesh_files(toml::array& bodies, const std::string& scene_file, const Validated& v,
                        MeshFiles mesh_files, std::vector<Diagnostic>& errors) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    toml::table& body = *bodies[i].as_table();
    toml::table* mesh = body["mesh"].as_table();
    if (!mesh) continue;
    const std::string name = text(*mesh, "file");
    const std::string key = element_path("body", body, i) + ".mesh.file";
    if (name.find('\0') != std::string::npos) {
      errors.push_back(v.at(key, "the path holds a NUL character"));
      continue;
    }
    fs::path file = name;
    if (file.is_relative()) file = fs::path(scene_file).parent_path() / file;
    std::error_code ec;
    const fs::path absolute = fs::weakly_canonical(fs::absolute(file), ec);
    if (ec || !fs::is_regular_file(absolute)) {
      if (mesh_files == MeshFiles::may_be_missing) continue;
      const bool exists = !ec && fs::exists(absolute);
      const std::string shown = (ec ? file : absolute).string();
      errors.push_back(v.at(key, exists
                                     ? "not a regular file (a directory, device or pipe): " + shown
                                     : "no such file: " + shown));
      continue;
    }
    mesh->insert_or_assign("file", absolute.string());
  }
}

MeshShape read_mesh(const toml::table& mesh, const GridSettings& grid) {
  const std::string unit = text(mesh, "unit");
  const double metres = unit == "m"    ? 1.0
                        : unit == "cm" ? 1e-2
                        : unit == "mm" ? 1e-3
                        : unit == "um" ? 1e-6
                                       : 0.0254;
  return MeshShape{text(mesh, "file"),
                   metres * number(mesh, "scale"),
                   vec<3>(mesh, "rotate"),
                   vec<3>(mesh, "translate"),
                   grid.lower,
                   grid.upper};
}

void read_panels(const toml::array& panels, Scene& s, const Validated& v,
                 std::vector<Diagnostic>& errors, const toml::table* far_field) {
  auto error = [&](const std::string& key, std::string message) {
    errors.push_back(v.at(key, std::move(message)));
  };
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const toml::table& t = *panels[i].as_table();
    const std::string path = element_path("panel", t, i);
    PanelSettings p;
    p.name = text(t, "name");
    p.front_thickness = number(t, "front_thickness");
    p.rear_thickness = number(t, "rear_thickness");
    p.wall_thickness = number(t, "wall_thickness");
    p.cell_diameter = number(t, "cell_diameter");
    p.core_height = number(t, "core_height");
    p.lower = vec<2>(t, "lower");
    p.upper = vec<2>(t, "upper");
    p.top = number(t, "top");
    p.rotation = number(t, "rotation");
    p.pattern_origin = vec<2>(t, "pattern_origin");
    p.origin_at = text(t, "origin_at");
    p.double_walls = t["double_walls"].value<bool>().value();
    p.thin_walls = text(t, "thin_walls");
    p.rear_gap = number(t, "rear_gap");
    if (!(p.rear_gap < p.core_height))
      error(path + ".rear_gap",
            fmt::format("a gap of {} m leaves no core of height {} m: expected a gap below "
                        "core_height",
                        p.rear_gap, p.core_height));
    if (p.rear_gap > 0 && far_field && text(*far_field, "panel") == p.name)
      error(path + ".rear_gap",
            "the far field's core stands on the rear facesheet: a gap needs the panel all "
            "material points (no [far_field] on it)");
    for (int d = 0; d < 2; ++d)
      if (!(p.upper[d] > p.lower[d]))
        error(path + ".upper",
              fmt::format("expected upper > lower on every axis; on {} upper = {} m, lower = {} m",
                          "xy"[d], p.upper[d], p.lower[d]));
    // A cell larger than the panel leaves no wall in it: no core to build.
    const double narrowest = std::min(p.upper[0] - p.lower[0], p.upper[1] - p.lower[1]);
    if (!(p.cell_diameter < narrowest))
      error(path + ".cell_diameter",
            fmt::format("cells of {} m do not fit in the panel, {} m across at its narrowest: "
                        "expected a cell diameter below the panel's width",
                        p.cell_diameter, narrowest));
    // Each cell keeps an interior: the walls on either side of it must not meet.
    const double widest = p.double_walls ? 2 * p.wall_thickness : p.wall_thickness;
    if (!(widest < p.cell_diameter / 2))
      error(path + ".wall_thickness", fmt::format("walls of {} m{} leave no room in cells of {} m: "
                                                  "expected a wall thickness below D_hc / {}",
                                                  widest, p.double_walls ? " (double walls)" : "",
                                                  p.cell_diameter, p.double_walls ? 4 : 2));
    std::optional<BoxShape> clip = clip_of(t);
    if (clip)
      if (const std::string problem = clip_problem(*clip, s.grid); !problem.empty())
        error(path + ".clip", problem);
    const double bottom = p.top - p.front_thickness - p.core_height - p.rear_thickness;
    // With a far field, only the zone is material points (the rest is finite elements).
    if (far_field && text(*far_field, "panel") == p.name) {
      const auto zl = vec<2>(*(*far_field)["zone"].as_table(), "lower");
      const auto zu = vec<2>(*(*far_field)["zone"].as_table(), "upper");
      BoxShape zone{{zl[0], zl[1], bottom}, {zu[0], zu[1], p.top}};
      if (clip)
        for (int d = 0; d < 3; ++d) {
          zone.lower[d] = std::max(zone.lower[d], clip->lower[d]);
          zone.upper[d] = std::min(zone.upper[d], clip->upper[d]);
        }
      // The far field's extent: the panel cut by its own clip.
      FarFieldSettings f;
      f.extent = {p.lower[0], p.lower[1], p.upper[0], p.upper[1]};
      if (clip)
        f.extent = {std::max(f.extent[0], clip->lower[0]), std::max(f.extent[1], clip->lower[1]),
                    std::min(f.extent[2], clip->upper[0]), std::min(f.extent[3], clip->upper[1])};
      f.panel = s.panels.size();
      f.zone = {zl[0], zl[1], zu[0], zu[1]};
      s.far_field = f;
      clip = zone;
    }

    // The extent and layers, cut by the clip box, must lie in the grid.
    Vec3 lo{p.lower[0], p.lower[1], bottom}, hi{p.upper[0], p.upper[1], p.top};
    if (clip)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::max(lo[d], clip->lower[d]);
        hi[d] = std::min(hi[d], clip->upper[d]);
      }
    for (int d = 0; d < 3; ++d)
      if (lo[d] < s.grid.lower[d] || hi[d] > s.grid.upper[d]) {
        error(path,
              fmt::format("the panel reaches [{}, {}] m along {}, outside the grid [{}, {}] m",
                          lo[d], hi[d], "xyz"[d], s.grid.lower[d], s.grid.upper[d]));
        break;
      }

    const char* parts[3] = {"front", "core", "rear"};
    const double z[4] = {p.top, p.top - p.front_thickness,
                         p.top - p.front_thickness - p.core_height, bottom};
    for (int part = 0; part < 3; ++part) {
      BodySettings b;
      b.name = p.name + "." + parts[part];
      std::string problem;
      if (const auto m =
              find_material(s, text(t, fmt::format("{}_material", parts[part]).c_str()), &problem))
        b.material = *m;
      else
        error(fmt::format("{}.{}_material", path, parts[part]), problem);
      b.particles_per_cell =
          static_cast<int>(t["particles_per_cell"].value<std::int64_t>().value());
      b.shape =
          PanelPart{s.panels.size(), static_cast<PanelPart::Part>(part),
                    Vec3{p.lower[0], p.lower[1], z[part + 1] + (part == 1 ? p.rear_gap : 0.0)},
                    Vec3{p.upper[0], p.upper[1], z[part]}};
      b.clip = clip;
      b.origin = v.at(path, "");
      for (const auto& other : s.bodies)
        if (other.name == b.name)
          error(path + ".name", fmt::format("a body named '{}' is already defined", b.name));
      s.bodies.push_back(b);
    }
    s.panels.push_back(p);
  }
}

namespace {

// [far_field.zone.grow] of a far field whose zone was read and checked.
void read_zone_growth(const toml::table& t, Scene& s, const Validated& v,
                      std::vector<Diagnostic>& errors) {
  auto error = [&](const std::string& key, std::string message) {
    errors.push_back(v.at("far_field.zone.grow." + key, std::move(message)));
  };
  FarFieldSettings& f = *s.far_field;
  const double h = s.grid.cell_size;
  FarFieldSettings::Grow g;
  const auto lower = vec<2>(t, "lower"), upper = vec<2>(t, "upper");
  g.limit = {lower[0], lower[1], upper[0], upper[1]};
  g.step = t["step"].value<double>().value_or(8 * h);
  g.margin = t["margin"].value<double>().value_or(4 * h);
  g.damage = number(t, "damage");
  auto& resolved =
      *(*s.resolved["far_field"].as_table())["zone"].as_table()->get_as<toml::table>("grow");
  resolved.insert_or_assign("step", g.step);
  resolved.insert_or_assign("margin", g.margin);
  for (int d = 0; d < 2; ++d) {
    const double l0 = g.limit[d], l1 = g.limit[2 + d];
    if (!(f.extent[d] <= l0 && l0 <= f.zone[d] && f.zone[2 + d] <= l1 && l1 <= f.extent[2 + d])) {
      error(
          f.extent[d] <= l0 && l0 <= f.zone[d] ? "upper" : "lower",
          fmt::format(
              "the limit's {} range [{}, {}] m must hold the zone's [{}, {}] m and lie inside the "
              "panel's [{}, {}] m",
              "xy"[d], l0, l1, f.zone[d], f.zone[2 + d], f.extent[d], f.extent[2 + d]));
      continue;
    }
    for (int side = 0; side < 2; ++side) {
      const double x = g.limit[2 * side + d], cells = (x - s.grid.lower[d]) / h;
      if (std::abs(cells - std::round(cells)) > 1e-9)
        error(side ? "upper" : "lower", fmt::format("the limit's {} bound {} m is not on a grid "
                                                    "plane (grid lower {} m, cell {} m): the zone "
                                                    "grows by whole cells",
                                                    "xy"[d], x, s.grid.lower[d], h));
    }
    const double lo = std::max(f.extent[d], l0 - f.band_elements * h),
                 hi = std::min(f.extent[2 + d], l1 + f.band_elements * h);
    if (lo < s.grid.lower[d] - 1e-9 * h || hi > s.grid.upper[d] + 1e-9 * h)
      error(lo < s.grid.lower[d] - 1e-9 * h ? "lower" : "upper",
            fmt::format("the limit and its band of {} cells reach [{}, {}] m along {}, outside the "
                        "grid [{}, {}] m: "
                        "the grown zone's band is tied to grid nodes",
                        f.band_elements, lo, hi, "xy"[d], s.grid.lower[d], s.grid.upper[d]));
  }
  const double cells = g.step / h;
  if (std::abs(cells - std::round(cells)) > 1e-9)
    error("step", fmt::format("{} m is not a whole number of grid cells ({} m)", g.step, h));
  // The zone grows where the panel's points are damaged or have failed: one of its materials
  // must model that.
  bool damaging = false;
  for (const auto& b : s.bodies)
    if (const auto* part = std::get_if<PanelPart>(&b.shape);
        part && part->panel == f.panel && b.material < s.materials.size())
      damaging = damaging || s.materials[b.material].models.damage ||
                 s.materials[b.material].models.max_principal_stress ||
                 s.materials[b.material].models.tuler_butcher;
  if (!damaging)
    error(
        "damage",
        fmt::format("the zone grows where panel '{}' is damaged, but none of its materials names "
                    "damage = \"johnson-cook\" or a max-principal-stress or tuler-butcher failure",
                    s.panels[f.panel].name));
  f.grow = g;
}

}  // namespace

std::string panel_names(const Scene& s) {
  std::string names;
  for (const auto& p : s.panels) names += (names.empty() ? "'" : ", '") + p.name + "'";
  return names.empty() ? "none" : names;
}

void read_far_field(const toml::table& t, Scene& s, const Validated& v,
                    std::vector<Diagnostic>& errors) {
  auto error = [&](const std::string& key, std::string message) {
    errors.push_back(v.at("far_field." + key, std::move(message)));
  };
  if (!s.far_field) {
    error("panel",
          fmt::format("no [[panel]] named '{}'; panels: {}", text(t, "panel"), panel_names(s)));
    return;
  }
  FarFieldSettings& f = *s.far_field;
  const PanelSettings& p = s.panels[f.panel];
  f.band_elements = static_cast<int>(t["band_elements"].value<std::int64_t>().value());
  f.core_elements = static_cast<int>(t["core_elements"].value<std::int64_t>().value());
  f.face_elements = static_cast<int>(t["face_elements"].value<std::int64_t>().value());
  f.growth = number(t, "growth");
  f.safety = number(t, "safety");
  f.clamped_edges = text(t, "edges") == "clamped";
  f.failing_faces = text(t, "plasticity") == "failing";
  f.plastic_faces = f.failing_faces || text(t, "plasticity") == "j2";
  f.finite_strain = text(t, "kinematics") == "finite";
  f.strain_rate = text(t, "strain_rate") == "johnson-cook";
  if (f.strain_rate && !f.plastic_faces)
    error("strain_rate",
          "\"johnson-cook\" sets the rate factor of the facesheets' J2 yield stress; "
          "plasticity = \"none\" has none: expected plasticity = \"j2\" or \"failing\", "
          "or strain_rate = \"reference\"");
  f.failing_core = text(t, "core") == "failing";
  f.yielding_core = f.failing_core || text(t, "core") == "yielding";
  // J2 facesheets and a yielding core take their materials' Johnson-Cook strength (hardening, or
  // the walls' yield stress A), a failing core its walls' Johnson-Cook damage too. Front and rear
  // often share a material: one error for it.
  std::size_t reported = s.materials.size();
  for (const auto& b : s.bodies) {
    const auto* part = std::get_if<PanelPart>(&b.shape);
    if (!part || part->panel != f.panel || b.material >= s.materials.size()) continue;
    const bool core = part->part == PanelPart::core;
    const MaterialSettings& m = s.materials[b.material];
    if (core && f.failing_core && !m.models.damage)
      error("core",
            fmt::format(
                "\"failing\" tears the core's walls where their Johnson-Cook damage reaches 1; "
                "'{}' ({}) names damage = \"{}\": expected \"johnson-cook\" or core = \"yielding\"",
                m.name, b.name, m.damage));
    if (!core && f.failing_faces && !m.models.damage)
      error("plasticity",
            fmt::format(
                "\"failing\" tears the facesheets where their Johnson-Cook damage reaches 1; "
                "'{}' ({}) names damage = \"{}\": expected \"johnson-cook\" or plasticity = \"j2\"",
                m.name, b.name, m.damage));
    if (!(core ? f.yielding_core : f.plastic_faces) || m.models.johnson_cook ||
        (!core && b.material == reported))
      continue;
    if (!core) reported = b.material;
    if (core)
      error(
          "core",
          fmt::format(
              "\"{}\" caps the core's stresses at its walls' yield, their Johnson-Cook A; "
              "'{}' ({}) names strength = \"{}\": expected \"johnson-cook\" or core = \"elastic\"",
              f.failing_core ? "failing" : "yielding", m.name, b.name, m.strength));
    else
      error("plasticity",
            fmt::format("\"{}\" hardens the facesheets as their material's Johnson-Cook strength; "
                        "'{}' ({}) names strength = \"{}\": expected \"johnson-cook\" or "
                        "plasticity = \"none\"",
                        f.failing_faces ? "failing" : "j2", m.name, b.name, m.strength));
  }
  const double h = s.grid.cell_size;
  f.max_element = t["max_element"].value<double>().value_or(
      6.0 * std::min(p.front_thickness, p.rear_thickness));
  s.resolved["far_field"].as_table()->insert_or_assign("max_element", f.max_element);
  if (f.max_element < h)
    error("max_element",
          fmt::format("{} m is smaller than a grid cell ({} m): the far field's elements are "
                      "at least one cell long",
                      f.max_element, h));
  const double quarter_turns = p.rotation / (std::numbers::pi / 2);
  if (p.double_walls && std::abs(quarter_turns - std::round(quarter_turns)) > 1e-9)
    error("panel",
          fmt::format(
              "panel '{}' has double walls and its cells turned by {} deg: the far field's core "
              "takes its shear moduli along and across the ribbon on the panel's axes, so the "
              "rotation must be a multiple of 90 deg",
              p.name, p.rotation * 180 / std::numbers::pi));
  for (int d = 0; d < 2; ++d) {
    const double z0 = f.zone[d], z1 = f.zone[2 + d], a = f.extent[d], b = f.extent[2 + d];
    if (!(a <= z0 && z0 < z1 && z1 <= b)) {
      error("zone",
            fmt::format("the zone's {} range [{}, {}] m must lie inside the panel's [{}, {}] m "
                        "(its extent cut by its clip)",
                        "xy"[d], z0, z1, a, b));
      continue;
    }
    for (double z : {z0, z1}) {
      const double cells = (z - s.grid.lower[d]) / h;
      if (std::abs(cells - std::round(cells)) > 1e-9)
        error("zone",
              fmt::format(
                  "the zone's {} bound {} m is not on a grid plane (grid lower {} m, cell {} m): "
                  "the interface nodes must be grid nodes",
                  "xy"[d], z, s.grid.lower[d], h));
    }
    // The band's nodes tie to grid nodes: the grid must hold the zone and the band.
    const double lo = std::max(a, z0 - f.band_elements * h),
                 hi = std::min(b, z1 + f.band_elements * h);
    if (lo < s.grid.lower[d] - 1e-9 * h || hi > s.grid.upper[d] + 1e-9 * h)
      error("zone",
            fmt::format(
                "the zone and its band of {} cells reach [{}, {}] m along {}, outside the grid "
                "[{}, {}] m: the band's far-field nodes are tied to grid nodes",
                f.band_elements, lo, hi, "xy"[d], s.grid.lower[d], s.grid.upper[d]));
  }
  if (const toml::table* grow = (*t["zone"].as_table())["grow"].as_table())
    read_zone_growth(*grow, s, v, errors);
}

void read_refinements(const toml::array& zones, Scene& s, const Validated& v,
                      std::vector<Diagnostic>& errors) {
  for (std::size_t i = 0; i < zones.size(); ++i) {
    const toml::table& t = *zones[i].as_table();
    const std::string path = element_path("refinement", t, i);
    RefinementSettings r;
    r.name = t["name"].value_or(std::string{});
    r.factor = static_cast<int>(t["factor"].value<std::int64_t>().value());
    if (const auto* b = t["box"].as_table()) {
      r.shape = BoxShape{vec<3>(*b, "lower"), vec<3>(*b, "upper")};
    } else if (const auto* c = t["cylinder"].as_table()) {
      r.shape = CylinderShape{vec<3>(*c, "base_center"), text(*c, "axis")[0] - 'x',
                              number(*c, "radius"), number(*c, "length")};
    }
    const toml::array& names = *t["bodies"].as_array();
    for (const auto& node : names) {
      const std::string name = node.value<std::string>().value();
      std::size_t found = s.bodies.size();
      for (std::size_t b = 0; b < s.bodies.size(); ++b)
        if (s.bodies[b].name == name) found = b;
      if (found == s.bodies.size()) {
        std::string known;
        for (const auto& b : s.bodies) known += (known.empty() ? "'" : ", '") + b.name + "'";
        errors.push_back(
            v.at(path + ".bodies", fmt::format("no body named '{}'; bodies: {}", name, known)));
      } else {
        r.bodies.push_back(found);
      }
    }
    if (names.empty())
      for (std::size_t b = 0; b < s.bodies.size(); ++b) r.bodies.push_back(b);
    s.refinements.push_back(r);
  }
}

}  // namespace hvi::scene::detail
