#pragma once
// The database of experiments (cases/experiments/hcsp_shots.csv): normal-incidence shots on
// honeycomb sandwich panels, one per row, in the database's units (mm, g/cm^3, km/s, ksi), and the
// `hvi run` overrides that turn the shot template (cases/experiments/shot.toml) into one shot's
// scene. Materials are named as the sources name them; material_names.csv beside the database
// maps each to a library material.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace hvi::driver {

// One shot, in SI.
struct Shot {
  std::string source, id;  // e.g. "Turner_IJIE_2001", "1-008"
  std::string label;       // source:line of the row
  std::string projectile_material, front_material, core_material, rear_material;  // library
  double d_p = 0, v_p = 0;                  // projectile diameter (m), speed (m/s)
  double t_f = 0, t_r = 0;                  // facesheet thicknesses, m
  double D_hc = 0, t_hc = 0;                // honeycomb cell diameter and foil thickness, m
  double S = 0;                             // panel thickness, front face to rear face, m
  double rear_density = 0, rear_yield = 0;  // kg/m^3, Pa (for the ballistic limit equation)
  double projectile_density = 0;            // kg/m^3
  bool perforated = false;                  // the experiment's outcome (P / NP)

  // A directory name: source_shot, with characters other than letters, digits, '_', '-' and '.'
  // replaced by '-'.
  std::string run_name() const;
  double core_height() const { return S - t_f - t_r; }
};

// Reads the database. `names` maps a source's material name to a library material (every name
// the database uses must be there). Throws std::invalid_argument naming file, line, column and
// value for a bad row.
std::vector<Shot> read_shots(const std::filesystem::path& database,
                             const std::map<std::string, std::string>& names);
// material_names.csv: columns `name` (as in the database) and `library`.
std::map<std::string, std::string> read_material_names(const std::filesystem::path& file);

// How a shot's scene is framed (the template's quarter model around the impact axis).
struct ShotFrame {
  double gap = 0.2e-3;  // projectile surface to front face at t = 0, m
  double rings = 2.5;   // half-width of the model: rings x D_hc + spread x d_p
  double spread = 1.5;
  double below = 3e-3;    // grid below the rear face: max(below, d_p), m
  double travel = 85e-3;  // end time = (S + travel) / v_p
};

// The `--set` overrides of the template for one shot, in the order they apply.
std::vector<std::string> shot_overrides(const Shot& shot, const ShotFrame& frame = {});

}  // namespace hvi::driver
