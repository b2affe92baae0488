// hvi measure's outputs: the printed summary (mm), measurements.json, measurements.csv (SI) and,
// on request, the top views as PGM images.
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "cases/run/measure_command.hpp"
#include "cases/run/run.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

namespace {

constexpr double mm = 1e-3;
constexpr double deg = std::numbers::pi / 180;

std::string rule_text(analysis::DiameterRule rule) {
  return rule == analysis::DiameterRule::two_chords ? "two chords, eq. (8)"
                                                    : "six directions, eqs. (9)-(10)";
}

toml::table sheet_json(const SheetMeasurement& s) {
  const auto& h = s.hole;
  toml::table t{{"body", s.body},
                {"perforated", h.perforated},
                {"rule", analysis::to_string(h.rule)},
                {"rotation_deg", h.rotation / deg},
                {"resolution", h.resolution},
                {"spacing", s.spacing},
                {"gap_closing_radius", s.closing_radius},
                {"intact_particles", static_cast<std::int64_t>(s.intact)},
                {"detached_particles", static_cast<std::int64_t>(s.detached)}};
  if (h.perforated) {
    t.insert("hole_open", h.open);
    toml::table d;
    for (int k = 0; k < 12; ++k)
      d.insert(
          fmt::format("{:g}",
                      std::round(analysis::HoleGeometry::angle(k, h.rotation) / deg * 1e6) / 1e6),
          h.D_theta(k));
    t.insert("D_theta", d);
    t.insert("D_h", h.D_h);
    t.insert("D_v", h.D_v);
    t.insert("D", h.D);
    t.insert("eccentricity", h.eccentricity);
    t.insert("area", h.area);
    t.insert("equivalent_diameter", h.equivalent_diameter);
  }
  return t;
}

// The CSV columns, in order, and their values (empty: not applicable).
std::vector<std::pair<std::string, std::string>> csv_cells(const Measurements& m) {
  std::vector<std::pair<std::string, std::string>> c;
  auto num = [](double v) { return fmt::format("{:.10g}", v); };
  auto opt = [&](bool have, double v) { return have ? num(v) : std::string{}; };
  c.emplace_back("run", m.run.filename().empty() ? m.run.parent_path().filename().string()
                                                 : m.run.filename().string());
  c.emplace_back("time", num(m.time));
  c.emplace_back("step", std::to_string(m.step));
  const char* names[] = {"v_p", "d_p", "t_f", "t_r", "c_f", "c_r", "c_hc", "t_hc", "D_hc", "S"};
  for (const char* name : names) {
    std::string v;
    for (const auto& [n, value] : m.variables)
      if (n == name) v = num(value);
    c.emplace_back(name, v);
  }
  auto sheet = [&](const std::optional<SheetMeasurement>& s, const std::string& x) {
    const bool hole = s && s->hole.perforated;
    c.emplace_back(x == "f" ? "front_perforated" : "rear_perforated",
                   s ? (s->hole.perforated ? "true" : "false") : "");
    c.emplace_back("D_" + x, opt(hole, hole ? s->hole.D : 0));
    c.emplace_back("D_" + x + "_h", opt(hole, hole ? s->hole.D_h : 0));
    c.emplace_back("D_" + x + "_v", opt(hole, hole ? s->hole.D_v : 0));
    c.emplace_back("e_" + x, opt(hole, hole ? s->hole.eccentricity : 0));
    c.emplace_back("D_" + x + "_equivalent", opt(hole, hole ? s->hole.equivalent_diameter : 0));
    c.emplace_back("hole_" + x + "_open", hole ? (s->hole.open ? "true" : "false") : "");
    c.emplace_back("resolution_" + x, opt(s.has_value(), s ? s->hole.resolution : 0));
  };
  sheet(m.front, "f");
  sheet(m.rear, "r");
  c.emplace_back("taper", opt(m.taper.has_value(), m.taper.value_or(0)));
  c.emplace_back("bulge", opt(m.bulge.has_value(), m.bulge ? m.bulge->displacement : 0));
  c.emplace_back("rear_spall_mass", opt(m.spall.has_value(), m.spall ? m.spall->mass : 0));
  c.emplace_back("rear_spall_particles",
                 m.spall ? std::to_string(m.spall->particles) : std::string{});
  c.emplace_back("debris_mass", num(m.debris.mass));
  c.emplace_back("debris_axial_extent", num(m.debris.axial_extent));
  c.emplace_back("debris_radial_extent", num(m.debris.radial_extent));
  c.emplace_back("debris_kinetic_energy", num(m.debris.kinetic_energy));
  return c;
}

// One CSV line of a measurement: its column names (header) or its values.
void write_csv_line(std::ostream& out, const Measurements& m, bool header) {
  const auto cells = csv_cells(m);
  for (std::size_t k = 0; k < cells.size(); ++k)
    out << (k ? "," : "") << (header ? cells[k].first : cells[k].second);
  out << '\n';
}

// One header line, then one row per measurement.
void write_csv(const std::vector<Measurements>& rows, const fs::path& file) {
  std::ofstream out(file);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (r == 0) write_csv_line(out, rows[r], true);
    write_csv_line(out, rows[r], false);
  }
  if (rows.empty()) out << '\n';
}

// Material black, the hole grey, other empty pixels white; +y up.
void write_pgm(const fs::path& file, const analysis::FacesheetResult& v) {
  const auto& r = v.raster;
  std::ofstream out(file, std::ios::binary);
  out << "P5\n" << r.nx << ' ' << r.ny << "\n255\n";
  std::vector<char> row(r.nx);
  for (int j = r.ny - 1; j >= 0; --j) {
    for (int i = 0; i < r.nx; ++i) {
      const std::size_t k = r.index(i, j);
      row[i] = static_cast<char>(r.material[k]                                      ? 0
                                 : (!v.region.inside.empty() && v.region.inside[k]) ? 160
                                                                                    : 255);
    }
    out.write(row.data(), r.nx);
  }
}

void print_sheet(const char* what, const SheetMeasurement& s) {
  const auto& h = s.hole;
  fmt::print("{} ({}): {}", what, s.body, h.perforated ? "perforated" : "not perforated (NP)");
  if (h.resolution == 0) {  // nothing of the sheet is left attached
    fmt::print("  [no intact attached material left: {} intact particles, all detached]\n",
               s.intact);
    return;
  }
  fmt::print("  [raster {:.4g} mm = spacing/{:.3g}; {} intact particles, {} detached left out]\n",
             h.resolution / mm, s.spacing / h.resolution, s.intact, s.detached);
  if (!h.perforated) return;
  fmt::print("  D_theta (mm):");
  for (int k = 0; k < 12; ++k)
    fmt::print(" {:g}:{:.3f}", std::round(analysis::HoleGeometry::angle(k, h.rotation) / deg),
               h.D_theta(k) / mm);
  fmt::print("\n  {}: D_h = {:.3f} mm, D_v = {:.3f} mm, D = {:.3f} mm, e = {:.4f}\n",
             rule_text(h.rule), h.D_h / mm, h.D_v / mm, h.D / mm, h.eccentricity);
  fmt::print("  area {:.4f} mm^2, equivalent diameter {:.3f} mm{}\n", h.area / (mm * mm),
             h.equivalent_diameter / mm,
             h.open ? "; the hole reaches the edge of the sheet: sizes are lower bounds" : "");
}

}  // namespace

void write_measurements(const Measurements& m, const fs::path& dir) {
  toml::table j{{"run", m.run.string()},
                {"snapshot", m.snapshot_file.filename().string()},
                {"time", m.time},
                {"step", m.step},
                {"units", "SI (m, kg, s); angles in degrees"},
                {"axis", toml::array{m.axis[0], m.axis[1]}},
                {"impact_direction", toml::array{0.0, 0.0, -1.0}}};
  toml::table mirror;
  if (m.mirror.x) mirror.insert("x", *m.mirror.x);
  if (m.mirror.y) mirror.insert("y", *m.mirror.y);
  j.insert("mirror_planes", mirror);
  // With --images, where each top view lies: pixel (0, 0) of the PGM's bottom row at (x0, y0).
  const auto sheet = [](const SheetMeasurement& s,
                        const std::optional<analysis::FacesheetResult>& view, const char* file) {
    toml::table t = sheet_json(s);
    if (view)
      t.insert("top_view", toml::table{{"file", file},
                                       {"x0", view->raster.x0},
                                       {"y0", view->raster.y0},
                                       {"pixel", view->raster.cell},
                                       {"nx", view->raster.nx},
                                       {"ny", view->raster.ny}});
    return t;
  };
  if (m.front) j.insert("front", sheet(*m.front, m.front_view, "top_view_front.pgm"));
  if (m.rear) j.insert("rear", sheet(*m.rear, m.rear_view, "top_view_rear.pgm"));
  if (m.taper) j.insert("taper", *m.taper);
  if (m.core_height) j.insert("core_height", *m.core_height);
  if (m.bulge)
    j.insert("rear_bulge",
             toml::table{{"displacement", m.bulge->displacement},
                         {"particle_id", m.bulge->id},
                         {"position", toml::array{m.bulge->position[0], m.bulge->position[1],
                                                  m.bulge->position[2]}}});
  if (!m.debris_behind.empty())
    j.insert("debris", toml::table{{"behind", m.debris_behind},
                                   {"back_face_z", m.debris_back_face},
                                   {"threshold", m.debris_threshold},
                                   {"mass", m.debris.mass},
                                   {"particles", static_cast<std::int64_t>(m.debris.particles)},
                                   {"axial_extent", m.debris.axial_extent},
                                   {"radial_extent", m.debris.radial_extent},
                                   {"kinetic_energy", m.debris.kinetic_energy}});
  if (m.spall)
    j.insert("rear_spall", toml::table{{"mass", m.spall->mass},
                                       {"particles", static_cast<std::int64_t>(m.spall->particles)},
                                       {"axial_extent", m.spall->axial_extent},
                                       {"radial_extent", m.spall->radial_extent}});
  toml::table vars;
  for (const auto& [name, value] : m.variables) vars.insert(name, value);
  j.insert("variables", vars);
  toml::array notes;
  for (const auto& n : m.notes) notes.push_back(n);
  j.insert("notes", notes);
  {
    std::ofstream json(dir / "measurements.json");
    json << toml::json_formatter(j) << '\n';
  }

  write_csv({m}, dir / "measurements.csv");
  if (m.front_view) write_pgm(dir / "top_view_front.pgm", *m.front_view);
  if (m.rear_view) write_pgm(dir / "top_view_rear.pgm", *m.rear_view);
}

void write_history(const std::vector<Measurements>& history, const fs::path& dir) {
  write_csv(history, dir / "measurements_history.csv");
}

void append_history_row(const Measurements& m, const fs::path& file) {
  const bool header = !fs::exists(file) || fs::file_size(file) == 0;
  std::ofstream out(file, std::ios::app);
  if (header) write_csv_line(out, m, true);
  write_csv_line(out, m, false);
}

void keep_history_rows(const fs::path& file, std::int64_t last_step) {
  if (!fs::exists(file)) return;
  std::string kept, line;
  {
    std::ifstream in(file);
    for (bool first = true; std::getline(in, line); first = false) {
      // The third column is the step (run, time, step, ...).
      const auto a = line.find(',');
      const auto b = a == std::string::npos ? a : line.find(',', a + 1);
      const auto c = b == std::string::npos ? b : line.find(',', b + 1);
      // (A line whose step does not parse, a file edited by hand, is kept rather than stopping the
      // run.)
      std::int64_t step = 0;
      const bool parsed =
          c != std::string::npos &&
          std::from_chars(line.data() + b + 1, line.data() + c, step).ec == std::errc{};
      if (!first && parsed && step > last_step) continue;
      kept += line + '\n';
    }
  }
  std::ofstream(file, std::ios::trunc) << kept;
}

void remove_measurements(const fs::path& dir) {
  for (const char* f : {"measurements.json", "measurements.csv", "top_view_front.pgm",
                        "top_view_rear.pgm", "measurements_history.csv", "measure.log"})
    fs::remove(dir / f);
}

std::vector<std::pair<std::string, double>> headline_quantities(const Measurements& m) {
  std::vector<std::pair<std::string, double>> q;
  auto sheet = [&](const std::optional<SheetMeasurement>& s, const char* which) {
    if (!s) return;
    q.emplace_back(fmt::format("{}_perforated", which), s->hole.perforated ? 1.0 : 0.0);
    if (!s->hole.perforated) return;
    const char c = which[0];
    // Nothing of the sheet left attached (a hybrid's zone torn away whole): no size to give.
    const double nan = std::numeric_limits<double>::quiet_NaN();
    q.emplace_back(fmt::format("D_{}", c), s->hole.resolution > 0 ? s->hole.D : nan);
    q.emplace_back(fmt::format("e_{}", c), s->hole.resolution > 0 ? s->hole.eccentricity : nan);
    // 1: the hole reaches the sheet's edge (a hybrid's zone, the model's side), so D is a lower
    // bound.
    q.emplace_back(fmt::format("{}_hole_open", which), s->hole.open ? 1.0 : 0.0);
  };
  sheet(m.front, "front");
  sheet(m.rear, "rear");
  if (m.taper) q.emplace_back("taper", *m.taper);
  if (m.bulge) q.emplace_back("bulge", m.bulge->displacement);
  if (!m.debris_behind.empty()) {
    q.emplace_back("debris_mass", m.debris.mass);
    q.emplace_back("debris_kinetic_energy", m.debris.kinetic_energy);
  }
  return q;
}

void print_measurements(const Measurements& m) {
  fmt::print("hvi measure {}: {} at t = {:.4g} us (step {})\n", m.run.string(),
             m.snapshot_file.filename().string(), m.time * 1e6, m.step);
  fmt::print("impact axis ({:.4f}, {:.4f}) mm along -z", m.axis[0] / mm, m.axis[1] / mm);
  if (m.mirror.x) fmt::print("; mirrored across x = {:.4g} mm", *m.mirror.x / mm);
  if (m.mirror.y) fmt::print("; mirrored across y = {:.4g} mm", *m.mirror.y / mm);
  fmt::print("\n");
  if (m.front) print_sheet("front", *m.front);
  if (m.rear) print_sheet("rear", *m.rear);
  if (m.taper)
    fmt::print("taper t = (D_r - D_f) / S = {:.4f} (S = {:.3f} mm), eq. (12)\n", *m.taper,
               *m.core_height / mm);
  if (m.bulge)
    fmt::print("rear bulge: {:.4f} mm (particle {} at ({:.3f}, {:.3f}, {:.3f}) mm)\n",
               m.bulge->displacement / mm, m.bulge->id, m.bulge->position[0] / mm,
               m.bulge->position[1] / mm, m.bulge->position[2] / mm);
  if (!m.debris_behind.empty())
    fmt::print(
        "debris behind {} (more than {:.4g} mm past z = {:.4f} mm): {:.4g} g in {} particles, "
        "{:.3f} mm deep, "
        "{:.3f} mm from the axis, kinetic energy {:.4g} J\n",
        m.debris_behind, m.debris_threshold / mm, m.debris_back_face / mm, m.debris.mass * 1e3,
        m.debris.particles, m.debris.axial_extent / mm, m.debris.radial_extent / mm,
        m.debris.kinetic_energy);
  if (m.spall && m.spall->particles > 0)
    fmt::print(
        "detached spall of the rear sheet: {:.4g} mg in {} intact particles, {:.3f} mm "
        "deep\n",
        m.spall->mass * 1e6, m.spall->particles, m.spall->axial_extent / mm);
  for (const auto& n : m.notes) fmt::print("note: {}\n", n);
}

int measure_command(const MeasureOptions& options) {
  const fs::path dir = options.out.empty() ? options.run : options.out;
  if (options.snapshot == "all") {
    const std::vector<Measurements> history = measure_history(options);
    fmt::print("hvi measure {}: {} snapshots\n", options.run.string(), history.size());
    fmt::print("{:>10} {:>7} {:>10} {:>10} {:>11} {:>12}\n", "t (us)", "step", "D_f (mm)",
               "D_r (mm)", "bulge (mm)", "debris (mg)");
    auto hole = [](const std::optional<SheetMeasurement>& s) {
      if (!s) return std::string{"-"};
      if (!s->hole.perforated) return std::string{"NP"};
      return s->hole.resolution > 0 ? fmt::format("{:.3f}", s->hole.D / mm) : std::string{"gone"};
    };
    for (const Measurements& m : history)
      fmt::print("{:>10.4g} {:>7} {:>10} {:>10} {:>11} {:>12.4g}\n", m.time * 1e6, m.step,
                 hole(m.front), hole(m.rear),
                 m.bulge ? fmt::format("{:.3f}", m.bulge->displacement / mm) : std::string{"-"},
                 m.debris.mass * 1e6);
    fs::create_directories(dir);
    write_history(history, dir);
    fmt::print("output: {}\n", (dir / "measurements_history.csv").string());
    return ExitCode::success;
  }
  const Measurements m = measure_run(options);
  print_measurements(m);
  fs::create_directories(dir);
  write_measurements(m, dir);
  fmt::print("output: {} and measurements.csv{}\n", (dir / "measurements.json").string(),
             options.images ? ", top_view_*.pgm" : "");
  return ExitCode::success;
}

}  // namespace hvi::driver
