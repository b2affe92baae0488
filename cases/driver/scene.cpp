#include "cases/driver/scene.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "cases/driver/scene_schema.hpp"

namespace hvi::scene {

SceneError::SceneError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(diagnostics.empty() ? "scene error" : diagnostics.front().text()),
      diagnostics_(std::move(diagnostics)) {}

namespace {

double number(const toml::table& t, const char* key) { return t[key].value<double>().value(); }
std::int64_t integer(const toml::table& t, const char* key) { return t[key].value<std::int64_t>().value(); }
std::string text(const toml::table& t, const char* key) { return t[key].value<std::string>().value(); }
std::optional<double> optional_number(const toml::table& t, const char* key) { return t[key].value<double>(); }
Vec3 vec3(const toml::table& t, const char* key) {
  const toml::array& a = *t[key].as_array();
  return {a[0].value<double>().value(), a[1].value<double>().value(), a[2].value<double>().value()};
}
int axis_index(const std::string& name) { return name[0] - 'x'; }

std::string element_path(const char* array, const toml::table& element, std::size_t index) {
  if (auto name = element["name"].value<std::string>()) return fmt::format("{}.{}", array, *name);
  return fmt::format("{}.{}", array, index);
}

// Collects cross-key problems while the typed scene is assembled.
struct Checker {
  const Validated& v;
  std::vector<Diagnostic> errors;
  void error(const std::string& key, std::string message) { errors.push_back(v.at(key, std::move(message))); }
};

void read_grid(const toml::table& t, Scene& s, Checker& c) {
  GridSettings& g = s.grid;
  g.lower = vec3(t, "lower");
  g.upper = vec3(t, "upper");
  g.cell_size = number(t, "cell_size");
  g.shape_function = text(t, "shape_function");
  g.scheme = text(t, "scheme");
  g.flip = number(t, "flip");
  g.cfl = number(t, "cfl");
  g.max_time_step = optional_number(t, "max_time_step");
  for (int d = 0; d < 3; ++d) {
    const double cells = (g.upper[d] - g.lower[d]) / g.cell_size;
    if (!(cells > 0)) {
      c.error("grid.upper", fmt::format("expected upper > lower on every axis; on {} upper = {} m, lower = {} m",
                                        "xyz"[d], g.upper[d], g.lower[d]));
      continue;
    }
    // A whole number of cells: round up (allowing for decimal round-off) and record the result.
    g.cells[d] = static_cast<int>(std::ceil(cells - 1e-9));
    if (cells > 4e6) c.error("grid.upper", fmt::format("{:.3g} cells along {} is more than the grid can index (4e6)", cells, "xyz"[d]));
    g.upper[d] = g.lower[d] + g.cells[d] * g.cell_size;
  }
  toml::array upper;
  for (double u : g.upper) upper.push_back(u);
  s.resolved["grid"].as_table()->insert_or_assign("upper", std::move(upper));
}

void read_boundaries(toml::array& array, Scene& s, Checker& c) {
  for (std::size_t i = 0; i < array.size(); ++i) {
    toml::table& t = *array[i].as_table();
    const std::string path = element_path("boundary", t, i);
    BoundarySettings b;
    const std::string face = text(t, "face");
    b.axis = axis_index(face);
    b.lower_face = face[1] == '-';
    b.type = text(t, "type");
    const GridSettings& g = s.grid;
    b.position = optional_number(t, "position").value_or(b.lower_face ? g.lower[b.axis] : g.upper[b.axis]);
    const double index = (b.position - g.lower[b.axis]) / g.cell_size;
    b.plane = static_cast<int>(std::lround(index));
    if (std::fabs(index - b.plane) > 1e-6)
      c.error(path + ".position",
              fmt::format("the plane {} = {} m does not lie on grid nodes (cell size {} m from {} m); "
                          "nearest node planes are {} m and {} m",
                          face.substr(0, 1), b.position, g.cell_size, g.lower[b.axis],
                          g.lower[b.axis] + std::floor(index) * g.cell_size,
                          g.lower[b.axis] + std::ceil(index) * g.cell_size));
    else if (b.plane < 0 || b.plane > g.cells[b.axis])
      c.error(path + ".position", fmt::format("the plane lies outside the grid [{}, {}] m", g.lower[b.axis], g.upper[b.axis]));
    t.insert_or_assign("position", b.position);
    s.boundaries.push_back(b);
  }
}

void read_materials(const toml::array& array, Scene& s, Checker& c) {
  for (std::size_t i = 0; i < array.size(); ++i) {
    const toml::table& t = *array[i].as_table();
    MaterialSettings m;
    m.name = text(t, "name");
    for (const auto& other : s.materials)
      if (other.name == m.name) c.error(element_path("material", t, i) + ".name", "a material of this name is already defined");
    m.strength = text(t, "strength");
    m.density = number(t, "density");
    m.youngs_modulus = number(t, "youngs_modulus");
    m.poisson_ratio = number(t, "poisson_ratio");
    s.materials.push_back(m);
  }
}

std::array<Vec3, 2> bounds_of(const BodySettings& b) {
  return std::visit(
      [](const auto& shape) -> std::array<Vec3, 2> {
        using T = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<T, SphereShape>) {
          const double r = shape.radius;
          const Vec3& x = shape.center;
          return {Vec3{x[0] - r, x[1] - r, x[2] - r}, Vec3{x[0] + r, x[1] + r, x[2] + r}};
        } else if constexpr (std::is_same_v<T, BoxShape>) {
          return {shape.lower, shape.upper};
        } else {
          Vec3 lo = shape.base_center, hi = shape.base_center;
          for (int d = 0; d < 3; ++d) {
            if (d == shape.axis) {
              hi[d] += shape.length;
            } else {
              lo[d] -= shape.radius;
              hi[d] += shape.radius;
            }
          }
          return {lo, hi};
        }
      },
      b.shape);
}

void read_bodies(const toml::array& array, Scene& s, Checker& c) {
  for (std::size_t i = 0; i < array.size(); ++i) {
    const toml::table& t = *array[i].as_table();
    const std::string path = element_path("body", t, i);
    BodySettings b;
    b.name = text(t, "name");
    const std::string material = text(t, "material");
    bool found = false;
    for (std::size_t m = 0; m < s.materials.size(); ++m)
      if (s.materials[m].name == material) {
        b.material = m;
        found = true;
      }
    if (!found) {
      std::string names;
      for (const auto& m : s.materials) names += (names.empty() ? "'" : ", '") + m.name + "'";
      c.error(path + ".material", fmt::format("no [[material]] named '{}'; defined: {}", material, names));
    }
    b.velocity = vec3(t, "velocity");
    b.particles_per_cell = static_cast<int>(integer(t, "particles_per_cell"));
    if (const auto* sp = t["sphere"].as_table()) {
      b.shape = SphereShape{vec3(*sp, "center"), number(*sp, "radius")};
    } else if (const auto* bx = t["box"].as_table()) {
      const BoxShape box{vec3(*bx, "lower"), vec3(*bx, "upper")};
      for (int d = 0; d < 3; ++d)
        if (!(box.upper[d] > box.lower[d]))
          c.error(path + ".box.upper", fmt::format("expected upper > lower on every axis; on {} upper = {} m, lower = {} m",
                                                   "xyz"[d], box.upper[d], box.lower[d]));
      b.shape = box;
    } else if (const auto* cy = t["cylinder"].as_table()) {
      b.shape = CylinderShape{vec3(*cy, "base_center"), axis_index(text(*cy, "axis")),
                              number(*cy, "radius"), number(*cy, "length")};
    }
    const auto box = bounds_of(b);
    for (int d = 0; d < 3; ++d)
      if (box[0][d] < s.grid.lower[d] || box[1][d] > s.grid.upper[d]) {
        c.error(path, fmt::format("the body reaches [{}, {}] m along {}, outside the grid [{}, {}] m",
                                  box[0][d], box[1][d], "xyz"[d], s.grid.lower[d], s.grid.upper[d]));
        break;
      }
    for (const auto& other : s.bodies)
      if (other.name == b.name) c.error(path + ".name", "a body of this name is already defined");
    s.bodies.push_back(b);
  }
}

Scene resolve(const toml::table& document, const std::string& file) {
  Validated v = validate(document, scene_schema(), file);
  if (!v.ok()) throw SceneError(v.errors);
  Scene s;
  s.file = file;
  s.resolved = v.resolved;
  Checker c{v, {}};
  const toml::table& r = s.resolved;
  s.title = text(r, "title");
  const toml::table& run = *r["run"].as_table();
  s.end_time = number(run, "end_time");
  s.max_steps = integer(run, "max_steps");
  read_grid(*r["grid"].as_table(), s, c);
  read_boundaries(*s.resolved["boundary"].as_array(), s, c);
  read_materials(*r["material"].as_array(), s, c);
  read_bodies(*r["body"].as_array(), s, c);

  toml::table& output = *s.resolved["output"].as_table();
  s.output_interval = optional_number(output, "interval").value_or(s.end_time / 10);
  s.checkpoint_interval = optional_number(output, "checkpoint_interval").value_or(s.output_interval);
  s.energy_every = integer(output, "energy_every");
  output.insert_or_assign("interval", s.output_interval);
  output.insert_or_assign("checkpoint_interval", s.checkpoint_interval);
  if (!c.errors.empty()) throw SceneError(c.errors);
  return s;
}

toml::table parse_document(const std::string& text, const std::string& file) {
  try {
    return toml::parse(std::string_view(text), std::string_view(file));
  } catch (const toml::parse_error& e) {
    Diagnostic d;
    d.file = file;
    d.line = static_cast<int>(e.source().begin.line);
    d.column = static_cast<int>(e.source().begin.column);
    d.message = fmt::format("not valid TOML: {}", e.description());
    throw SceneError({d});
  }
}

void apply_overrides(toml::table& document, const std::vector<std::string>& overrides) {
  std::vector<Diagnostic> errors;
  for (const auto& o : overrides) {
    try {
      apply_override(document, o);
    } catch (const std::invalid_argument& e) {
      Diagnostic d;
      d.file = "--set " + o;
      d.line = 1;
      d.column = 1;
      d.message = e.what();
      errors.push_back(d);
    }
  }
  if (!errors.empty()) throw SceneError(errors);
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file,
                  const std::vector<std::string>& overrides) {
  toml::table document = parse_document(text, file);
  apply_overrides(document, overrides);
  return resolve(document, file);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) {
    Diagnostic d;
    d.file = path;
    d.message = "cannot read the scene file";
    throw SceneError({d});
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_scene(buffer.str(), path, overrides);
}

std::string resolved_text(const Scene& scene) {
  std::stringstream out;
  out << "# Fully resolved scene: every key with its value, defaults filled in.\n"
         "# All values are SI: m, kg, s, K, Pa, J (a plain number in a scene file is read as SI).\n"
      << toml::toml_formatter(scene.resolved) << '\n';
  return out.str();
}

}  // namespace hvi::scene
