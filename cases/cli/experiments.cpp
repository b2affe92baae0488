#include "cases/cli/experiments.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "analysis/table.hpp"

namespace hvi::driver {

namespace {

constexpr double mm = 1e-3, km_s = 1e3, g_cm3 = 1e3, ksi = 6.894757293168361e6;

struct Row {
  const analysis::Table& table;
  std::size_t r;
  std::string file;

  std::string text(const std::string& column) const {
    const int c = table.column(column);
    if (c < 0)
      throw std::invalid_argument(
          fmt::format("{}: no column '{}' (the database's header names "
                      "every column of cases/experiments/README.md)",
                      file, column));
    return table.rows[r][static_cast<std::size_t>(c)];
  }
  // A positive number in `unit`, converted to SI.
  double positive(const std::string& column, double unit) const {
    const double v = table.number(r, table.column(column));
    if (!(v > 0) || !std::isfinite(v))
      throw std::invalid_argument(
          fmt::format("{}: column '{}' = \"{}\": expected a positive number", table.labels[r],
                      column, text(column)));
    return v * unit;
  }
  std::string material(const std::string& column,
                       const std::map<std::string, std::string>& names) const {
    const std::string name = text(column);
    const auto it = names.find(name);
    if (it == names.end())
      throw std::invalid_argument(fmt::format(
          "{}: column '{}' = \"{}\": a material material_names.csv does not map to the library",
          table.labels[r], column, name));
    return it->second;
  }
};

std::string length(double metres) {
  return fmt::format("{:.6g} mm", metres / mm);
}

}  // namespace

std::string Shot::run_name() const {
  std::string name = source + "_" + id;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') c = '-';
  return name;
}

std::map<std::string, std::string> read_material_names(const std::filesystem::path& file) {
  const analysis::Table t = analysis::read_csv(file);
  const int name = t.column("name"), library = t.column("library");
  if (name < 0 || library < 0)
    throw std::invalid_argument(
        fmt::format("{}: expected the columns 'name' and 'library'", file.string()));
  std::map<std::string, std::string> names;
  for (const auto& row : t.rows)
    names[row[static_cast<std::size_t>(name)]] = row[static_cast<std::size_t>(library)];
  return names;
}

std::vector<Shot> read_shots(const std::filesystem::path& database,
                             const std::map<std::string, std::string>& names) {
  const analysis::Table t = analysis::read_csv(database);
  std::vector<Shot> shots;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    const Row row{t, r, database.string()};
    Shot s;
    s.source = row.text("source");
    s.id = row.text("shot");
    s.label = t.labels[r];
    s.projectile_material = row.material("proj_mat", names);
    s.front_material = row.material("face_mat", names);
    s.core_material = row.material("core_mat", names);
    s.rear_material = row.material("rear_mat", names);
    s.projectile_density = row.positive("proj_rho", g_cm3);
    s.d_p = row.positive("d_p_mm", mm);
    s.v_p = row.positive("v_km_s", km_s);
    s.t_f = row.positive("t_f_mm", mm);
    s.D_hc = row.positive("D_hc_mm", mm);
    s.t_hc = row.positive("t_hc_mm", mm);
    s.S = row.positive("S_mm", mm);
    s.rear_density = row.positive("rear_rho", g_cm3);
    s.rear_yield = row.positive("rear_yield_ksi", ksi);
    s.t_r = row.positive("t_r_mm", mm);
    const std::string result = row.text("result");
    if (result != "P" && result != "NP")
      throw std::invalid_argument(
          fmt::format("{}: column 'result' = \"{}\": expected P or NP", s.label, result));
    s.perforated = result == "P";
    if (!(s.core_height() > 0))
      throw std::invalid_argument(fmt::format(
          "{}: S_mm = {:g} leaves no core between facesheets of {:g} and {:g} mm (S is the panel's "
          "thickness, front face to rear face)",
          s.label, s.S / mm, s.t_f / mm, s.t_r / mm));
    for (const Shot& other : shots)
      if (other.run_name() == s.run_name())
        throw std::invalid_argument(fmt::format("{}: shot '{}' of {} appears twice (also {})",
                                                s.label, s.id, s.source, other.label));
    shots.push_back(std::move(s));
  }
  return shots;
}

std::vector<std::string> shot_overrides(const Shot& s, const ShotFrame& f) {
  const double r = 0.5 * s.d_p;
  const double half = f.rings * s.D_hc + f.spread * s.d_p;
  const double top = s.d_p + f.gap + 1e-3;
  const double bottom = -s.S - std::max(f.below, s.d_p);
  const std::string lower = fmt::format("[\"0 mm\", \"0 mm\", \"{}\"]", length(bottom));
  const std::string upper = fmt::format("[\"{0}\", \"{0}\", \"{1}\"]", length(half), length(top));
  return {
      fmt::format("title=shot {} of {} ({:g} mm at {:g} km/s)", s.id, s.source, s.d_p / mm,
                  s.v_p / km_s),
      "material.projectile.library=" + s.projectile_material,
      "material.front.library=" + s.front_material,
      "material.core.library=" + s.core_material,
      "material.rear.library=" + s.rear_material,
      "grid.lower=" + lower,
      "grid.upper=" + upper,
      "body.projectile.sphere.radius=" + length(r),
      fmt::format("body.projectile.sphere.center=[\"0 mm\", \"0 mm\", \"{}\"]", length(r + f.gap)),
      fmt::format("body.projectile.velocity=[\"0 m/s\", \"0 m/s\", \"{:.6g} m/s\"]", -s.v_p),
      "body.projectile.clip.lower=" + lower,
      "body.projectile.clip.upper=" + upper,
      "panel.panel.front_thickness=" + length(s.t_f),
      "panel.panel.rear_thickness=" + length(s.t_r),
      "panel.panel.wall_thickness=" + length(s.t_hc),
      "panel.panel.cell_diameter=" + length(s.D_hc),
      "panel.panel.core_height=" + length(s.core_height()),
      fmt::format("panel.panel.lower=[\"-{0}\", \"-{0}\"]", length(half)),
      fmt::format("panel.panel.upper=[\"{0}\", \"{0}\"]", length(half)),
      "panel.panel.clip.lower=" + lower,
      "panel.panel.clip.upper=" + upper,
      fmt::format("run.end_time={:.6g} us", (s.S + f.travel) / s.v_p * 1e6),
  };
}

}  // namespace hvi::driver
