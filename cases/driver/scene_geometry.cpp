#include "cases/driver/scene_geometry.hpp"

#include <filesystem>

#include <fmt/format.h>

namespace hvi::scene::detail {

std::optional<std::size_t> find_material(const Scene& s, const std::string& name, std::string* problem) {
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

void resolve_mesh_files(toml::array& bodies, const std::string& scene_file, const Validated& v,
                        std::vector<Diagnostic>& errors) {
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    toml::table& body = *bodies[i].as_table();
    toml::table* mesh = body["mesh"].as_table();
    if (!mesh) continue;
    fs::path file = text(*mesh, "file");
    if (file.is_relative()) file = fs::path(scene_file).parent_path() / file;
    std::error_code ec;
    const fs::path absolute = fs::weakly_canonical(fs::absolute(file), ec);
    if (ec || !fs::is_regular_file(absolute)) {
      errors.push_back(v.at(element_path("body", body, i) + ".mesh.file",
                            fmt::format("no such file: {}", (ec ? file : absolute).string())));
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
                 std::vector<Diagnostic>& errors) {
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
    for (int d = 0; d < 2; ++d)
      if (!(p.upper[d] > p.lower[d]))
        error(path + ".upper",
              fmt::format("expected upper > lower on every axis; on {} upper = {} m, lower = {} m",
                          "xy"[d], p.upper[d], p.lower[d]));
    // Each cell keeps an interior: the walls on either side of it must not meet.
    const double widest = p.double_walls ? 2 * p.wall_thickness : p.wall_thickness;
    if (!(widest < p.cell_diameter / 2))
      error(path + ".wall_thickness", fmt::format("walls of {} m{} leave no room in cells of {} m: "
                                                  "expected a wall thickness below D_hc / {}",
                                                  widest, p.double_walls ? " (double walls)" : "",
                                                  p.cell_diameter, p.double_walls ? 4 : 2));
    const std::optional<BoxShape> clip = clip_of(t);

    // The extent and layers, cut by the clip box, must lie in the grid.
    const double bottom = p.top - p.front_thickness - p.core_height - p.rear_thickness;
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
      if (const auto m = find_material(s, text(t, fmt::format("{}_material", parts[part]).c_str()), &problem))
        b.material = *m;
      else
        error(fmt::format("{}.{}_material", path, parts[part]), problem);
      b.particles_per_cell =
          static_cast<int>(t["particles_per_cell"].value<std::int64_t>().value());
      b.shape = PanelPart{s.panels.size(), static_cast<PanelPart::Part>(part),
                          Vec3{p.lower[0], p.lower[1], z[part + 1]},
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
