#include "cases/cli/convergence_command.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "cases/cli/child_run.hpp"
#include "cases/run/run.hpp"
#include "cases/scene/scene.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

namespace {

struct Level {
  std::string label;
  double cell_size = 0;
  int particles_per_cell = 0;  // 0: the scene's
  // From the run's summary.
  bool done = false;
  double wall_seconds = 0, peak_memory = 0, particles = 0, steps = 0;
  std::map<std::string, double> measures;
};

bool read_summary(const fs::path& dir, Level& level) {
  const RunSummary s = read_run_summary(dir);
  if (!s.finished()) return false;
  level.wall_seconds = s.wall_seconds;
  level.peak_memory = s.peak_memory;
  level.particles = s.particles;
  level.steps = s.steps;
  level.measures = s.measures;
  level.done = true;
  return true;
}

}  // namespace

Extrapolation richardson(double q0, double q1, double q2, double ratio) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Extrapolation e{nan, nan};
  const double d1 = q1 - q0, d2 = q2 - q1;
  if (d1 == 0.0 || d2 == 0.0 || d1 * d2 < 0.0) return e;  // not (monotonically) converging
  e.order = std::log(std::fabs(d1 / d2)) / std::log(ratio);
  if (e.order > 0.0) e.value = q2 + d2 / (std::pow(ratio, e.order) - 1.0);
  return e;
}

namespace {

// The ladder: each cell size from the scene's down by `ratio`, at each particle count.
std::vector<Level> ladder_levels(const ConvergenceOptions& o, const scene::Scene& base,
                                 const std::vector<int>& ppcs) {
  std::vector<Level> levels;
  for (int k = 0; k < o.levels; ++k)
    for (const int ppc : ppcs) {
      Level l;
      l.cell_size = base.grid.cell_size / std::pow(o.ratio, k);
      l.particles_per_cell = ppc;
      l.label = ppc ? fmt::format("h{}_ppc{}", k, ppc) : fmt::format("h{}", k);
      levels.push_back(l);
    }
  return levels;
}

// Runs a level as a child `hvi run` unless it is done; false (having said why) when it failed.
bool run_level(const ConvergenceOptions& o, const scene::Scene& base, Level& l) {
  const fs::path dir = fs::path(o.out) / l.label;
  if (read_summary(dir, l)) {
    fmt::print("hvi convergence: {} already done ({:.1f} s)\n", l.label, l.wall_seconds);
    return true;
  }
  // The user's overrides first: the level's cell size and particle count come last and win.
  std::vector<std::string> args{"run", o.scene, "--out", dir.string(), "--overwrite"};
  if (o.threads > 0) args.insert(args.end(), {"--threads", std::to_string(o.threads)});
  for (const auto& s : o.overrides) args.insert(args.end(), {"--set", s});
  args.insert(args.end(), {"--set", fmt::format("grid.cell_size={:.17g}", l.cell_size)});
  if (l.particles_per_cell)
    for (const auto& b : base.bodies)
      args.insert(args.end(), {"--set", fmt::format("body.{}.particles_per_cell={}", b.name,
                                                    l.particles_per_cell)});
  fmt::print("hvi convergence: running {} (cell {:.4g} m)\n", l.label, l.cell_size);
  std::fflush(stdout);
  const fs::path log = fs::path(o.out) / (l.label + ".log");
  const int status = run_child(o.hvi, args, log);
  // The level's warnings, and for a failed one its own account, on the console (as hvi sweep).
  const ChildLog said = read_child_log(log, 0, o.scene);
  if (status != 0 || !read_summary(dir, l)) {
    fmt::print(stderr, "hvi convergence: level {} failed; see {}\n", l.label, log.string());
    for (const auto& line : said.outcome) fmt::print(stderr, "  {}\n", line);
    for (const auto& line : said.warnings) fmt::print(stderr, "  {}\n", line);
    return false;
  }
  for (const auto& line : said.warnings) fmt::print("  {}\n", line);
  return true;
}

// Each measure's reference, and its errors: given by --reference, else Richardson-extrapolated
// from the three finest cell sizes (at the first particle count of the ladder). An energy_error
// measure is an error already: its reference is 0 and its error its value.
struct References {
  std::map<std::string, double> value;
  std::map<std::string, Extrapolation> extrapolated;
  std::set<std::string> is_error;
  double of(const std::string& name) const {
    return value.count(name) ? value.at(name) : std::numeric_limits<double>::quiet_NaN();
  }
  double relative_error(const std::string& name, double v, double ref) const {
    return is_error.count(name) ? v : (v - ref) / std::fabs(ref);
  }
};

References references(const ConvergenceOptions& o, const scene::Scene& base,
                      const std::vector<Level>& levels, int first_ppc) {
  References r;
  std::vector<const Level*> ladder;
  for (const auto& l : levels)
    if (l.particles_per_cell == first_ppc) ladder.push_back(&l);
  for (const auto& [name, value] : levels.back().measures) {
    if (ladder.size() >= 3) {
      const auto n = ladder.size();
      r.extrapolated[name] =
          richardson(ladder[n - 3]->measures.at(name), ladder[n - 2]->measures.at(name),
                     ladder[n - 1]->measures.at(name), o.ratio);
      r.value[name] = r.extrapolated[name].value;
    }
  }
  for (const auto& ref : o.references) {
    const auto eq = ref.find('=');
    r.value[ref.substr(0, eq)] = std::stod(ref.substr(eq + 1));
  }
  for (const auto& m : base.measures)
    if (m.kind == "energy_error") r.is_error.insert(m.name);
  return r;
}

// convergence.csv: one row per level and quantity.
void write_csv(const ConvergenceOptions& o, const std::vector<Level>& levels, const References& r) {
  std::ofstream csv(fs::path(o.out) / "convergence.csv");
  csv << "level,cell_size,particles_per_cell,particles,steps,wall_seconds,peak_memory_bytes,"
         "quantity,value,reference,relative_error\n";
  for (const auto& l : levels)
    for (const auto& [name, value] : l.measures) {
      const double ref = r.of(name);
      csv << fmt::format("{},{:.6g},{},{:.0f},{:.0f},{:.3f},{:.0f},{},{:.10g},{:.10g},{:.6g}\n",
                         l.label, l.cell_size, l.particles_per_cell, l.particles, l.steps,
                         l.wall_seconds, l.peak_memory, name, value, ref,
                         r.relative_error(name, value, ref));
    }
}

// convergence.md: a table per quantity, error and cost side by side.
std::string markdown(const ConvergenceOptions& o, const std::vector<Level>& levels,
                     const References& r) {
  std::string md =
      fmt::format("# Convergence of {}\n\nCommand: `hvi convergence {} --levels {}{}`\n\n", o.scene,
                  o.scene, o.levels, o.ratio == 2.0 ? "" : fmt::format(" --ratio {:g}", o.ratio));
  for (const auto& entry : levels.back().measures) {
    const std::string& name = entry.first;
    const double ref = r.of(name);
    md += fmt::format("## {}\n\n", name);
    const auto e = r.extrapolated.find(name);
    if (e != r.extrapolated.end() && std::isfinite(e->second.order))
      md += fmt::format("Observed order {:.2f}; Richardson-extrapolated value {:.6g}.\n\n",
                        e->second.order, e->second.value);
    if (r.is_error.count(name))
      md += "The value is itself the relative error of the energy balance.\n\n";
    else if (std::isfinite(ref))
      md += fmt::format("Reference: {:.6g}\n\n", ref);
    else
      md +=
          "No reference (three converging levels or --reference name=value are needed for "
          "errors).\n\n";
    md +=
        "| level | cell (mm) | ppc | particles | value | error vs reference | wall time (s) | peak "
        "memory (MB) |\n";
    md += "|---|---|---|---|---|---|---|---|\n";
    for (const auto& l : levels) {
      const double v =
          l.measures.count(name) ? l.measures.at(name) : std::numeric_limits<double>::quiet_NaN();
      const double err = r.relative_error(name, v, ref);
      const std::string error = std::isfinite(err) ? fmt::format("{:+.3g}%", 100 * err) : "—";
      md += fmt::format("| {} | {:.4g} | {} | {:.0f} | {:.6g} | {} | {:.1f} | {:.0f} |\n", l.label,
                        l.cell_size * 1e3,
                        l.particles_per_cell ? std::to_string(l.particles_per_cell) : "scene",
                        l.particles, v, error, l.wall_seconds, l.peak_memory / 1e6);
    }
    md += "\n";
  }
  return md;
}

// Plots: error against wall time, one panel per quantity (matplotlib), with Debian's python3
// (with python3-matplotlib) rather than another one earlier on the PATH.
void plot(const ConvergenceOptions& o) {
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string plot =
      fmt::format("{} {} {} > /dev/null 2>&1", python,
                  shell_quote(std::string(HVI_SOURCE_DIR) + "/scripts/plot_convergence.py"),
                  shell_quote(o.out));
  if (std::system(plot.c_str()) == 0)
    fmt::print("plots: {}\n", (fs::path(o.out) / "convergence.png").string());
  else
    fmt::print(
        "(no plots: python3 with matplotlib not found; the CSV and Markdown are complete)\n");
}

}  // namespace

int run_convergence(const ConvergenceOptions& o) {
  const scene::Scene base = scene::load_scene(o.scene, o.overrides);
  const std::vector<int> ppcs =
      o.particles_per_cell.empty() ? std::vector<int>{0} : o.particles_per_cell;
  std::vector<Level> levels = ladder_levels(o, base, ppcs);
  fs::create_directories(o.out);
  for (auto& l : levels)
    if (!run_level(o, base, l)) return run_failed;
  const References r = references(o, base, levels, ppcs.front());
  write_csv(o, levels, r);
  const std::string md = markdown(o, levels, r);
  std::ofstream(fs::path(o.out) / "convergence.md") << md;
  fmt::print("{}", md);
  plot(o);
  return success;
}

}  // namespace hvi::driver
