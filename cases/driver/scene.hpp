#pragma once
// A scene: the validated, fully resolved contents of a scene file, as typed values in SI.
// load_scene() parses the file, applies command-line overrides, validates every key against the
// declaration (scene_schema.cpp), checks what relates keys to each other (a body's material
// exists, a boundary plane lies on grid nodes, bodies lie inside the grid) and fills the defaults
// that depend on other keys. Any problem throws SceneError with every diagnostic.
#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <toml++/toml.h>

#include "cases/driver/schema.hpp"
#include "mpm/materials/hydro_material.hpp"

namespace hvi::scene {

using Vec3 = std::array<double, 3>;

class SceneError : public std::runtime_error {
 public:
  explicit SceneError(std::vector<Diagnostic> diagnostics);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

struct GridSettings {
  Vec3 lower{}, upper{};
  double cell_size = 0.0;
  std::array<int, 3> cells{};
  std::string shape_function, scheme;
  double flip = 1.0, cfl = 0.5;
  std::optional<double> max_time_step;
};

struct BoundarySettings {
  int axis = 0;
  bool lower_face = true;  // x-, y-, z-
  std::string type;        // fixed | symmetry
  double position = 0.0;
  int plane = 0;           // grid node index of the plane
};

// A material: the models it names and their parameters (scene values over library values).
struct MaterialSettings {
  std::string name, library;
  std::string strength, eos, viscosity, damage, failure, heating;  // as named in the scene
  mpm::HydroModels models;  // density, elasticity, and the parameters of the named models only
  // Nothing but elasticity: simulated by the plain linear elastic material.
  bool elastic_only() const {
    return strength == "elastic" && eos == "none" && viscosity == "none" && damage == "none" &&
           failure == "none" && heating == "none";
  }
  // The models named, for messages ("johnson-cook strength, mie-gruneisen eos").
  std::string effects() const;
};

struct SphereShape {
  Vec3 center;
  double radius;
};
struct BoxShape {
  Vec3 lower, upper;
};
struct CylinderShape {
  Vec3 base_center;
  int axis;
  double radius, length;
};

struct BodySettings {
  std::string name;
  std::size_t material = 0;  // index into Scene::materials
  Vec3 velocity{};
  int particles_per_cell = 2;
  std::variant<SphereShape, BoxShape, CylinderShape> shape;
  std::optional<BoxShape> clip;  // keep only the part inside (half and quarter models)
};

struct Scene {
  std::string file;
  std::string title;
  double end_time = 0.0;
  std::int64_t max_steps = 0;
  double output_interval = 0.0, checkpoint_interval = 0.0;
  std::int64_t energy_every = 10;
  GridSettings grid;
  std::vector<BoundarySettings> boundaries;
  std::vector<MaterialSettings> materials;
  std::vector<BodySettings> bodies;
  toml::table resolved;  // every key, defaults filled, SI values: written next to the output
  std::vector<std::string> warnings;  // likely mistakes that are not errors ("no EOS at 5 km/s")
};

// Reads, overrides, validates and resolves a scene file. Throws SceneError.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});
// The same from text (tests), `file` naming it in diagnostics.
Scene parse_scene(const std::string& text, const std::string& file,
                  const std::vector<std::string>& overrides = {});

// The resolved scene as TOML text (SI values), with a header naming the units.
std::string resolved_text(const Scene& scene);

}  // namespace hvi::scene
