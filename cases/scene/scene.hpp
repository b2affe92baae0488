#pragma once
// A scene: the validated, fully resolved contents of a scene file, as typed values in SI.
// load_scene() parses the file, applies command-line overrides, validates every key against the
// declaration (scene_schema.cpp), checks what relates keys to each other (a body's material
// exists, a boundary plane lies on grid nodes, bodies lie inside the grid) and fills the defaults
// that depend on other keys. Any problem throws SceneError with every diagnostic.
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <toml++/toml.h>

#include "cases/scene/measure_settings.hpp"
#include "cases/scene/schema.hpp"
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
  std::string dilatation = "particle";  // particle | node-average
  bool stencil_cache = false;
  double flip = 1.0, cfl = 0.5;
  std::optional<double> max_time_step;
};

struct BoundarySettings {
  int axis = 0;
  bool lower_face = true;  // x-, y-, z-
  std::string type;        // fixed | symmetry
  double position = 0.0;
  int plane = 0;  // grid node index of the plane
};

// A material: the models it names and their parameters (scene values over library values).
struct MaterialSettings {
  std::string name, library;
  std::string strength, eos, viscosity, damage, failure, heating, erosion;  // as named in the scene
  std::string damage_evolution = "instant", scatter = "none";
  mpm::HydroModels models;  // density, elasticity, and the parameters of the named models only
  // Nothing but elasticity: simulated by the plain linear elastic material.
  bool elastic_only() const {
    return strength == "elastic" && eos == "none" && viscosity == "none" && damage == "none" &&
           failure == "none" && heating == "none" && erosion == "none";
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
// A solid bounded by a surface file: x = R (scale x_file) + translate, R = Rz Ry Rx.
struct MeshShape {
  std::string file;    // absolute path (resolved against the scene file's folder)
  double scale = 1.0;  // the file's length unit in m, times the scene's scale
  Vec3 rotate{}, translate{};
  Vec3 lower{},
      upper{};  // until the file is read: the grid (the builder checks the surface against it)
};
// One of the three bodies of a [[panel]].
struct PanelPart {
  enum Part { front, core, rear };
  std::size_t panel = 0;  // index into Scene::panels
  Part part = front;
  Vec3 lower{}, upper{};  // the part's box (before any clip)
};

struct BodySettings {
  std::string name;
  std::size_t material = 0;  // index into Scene::materials
  Vec3 velocity{};
  int particles_per_cell = 2;
  std::variant<SphereShape, BoxShape, CylinderShape, MeshShape, PanelPart> shape;
  std::optional<BoxShape> clip;  // keep only the part inside (half and quarter models)
  // Where the body is declared, for problems found only when it is built (a refused surface
  // file): the builder reports them as scene errors located here.
  Diagnostic origin;
};

// A honeycomb sandwich panel ([[panel]]; geometry/honeycomb.hpp); its bodies are in
// Scene::bodies as <name>.front, <name>.core, <name>.rear.
struct PanelSettings {
  std::string name;
  double front_thickness = 0, rear_thickness = 0, wall_thickness = 0, cell_diameter = 0,
         core_height = 0;
  std::array<double, 2> lower{}, upper{}, pattern_origin{};
  double top = 0, rotation = 0;  // rotation in rad
  std::string origin_at;         // cell-center | vertex | wall
  bool double_walls = false;
  std::string thin_walls;  // auto | lattice | point-type
  double rear_gap = 0;     // the core's walls end this far above the rear facesheet, m
};

// A refinement zone ([[refinement]]).
struct RefinementSettings {
  std::string name;
  int factor = 2;
  std::variant<BoxShape, CylinderShape> shape;
  std::vector<std::size_t> bodies;  // indices into Scene::bodies it applies to
};

// The hybrid ([far_field]; coupling/): the panel outside `zone` is finite elements.
struct FarFieldSettings {
  std::size_t panel = 0;           // index into Scene::panels
  std::array<double, 4> zone{};    // the MPM zone in plane: x0, y0, x1, y1 (m, on grid planes)
  std::array<double, 4> extent{};  // the whole panel in plane, cut by its clip (m)
  int band_elements = 2, core_elements = 8, face_elements = 1;
  double growth = 1.25, max_element = 0.0, safety = 0.9;
  bool clamped_edges = false;
  bool plastic_faces =
      false;  // plasticity = "j2" or "failing": the facesheets yield (their Johnson-Cook A, B, n)
  bool failing_faces =
      false;  // plasticity = "failing": and tear where their Johnson-Cook damage reaches 1
  bool finite_strain = false;  // kinematics = "finite": Green-Lagrange strain, P = F S
  bool strain_rate =
      false;  // strain_rate = "johnson-cook": J2 facesheets' yield takes eq. (1)'s rate factor
  bool yielding_core = false;  // core = "yielding" or "failing": its out-of-plane stresses capped
                               // (walls' Johnson-Cook A)
  bool failing_core = false;  // core = "failing": and dropped to zero where the walls' Johnson-Cook
                              // damage reaches 1
  // [far_field.zone.grow]: the zone grows over the far field where the panel's damage reaches its
  // edge (coupling/zone_growth.hpp); none: a fixed zone.
  struct Grow {
    std::array<double, 4> limit{};  // the largest zone: x0, y0, x1, y1 (m, on grid planes)
    double step = 0.0, margin = 0.0, damage = 1.0;
  };
  std::optional<Grow> grow;
};

// [contact]: the impactor's bodies (indices into Scene::bodies) and the friction coefficient.
struct ContactSettings {
  std::vector<std::size_t> bodies;
  double friction = 0.0;
};

// [bond]: a panel's core bonded to its facesheets (mpm/bond.hpp).
struct BondSceneSettings {
  std::size_t panel = 0;                               // index into Scene::panels
  double normal_strength = 0.0, shear_strength = 0.0;  // Pa
  double width = 0.0;                                  // of the bonded strip under each wall, m
};

struct Scene {
  std::string file;
  std::string title;
  double end_time = 0.0;
  std::int64_t max_steps = 0;
  double max_energy_growth = 0.5;
  double output_interval = 0.0, checkpoint_interval = 0.0;
  std::int64_t energy_every = 10;
  bool energy_ledger = false;       // energy_ledger.csv (mpm/energy_ledger.hpp)
  std::int64_t keep_snapshots = 0;  // 0: all; else the first and the newest N
  GridSettings grid;
  std::vector<BoundarySettings> boundaries;
  std::vector<MaterialSettings> materials;
  std::vector<BodySettings> bodies;  // [[body]] entries, then three per [[panel]]
  std::vector<PanelSettings> panels;
  std::vector<RefinementSettings> refinements;
  std::optional<FarFieldSettings> far_field;  // none: a pure MPM scene
  std::optional<ContactSettings> contact;     // none: one velocity field
  std::optional<BondSceneSettings> bond;      // none: walls and sheets share their nodes
  toml::table resolved;  // every key, defaults filled, SI values: written next to the output
  std::vector<std::string> warnings;  // likely mistakes that are not errors ("no EOS at 5 km/s")
  std::vector<MeasureSettings> measures;  // [[measure]]: quantities of interest at the end
};

// Whether the surface files a scene names must exist. A finished run's resolved scene is read
// for its bodies' names and sizes (hvi measure), also where the run was moved without its meshes.
enum class MeshFiles { must_exist, may_be_missing };

// Reads, overrides, validates and resolves a scene file. Throws SceneError.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {},
                 MeshFiles mesh_files = MeshFiles::must_exist);
// The same from text (tests), `file` naming it in diagnostics.
Scene parse_scene(const std::string& text, const std::string& file,
                  const std::vector<std::string>& overrides = {});

// A TOML file of hvi's (a scene, a study) parsed; an unreadable file or a TOML syntax error is a
// SceneError naming the file (and line and column). `what` names the kind of file in the message.
toml::table read_document(const std::string& path, const std::string& what = "scene");

// The resolved scene as TOML text (SI values), with a header naming the units.
std::string resolved_text(const Scene& scene);

// The keys that may change when a run resumes from its checkpoint: none of them changes the state
// computed so far (when to stop, what to write, what to measure at the end).
inline constexpr const char* resumable_keys =
    "title, run.end_time, run.max_steps, run.max_energy_growth, [output], [[measure]]";
// A hash (64-bit FNV-1a) of the resolved scene without the keys above: equal for two scenes
// that compute the same state.
std::uint64_t state_hash(const Scene& scene);

}  // namespace hvi::scene
