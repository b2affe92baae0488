#pragma once
// What hvi measure needs to know about a finished run: the bodies in snapshot order, their point
// spacings, the panel dimensions, the materials' sound speeds and the symmetry planes. Read from
// the run's scene.resolved.toml by the one scene reader (load_scene), which need not find the
// surface files a moved run's scene names.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/particle_set.hpp"

namespace hvi::driver {

struct RunBody {
  std::string name;
  std::string material;
  double spacing = 0;                   // coarse point spacing: cell_size / particles_per_cell, m
  std::vector<int> refinements;         // factors of the [[refinement]] zones that apply to it
  std::optional<double> sphere_radius;  // of a [body.sphere], m
  std::optional<double> thickness;      // z extent of a [body.box] or a panel facesheet, m
};

struct RunPanel {
  std::string name;
  double front_thickness = 0, rear_thickness = 0, wall_thickness = 0, cell_diameter = 0,
         core_height = 0;
  std::string front_material, core_material, rear_material;
};

struct RunInfo {
  // Bodies in the order of the snapshots' body index: the [[body]] tables, then three per
  // [[panel]] (<panel>.front, <panel>.core, <panel>.rear), as cases/scene/scene.hpp builds them.
  std::vector<RunBody> bodies;
  std::vector<RunPanel> panels;
  std::map<std::string, double> sound_speed;  // per material: Mie-Grueneisen c0, else sqrt(K / rho)
  analysis::MirrorPlanes mirror;              // from [[boundary]] type = "symmetry" on x or y

  // Index of the body called `name`, or -1.
  int body(const std::string& name) const;
  // The point spacing of a particle of `body` whose initial volume is v0: of the body's coarse
  // spacing and its refined ones, the one nearest to cbrt(v0) in ratio. (A point carries an equal
  // share of its body's exact volume, so cbrt(v0) is the spacing to a few per cent; refinement
  // factors are integers >= 2, so the nearest candidate is unambiguous.)
  double spacing(int body, double v0) const;
};

// Throws std::invalid_argument with the scene reader's located message.
RunInfo read_run_info(const std::filesystem::path& resolved_scene);

}  // namespace hvi::driver
