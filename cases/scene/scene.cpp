#include "cases/scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "cases/scene/scene_geometry.hpp"
#include "cases/scene/scene_reading.hpp"
#include "cases/scene/scene_schema.hpp"

namespace hvi::scene {

SceneError::SceneError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(diagnostics.empty() ? "scene error" : diagnostics.front().text()),
      diagnostics_(std::move(diagnostics)) {}

std::string MaterialSettings::effects() const {
  std::string out = strength + " strength";
  if (eos != "none") out += ", " + eos + " eos";
  if (viscosity != "none") out += ", " + viscosity + " viscosity";
  if (damage != "none") out += ", " + damage + " damage";
  if (damage_evolution != "instant") out += " with " + damage_evolution + " evolution";
  if (scatter != "none") out += ", " + scatter + " scatter";
  if (failure != "none") out += ", " + failure + " failure";
  if (heating != "none") out += ", " + heating + " heating";
  if (erosion != "none") out += ", " + erosion + " erosion";
  return out;
}

namespace {

using namespace reading;

void read_grid(const toml::table& t, Scene& s, Checker& c) {
  GridSettings& g = s.grid;
  g.lower = vec3(t, "lower");
  g.upper = vec3(t, "upper");
  g.cell_size = number(t, "cell_size");
  g.shape_function = text(t, "shape_function");
  g.scheme = text(t, "scheme");
  g.flip = number(t, "flip");
  g.dilatation = text(t, "dilatation");
  g.stencil_cache = t["stencil_cache"].value<bool>().value();
  g.cfl = number(t, "cfl");
  g.max_time_step = optional_number(t, "max_time_step");
  for (int d = 0; d < 3; ++d) {
    const double cells = (g.upper[d] - g.lower[d]) / g.cell_size;
    if (!(cells > 0)) {
      c.error("grid.upper",
              fmt::format("expected upper > lower on every axis; on {} upper = {} m, lower = {} m",
                          "xyz"[d], g.upper[d], g.lower[d]));
      continue;
    }
    // A whole number of cells: round up (allowing for decimal round-off) and record the result.
    g.cells[d] = static_cast<int>(std::ceil(cells - 1e-9));
    if (cells > 4e6)
      c.error("grid.upper",
              fmt::format("{:.3g} cells along {} is more than the grid can index (4e6)", cells,
                          "xyz"[d]));
    // Round-off can leave the snapped bound a hair (< 1e-9 cell) short of the requested one (a
    // cell of 0.4 mm / sqrt(2)^2 = 0.19999999999999998 mm over 18 mm): keep the requested bound
    // then, so what fits the requested grid fits this one.
    g.upper[d] = std::max(g.lower[d] + g.cells[d] * g.cell_size, g.upper[d]);
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
    b.position =
        optional_number(t, "position").value_or(b.lower_face ? g.lower[b.axis] : g.upper[b.axis]);
    const double index = (b.position - g.lower[b.axis]) / g.cell_size;
    b.plane = static_cast<int>(std::lround(index));
    if (std::fabs(index - b.plane) > 1e-6)
      c.error(
          path + ".position",
          fmt::format("the plane {} = {} m does not lie on grid nodes (cell size {} m from {} m); "
                      "nearest node planes are {} m and {} m",
                      face.substr(0, 1), b.position, g.cell_size, g.lower[b.axis],
                      g.lower[b.axis] + std::floor(index) * g.cell_size,
                      g.lower[b.axis] + std::ceil(index) * g.cell_size));
    else if (b.plane < 0 || b.plane > g.cells[b.axis])
      c.error(path + ".position", fmt::format("the plane lies outside the grid [{}, {}] m",
                                              g.lower[b.axis], g.upper[b.axis]));
    t.insert_or_assign("position", b.position);
    s.boundaries.push_back(b);
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
        } else if constexpr (std::is_same_v<T, BoxShape> || std::is_same_v<T, MeshShape> ||
                             std::is_same_v<T, PanelPart>) {
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

// [contact] names bodies that exist (panel parts as <panel>.<part>), at least one and not all.
void read_contact(const toml::table& t, Scene& s, Checker& c) {
  ContactSettings contact;
  contact.friction = number(t, "friction");
  std::string known;
  for (const auto& b : s.bodies) known += (known.empty() ? "'" : ", '") + b.name + "'";
  for (const auto& node : *t["bodies"].as_array()) {
    const std::string name = node.value_or(std::string{});
    std::size_t found = s.bodies.size();
    for (std::size_t b = 0; b < s.bodies.size(); ++b)
      if (s.bodies[b].name == name) found = b;
    if (found == s.bodies.size())
      c.error("contact.bodies", fmt::format("no body named '{}'; bodies: {}", name, known));
    else if (s.far_field && name.rfind(s.panels.at(s.far_field->panel).name + ".", 0) == 0)
      c.error("contact.bodies",
              fmt::format("'{}' is part of the far field's panel, whose finite elements share "
                          "the other field's nodes; name the impactor's bodies only",
                          name));
    else if (std::find(contact.bodies.begin(), contact.bodies.end(), found) == contact.bodies.end())
      contact.bodies.push_back(found);
  }
  if (t["bodies"].as_array()->empty())
    c.error("contact.bodies",
            fmt::format("expected the impactor's bodies, at least one of {}", known));
  else if (contact.bodies.size() == s.bodies.size())
    c.error("contact.bodies",
            "every body is named: contact needs bodies on both sides; name the impactor's only");
  s.contact = contact;
}

// [bond] names a panel of the scene that the far field does not hold; it takes the second
// velocity field, so it excludes [contact].
void read_bond(const toml::table& t, Scene& s, Checker& c) {
  BondSceneSettings b;
  const std::string name = text(t, "panel");
  b.panel = s.panels.size();
  for (std::size_t p = 0; p < s.panels.size(); ++p)
    if (s.panels[p].name == name) b.panel = p;
  if (b.panel == s.panels.size())
    c.error("bond.panel",
            fmt::format("no [[panel]] named '{}'; panels: {}", name, detail::panel_names(s)));
  else if (s.far_field && s.far_field->panel == b.panel)
    c.error("bond.panel",
            "the far field's panel has no core of points to bond: bond a panel "
            "that is all material points");
  if (s.contact)
    c.error("bond",
            "a bond puts the core on the second velocity field, which [contact] takes "
            "too: name one of them");
  b.normal_strength = number(t, "normal_strength");
  b.shear_strength = number(t, "shear_strength");
  b.width = number(t, "width");
  s.bond = b;
}

void read_bodies(const toml::array& array, Scene& s, Checker& c) {
  for (std::size_t i = 0; i < array.size(); ++i) {
    const toml::table& t = *array[i].as_table();
    const std::string path = element_path("body", t, i);
    BodySettings b;
    b.name = text(t, "name");
    std::string problem;
    if (const auto m = detail::find_material(s, text(t, "material"), &problem))
      b.material = *m;
    else
      c.error(path + ".material", problem);
    b.velocity = vec3(t, "velocity");
    b.particles_per_cell = static_cast<int>(integer(t, "particles_per_cell"));
    if (const auto* sp = t["sphere"].as_table()) {
      b.shape = SphereShape{vec3(*sp, "center"), number(*sp, "radius")};
    } else if (const auto* bx = t["box"].as_table()) {
      const BoxShape box{vec3(*bx, "lower"), vec3(*bx, "upper")};
      for (int d = 0; d < 3; ++d)
        if (!(box.upper[d] > box.lower[d]))
          c.error(
              path + ".box.upper",
              fmt::format("expected upper > lower on every axis; on {} upper = {} m, lower = {} m",
                          "xyz"[d], box.upper[d], box.lower[d]));
      b.shape = box;
    } else if (const auto* cy = t["cylinder"].as_table()) {
      b.shape = CylinderShape{vec3(*cy, "base_center"), axis_index(text(*cy, "axis")),
                              number(*cy, "radius"), number(*cy, "length")};
    } else if (const auto* me = t["mesh"].as_table()) {
      b.shape = detail::read_mesh(*me, s.grid);
    }
    b.origin = c.v.at(path + (t["mesh"].as_table() ? ".mesh.file" : ""), "");
    if (const auto* cl = t["clip"].as_table())
      b.clip = BoxShape{vec3(*cl, "lower"), vec3(*cl, "upper")};
    if (b.clip)
      if (const std::string problem = detail::clip_problem(*b.clip, s.grid); !problem.empty())
        c.error(path + ".clip", problem);
    auto box = bounds_of(b);
    if (b.clip)
      for (int d = 0; d < 3; ++d) {
        box[0][d] = std::max(box[0][d], b.clip->lower[d]);
        box[1][d] = std::min(box[1][d], b.clip->upper[d]);
      }
    for (int d = 0; d < 3; ++d)
      if (box[0][d] < s.grid.lower[d] || box[1][d] > s.grid.upper[d]) {
        c.error(path,
                fmt::format("the body reaches [{}, {}] m along {}, outside the grid [{}, {}] m",
                            box[0][d], box[1][d], "xyz"[d], s.grid.lower[d], s.grid.upper[d]));
        break;
      }
    for (const auto& other : s.bodies)
      if (other.name == b.name) c.error(path + ".name", "a body of this name is already defined");
    s.bodies.push_back(b);
  }
}

// Physics a scene likely needs but does not name. Impact speed: the largest speed of a body or
// between two bodies. A material without an equation of state answers with its linear bulk
// modulus, which departs from a shock Hugoniot by about s mu ~ s v / (2 c0): 7% at an impact
// speed of 10% of the bulk sound speed for like materials. Above that fraction, warn (a steel
// Taylor bar at 287 m/s, 6%, does not need an EOS; a 1 km/s aluminium plate impact, 19%, does).
constexpr double eos_warning_fraction = 0.10;

// A body narrower than this many cells meets other bodies through a handful of grid nodes: the
// grid compresses it before it decelerates (a 0.4-cell projectile at 4.5 km/s gained 29% of its
// energy at cfl 0.5, 1.3% at cfl 0.05, in cases/stability).
constexpr double resolved_cells = 2.0;

void add_warnings(Scene& s) {
  // A honeycomb core without a failure model cannot perforate: its walls only bend and stretch.
  for (const auto& b : s.bodies) {
    const auto* part = std::get_if<PanelPart>(&b.shape);
    if (!part || part->part != PanelPart::core) continue;
    const MaterialSettings& m = s.materials[b.material];
    if (m.damage == "none" && m.failure == "none")
      s.warnings.push_back(
          fmt::format("body '{}' is a honeycomb core whose material '{}' names no damage or "
                      "failure model: its walls "
                      "cannot break, so a projectile is channelled by walls that never fail; name "
                      "damage = \"johnson-cook\" "
                      "(the paper's) or failure = \"max-principal-stress\"",
                      b.name, m.name));
  }
  for (const auto& b : s.bodies) {
    auto box = bounds_of(b);
    double widest = 0.0;  // a plate or a honeycomb wall is thin but wide: only small blobs warn
    for (int d = 0; d < 3; ++d) widest = std::max(widest, box[1][d] - box[0][d]);
    const double cells = widest / s.grid.cell_size;
    if (cells < resolved_cells && s.bodies.size() > 1)
      s.warnings.push_back(
          fmt::format("body '{}' is {:.2g} cells across (under {:.0f}): its contact with other "
                      "bodies is under-resolved "
                      "and can create energy (29% for a 0.4-cell projectile at cfl 0.5); refine "
                      "the grid or lower "
                      "grid.cfl (1.3% at 0.05)",
                      b.name, cells, resolved_cells));
  }
  double impact = 0.0;
  for (const auto& a : s.bodies) {
    impact = std::max(impact, std::hypot(a.velocity[0], a.velocity[1], a.velocity[2]));
    for (const auto& b : s.bodies)
      impact =
          std::max(impact, std::hypot(a.velocity[0] - b.velocity[0], a.velocity[1] - b.velocity[1],
                                      a.velocity[2] - b.velocity[2]));
  }
  for (std::size_t m = 0; m < s.materials.size(); ++m) {
    const MaterialSettings& mat = s.materials[m];
    bool used = false;
    for (const auto& b : s.bodies) used = used || b.material == m;
    if (!used || mat.eos != "none") continue;
    const auto& h = mat.models;
    const double bulk = h.youngs_modulus / (3.0 * (1.0 - 2.0 * h.poisson_ratio));
    const double c = std::sqrt(bulk / h.density);
    if (impact > eos_warning_fraction * c)
      s.warnings.push_back(fmt::format(
          "material '{}' names no equation of state, but the impact speed {:.4g} m/s is {:.0f}% of "
          "its "
          "bulk sound speed {:.4g} m/s (above {:.0f}%): its linear bulk response misses shock "
          "compression; name eos = \"mie-gruneisen\"",
          mat.name, impact, 100 * impact / c, c, 100 * eos_warning_fraction));
  }
}

Scene resolve(const toml::table& document, const std::string& file, MeshFiles mesh_files) {
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
  s.max_energy_growth = number(run, "max_energy_growth");
  read_grid(*r["grid"].as_table(), s, c);
  read_boundaries(*s.resolved["boundary"].as_array(), s, c);
  read_materials(*s.resolved["material"].as_array(), s, c);
  detail::resolve_mesh_files(*s.resolved["body"].as_array(), file, v, mesh_files, c.errors);
  read_bodies(*r["body"].as_array(), s, c);
  const toml::table* far_field = r["far_field"].as_table();
  detail::read_panels(*r["panel"].as_array(), s, v, c.errors, far_field);
  if (far_field) detail::read_far_field(*far_field, s, v, c.errors);
  if (s.bodies.empty()) c.error("body", "a scene needs at least one [[body]] or [[panel]]");
  detail::read_refinements(*r["refinement"].as_array(), s, v, c.errors);
  if (const toml::table* contact = r["contact"].as_table()) read_contact(*contact, s, c);
  if (const toml::table* bond = r["bond"].as_table()) read_bond(*bond, s, c);
  {
    std::vector<std::string> body_names;
    for (const auto& b : s.bodies) body_names.push_back(b.name);
    s.measures = read_measures(*r["measure"].as_array(), v, body_names, c.errors);
    for (const auto& m : s.measures)
      if (m.kind == "holes" && m.body.empty() && s.panels.empty())
        c.error(
            "measure." + m.name,
            "a holes measure needs a [[panel]], or `body` naming the plate whose hole it measures");
  }

  toml::table& output = *s.resolved["output"].as_table();
  s.output_interval = optional_number(output, "interval").value_or(s.end_time / 10);
  s.checkpoint_interval =
      optional_number(output, "checkpoint_interval").value_or(s.output_interval);
  s.energy_every = integer(output, "energy_every");
  s.energy_ledger = output["energy_ledger"].value<bool>().value();
  s.keep_snapshots = integer(output, "keep_snapshots");
  output.insert_or_assign("interval", s.output_interval);
  output.insert_or_assign("checkpoint_interval", s.checkpoint_interval);
  if (!c.errors.empty()) throw SceneError(c.errors);
  add_warnings(s);
  return s;
}

// hvi's keys nest a few levels (material.johnson_cook.A); a key or table header nested deeper
// than this is refused before parsing, whose recursion a key thousands of levels deep overflows.
constexpr int max_key_depth = 32;

// The dots between the parts of the key (or table header) a line begins with, outside quotes.
int key_depth(std::string_view line) {
  const auto first = line.find_first_not_of(" \t");
  if (first == std::string_view::npos || line[first] == '#') return 0;
  int dots = 0;
  char quote = 0;
  for (std::size_t i = first; i < line.size(); ++i) {
    const char ch = line[i];
    if (quote) {
      if (ch == quote) quote = 0;
    } else if (ch == '"' || ch == '\'') {
      quote = ch;
    } else if (ch == '.') {
      ++dots;
    } else if (ch == '=' || (ch == ']' && line[first] == '[')) {
      break;
    }
  }
  return dots;
}

void check_nesting(const std::string& text, const std::string& file) {
  std::size_t start = 0;
  for (int line = 1; start <= text.size(); ++line) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (const int depth = key_depth(std::string_view(text).substr(start, end - start));
        depth >= max_key_depth) {
      Diagnostic d;
      d.file = file;
      d.line = line;
      d.column = 1;
      d.message = fmt::format("a key nested {} levels deep; scene keys nest at most {}", depth + 1,
                              max_key_depth);
      throw SceneError({d});
    }
    start = end + 1;
  }
}

toml::table parse_document(const std::string& text, const std::string& file) {
  check_nesting(text, file);
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

Diagnostic located(const toml::node& node, const std::string& file, std::string key,
                   std::string message) {
  Diagnostic d;
  d.file = node.source().path ? std::string(*node.source().path) : file;
  d.line = static_cast<int>(node.source().begin.line);
  d.column = static_cast<int>(node.source().begin.column);
  d.key = std::move(key);
  d.message = std::move(message);
  return d;
}

// A value as TOML text, for an override assignment.
std::string toml_text(const toml::node& value) {
  toml::table wrapper;
  value.visit([&](const auto& v) { wrapper.insert("v", v); });
  std::stringstream out;
  out << toml::toml_formatter(wrapper, toml::format_flags::none);
  std::string text = out.str();
  return text.substr(text.find('=') + 1);
}

// Named override sets: a scene may define [resolutions.<name>] tables of "key.path" = value
// entries; `resolution = "<name>"` (in the file or given as --set resolution=<name>) applies one,
// then the command-line overrides are applied again so that they win. The sets themselves are
// dropped: the resolved scene records the values they set, the chosen name, and the chosen set as
// an empty table, so that it reads back as it is (a resumed run, `hvi measure`).
std::string apply_resolution(toml::table& document, const std::string& file) {
  const toml::node* sets_node = document.get("resolutions");
  const toml::node* name_node = document.get("resolution");
  std::vector<Diagnostic> errors;
  if (sets_node && !sets_node->is_table()) {
    errors.push_back(located(*sets_node, file, "resolutions",
                             "expected a table of named override tables, [resolutions.<name>]"));
    throw SceneError(errors);
  }
  const toml::table empty;
  const toml::table& sets = sets_node ? *sets_node->as_table() : empty;
  std::vector<std::string> names;
  for (const auto& [name, set] : sets) {
    names.emplace_back(name.str());
    if (!set.is_table()) {
      errors.push_back(located(set, file, "resolutions." + std::string(name.str()),
                               "expected a table of \"key.path\" = value overrides"));
    }
  }
  if (!errors.empty()) throw SceneError(errors);
  const std::string choice =
      name_node && name_node->is_string() ? name_node->as_string()->get() : "";
  if (!choice.empty()) {
    const toml::table* set = sets.get_as<toml::table>(choice);
    if (!set) {
      Diagnostic d =
          located(*name_node, file, "resolution",
                  fmt::format("the scene defines no [resolutions.{}]; it defines: {}", choice,
                              names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
      d.value = fmt::format("\"{}\"", choice);
      throw SceneError({d});
    }
    const toml::table chosen = *set;  // copied: applying may not touch the table it reads
    for (const auto& [key, value] : chosen) {
      const std::string assignment = std::string(key.str()) + "=" + toml_text(value);
      try {
        apply_override(document, assignment,
                       fmt::format("{} [resolutions.{}] {}", file, choice, key.str()));
      } catch (const std::invalid_argument& e) {
        errors.push_back(
            located(value, file, fmt::format("resolutions.{}.{}", choice, key.str()), e.what()));
      }
    }
  }
  if (!errors.empty()) throw SceneError(errors);
  document.erase("resolutions");
  return choice;
}

// The values a chosen [resolutions.<name>] replaces are checked too: a scene whose base value is
// wrong ("nan mm") is wrong at any resolution, though the chosen one never reads it. Only values
// written in the base are checked here; what the base leaves out the set may supply.
void check_replaced_values(const toml::table& document, const std::string& file) {
  const auto* name = document["resolution"].as_string();
  const auto* set = name ? document["resolutions"][name->get()].as_table() : nullptr;
  if (!set) return;  // no choice, or an unknown one: apply_resolution says so
  toml::table base = document;
  base.erase("resolutions");
  std::vector<Diagnostic> errors;
  for (const Diagnostic& d : validate(base, scene_schema(), file).errors)
    if (set->contains(d.key) && !d.message.starts_with("missing required")) {
      Diagnostic e = d;
      e.message += fmt::format(" (the base value, which [resolutions.{}] replaces)", name->get());
      errors.push_back(e);
    }
  if (!errors.empty()) throw SceneError(errors);
}

Scene resolve_document(toml::table document, const std::string& file,
                       const std::vector<std::string>& overrides,
                       MeshFiles mesh_files = MeshFiles::must_exist) {
  apply_overrides(document, overrides);  // a --set resolution=<name> picks the set
  check_replaced_values(document, file);
  const std::string choice = apply_resolution(document, file);
  apply_overrides(document, overrides);  // the command line wins over the set
  Scene scene = resolve(document, file, mesh_files);
  if (!choice.empty())
    scene.resolved.insert_or_assign("resolutions", toml::table{{choice, toml::table{}}});
  return scene;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file,
                  const std::vector<std::string>& overrides) {
  return resolve_document(parse_document(text, file), file, overrides);
}

toml::table read_document(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) {
    Diagnostic d;
    d.file = path;
    d.message = fmt::format("cannot read the {} file", what);
    throw SceneError({d});
  }
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_document(buffer.str(), path);
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides,
                 MeshFiles mesh_files) {
  return resolve_document(read_document(path), path, overrides, mesh_files);
}

std::uint64_t state_hash(const Scene& scene) {
  toml::table state = scene.resolved;
  for (const char* key : {"title", "output", "measure", "resolution", "resolutions"})
    state.erase(key);
  if (toml::table* run = state["run"].as_table())
    for (const char* key : {"end_time", "max_steps", "max_energy_growth"}) run->erase(key);
  std::stringstream text;
  text << toml::toml_formatter(state);
  std::uint64_t hash = 14695981039346656037ull;
  for (const unsigned char c : text.str()) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

std::string resolved_text(const Scene& scene) {
  std::stringstream out;
  out << "# Fully resolved scene: every key with its value, defaults filled in.\n"
         "# All values are SI: m, kg, s, K, Pa, J (a plain number in a scene file is read as SI).\n"
      << toml::toml_formatter(scene.resolved) << '\n';
  return out.str();
}

}  // namespace hvi::scene
