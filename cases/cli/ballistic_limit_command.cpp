#include "cases/cli/ballistic_limit_command.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "analysis/ballistic_limit_equation.hpp"
#include "cases/cli/child_run.hpp"
#include "cases/cli/curve_search.hpp"
#include "cases/cli/experiments.hpp"
#include "cases/cli/option_value.hpp"
#include "cases/cli/rear_outcome.hpp"
#include "cases/cli/sweep_command.hpp"
#include "cases/run/run.hpp"
#include "cases/scene/scene.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

namespace {

constexpr double mm = 1e-3, km_s = 1e3;

// A positive value with a unit of dimension `dim` (a bare number is SI, or in `fallback_unit`).
double quantity(const std::string& option, const std::string& text, const std::string& dim,
                const std::string& fallback_unit = "") {
  const bool bare = text.find_first_not_of("0123456789.eE+- ") == std::string::npos;
  const std::string written = bare && !fallback_unit.empty() ? text + " " + fallback_unit : text;
  const double v = si_value(written, dim, option + " ");
  if (!(v > 0))
    throw std::invalid_argument(fmt::format("{} '{}': expected a positive {}", option, text, dim));
  return v;
}

// What a trial changes, and the panel the SRL equation sees.
struct Setup {
  scene::Scene scene;
  scene::SphereShape sphere{};
  scene::Vec3 direction{};  // unit, of the projectile's velocity
  double speed = 0;         // the scene's, m/s
  analysis::SandwichPanel panel;
  double projectile_density = 0;
};

Setup read_setup(const BallisticLimitOptions& o) {
  Setup s;
  s.scene = scene::load_scene(o.scene, o.overrides);
  const scene::BodySettings* projectile = nullptr;
  for (const auto& b : s.scene.bodies)
    if (b.name == o.projectile) projectile = &b;
  if (!projectile || !std::holds_alternative<scene::SphereShape>(projectile->shape))
    throw std::invalid_argument(
        fmt::format("--projectile {}: {} has no sphere body of that name", o.projectile, o.scene));
  s.sphere = std::get<scene::SphereShape>(projectile->shape);
  const auto& v = projectile->velocity;
  s.speed = std::hypot(v[0], v[1], v[2]);
  if (!(s.speed > 0))
    throw std::invalid_argument(
        fmt::format("body '{}' of {} does not move", o.projectile, o.scene));
  for (int k = 0; k < 3; ++k) s.direction[k] = v[k] / s.speed;
  if (s.scene.panels.size() != 1)
    throw std::invalid_argument(fmt::format("{}: a ballistic limit needs one [[panel]]", o.scene));
  const scene::PanelSettings& p = s.scene.panels[0];
  auto material_of = [&](const std::string& body) -> const scene::MaterialSettings& {
    for (const auto& b : s.scene.bodies)
      if (b.name == body) return s.scene.materials[b.material];
    throw std::invalid_argument("no body " + body);
  };
  const auto& rear = material_of(p.name + ".rear");
  double yield = rear.models.johnson_cook ? rear.models.johnson_cook->A : 0;
  if (!o.rear_yield.empty()) yield = quantity("--rear-yield", o.rear_yield, "pressure");
  if (!(yield > 0))
    throw std::invalid_argument(
        "the rear sheet's material has no Johnson-Cook A: give --rear-yield for the SRL equation");
  s.panel = {p.front_thickness, p.rear_thickness,
             p.front_thickness + p.core_height + p.rear_thickness, yield,
             material_of(p.name + ".front").models.density};
  s.projectile_density = s.scene.materials[projectile->material].models.density;
  return s;
}

std::string si(double v, const char* unit) {
  return fmt::format("{:.9g} {}", v, unit);
}

// The overrides of one trial: the projectile of diameter d at speed v.
std::vector<std::string> trial_overrides(const Setup& s, const BallisticLimitOptions& o, double d,
                                         double v) {
  const std::string body = "body." + o.projectile;
  // Scaled about its leading point: c' = c + u (r0 - r).
  const double r = 0.5 * d, shift = s.sphere.radius - r;
  std::vector<std::string> out = o.overrides;
  out.push_back(fmt::format("{}.sphere.radius={}", body, si(r, "m")));
  out.push_back(fmt::format("{}.sphere.center=[\"{}\", \"{}\", \"{}\"]", body,
                            si(s.sphere.center[0] + s.direction[0] * shift, "m"),
                            si(s.sphere.center[1] + s.direction[1] * shift, "m"),
                            si(s.sphere.center[2] + s.direction[2] * shift, "m")));
  out.push_back(fmt::format("{}.velocity=[\"{}\", \"{}\", \"{}\"]", body,
                            si(s.direction[0] * v, "m/s"), si(s.direction[1] * v, "m/s"),
                            si(s.direction[2] * v, "m/s")));
  out.push_back(fmt::format("run.end_time={}", si(s.scene.end_time * s.speed / v, "s")));
  return out;
}

std::string trial_name(double d, double v) {
  return fmt::format("v{:.3f}kms_d{:.4f}mm", v / km_s, d / mm);
}

}  // namespace

std::vector<double> parse_speeds(const std::string& text) {
  std::vector<std::string> parts;
  std::string part;
  for (const char c : text + ",") {
    if (c == ',') {
      parts.push_back(part);
      part.clear();
    } else {
      part += c;
    }
  }
  // The unit of the last part applies to bare numbers before it ("2,3,4km/s").
  std::string unit;
  const std::string& last = parts.back();
  const auto at = last.find_first_not_of("0123456789.eE+- ");
  if (at != std::string::npos) unit = last.substr(at);
  if (unit.empty())
    throw std::invalid_argument(
        fmt::format("--speeds {}: give the speeds a unit, such as 2,3,4.5km/s", text));
  std::vector<double> speeds;
  for (const auto& p : parts) speeds.push_back(quantity("--speeds", p, "velocity", unit));
  return speeds;
}

namespace {

// The experiments of the database on this panel (t_f, t_r and S within 2%).
std::vector<Shot> matching_shots(const Setup& s, const BallisticLimitOptions& o) {
  fs::path db = o.database;
  if (db.empty()) db = fs::path(o.scene).parent_path() / "hcsp_shots.csv";
  if (!fs::exists(db)) return {};
  const auto names = read_material_names(db.parent_path() / "material_names.csv");
  auto near = [](double a, double b) { return std::abs(a - b) <= 0.02 * b; };
  std::vector<Shot> out;
  for (const Shot& shot : read_shots(db, names))
    if (near(shot.t_f, s.panel.front_thickness) && near(shot.t_r, s.panel.rear_thickness) &&
        near(shot.S, s.panel.spacing))
      out.push_back(shot);
  return out;
}

// Runs the trials of one round (search, value); the code of an interrupted study, else success.
int run_round(const Setup& s, const BallisticLimitOptions& o,
              const std::vector<std::pair<std::size_t, double>>& pending, CurveSearch& curve,
              Study& all, bool by_diameter, const parallel::Ranks& ranks) {
  SweepOptions sweep;
  sweep.study = o.scene;
  sweep.out = (fs::path(o.out) / "trials").string();
  sweep.threads = o.threads;
  sweep.hvi = o.hvi;
  sweep.quiet_end = true;
  sweep.quiet_start = true;
  auto trial = [&](std::size_t k, double value) {
    const double fixed = curve.entry(k).point.fixed;
    return by_diameter ? std::pair{value, fixed} : std::pair{fixed, value};  // d, v
  };
  for (const auto& [k, value] : pending) {
    const auto [d, v] = trial(k, value);
    const std::string name = trial_name(d, v);
    sweep.only.push_back(name);
    if (std::none_of(all.runs.begin(), all.runs.end(), [&](auto& r) { return r.name == name; }))
      all.runs.push_back(
          SweepRun{name, {{"speed", fmt::format("{:g}", v / km_s)}}, trial_overrides(s, o, d, v)});
  }
  const int code = run_study(all, sweep, ranks);
  if (stopped_by_signal(code)) return code;
  const Criterion criterion = *parse_criterion(o.criterion);
  for (const auto& [k, value] : pending) {
    const auto [d, v] = trial(k, value);
    const fs::path dir = fs::path(sweep.out) / trial_name(d, v);
    CurveSearch::Entry& e = curve.entry(k);
    e.wall += read_run_summary(dir).wall_seconds;
    const auto outcome = read_rear_outcome(dir);
    if (!outcome)
      e.failed = trial_name(d, v);
    else
      curve.record(k, value, outcome->perforated(criterion));
  }
  return success;
}

std::string mm_or_blank(double v) {
  return std::isfinite(v) ? fmt::format("{:.6g}", v / mm) : "";
}

std::string status_of(const CurveSearch::Entry& x) {
  if (!x.failed.empty()) return "trial " + x.failed + " failed";
  return x.started ? x.search.status() : "waiting";
}

// Where a search's first trial came from: "srl" or a neighbour's speed (diameter), "5 km/s".
std::string started_from(const CurveSearch::Entry& x, bool by_diameter) {
  if (!x.started_from) return by_diameter ? "srl" : "geometric mean";
  return by_diameter ? fmt::format("{:g} km/s", *x.started_from / km_s)
                     : fmt::format("{:g} mm", *x.started_from / mm);
}

// ballistic_limit.csv and trials.csv, rewritten after every round.
void write_limits(const Setup& s, const BallisticLimitOptions& o, const CurveSearch& curve,
                  bool by_diameter) {
  std::ofstream limits(fs::path(o.out) / "ballistic_limit.csv");
  std::ofstream trials(fs::path(o.out) / "trials.csv");
  if (by_diameter) {
    limits << "speed_km_s,critical_diameter_mm,stopped_mm,perforated_mm,trials,wall_seconds,"
              "status,srl_critical_diameter_mm,srl_regime,started_from\n";
    trials << "speed_km_s,diameter_mm,outcome,run\n";
  } else {
    limits << "diameter_mm,critical_speed_km_s,stopped_km_s,perforated_km_s,trials,wall_seconds,"
              "status,started_from\n";
    trials << "diameter_mm,speed_km_s,outcome,run\n";
  }
  for (const CurveSearch::Entry& x : curve.entries()) {
    const LimitSearch& f = x.search;
    const double fixed = x.point.fixed;
    const std::string status = status_of(x), from = started_from(x, by_diameter);
    if (by_diameter) {
      const auto srl = analysis::srl_critical_diameter(s.panel, s.projectile_density, fixed);
      limits << fmt::format("{:g},{},{},{},{},{:.1f},{},{:.6g},{},{}\n", fixed / km_s,
                            mm_or_blank(f.limit()), mm_or_blank(f.stopped()),
                            mm_or_blank(f.perforated()), f.trials(), x.wall, status,
                            srl.diameter / mm, analysis::to_string(srl.regime), from);
    } else {
      auto kms = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v / km_s) : ""; };
      limits << fmt::format("{:g},{},{},{},{},{:.1f},{},{}\n", fixed / mm, kms(f.limit()),
                            kms(f.stopped()), kms(f.perforated()), f.trials(), x.wall, status,
                            from);
    }
    for (const auto& [value, p] : f.history()) {
      const double d = by_diameter ? value : fixed, v = by_diameter ? fixed : value;
      trials << fmt::format("{:.6g},{:.6g},{},{}\n", by_diameter ? v / km_s : d / mm,
                            by_diameter ? d / mm : v / km_s, p ? "P" : "NP", trial_name(d, v));
    }
  }
}

void print_limits(const CurveSearch& curve, bool by_diameter) {
  fmt::print("\n{:>10} {:>12} {:>22} {:>7} {:>10}  {:<14}  {}\n",
             by_diameter ? "v (km/s)" : "d (mm)", by_diameter ? "d_c (mm)" : "v_c (km/s)",
             "bracket (NP .. P)", "trials", "wall (s)", "first trial", "status");
  const double unit = by_diameter ? mm : km_s, fixed_unit = by_diameter ? km_s : mm;
  for (const CurveSearch::Entry& x : curve.entries()) {
    const LimitSearch& f = x.search;
    fmt::print("{:>10.3g} {:>12.4g} {:>10.4g} .. {:>8.4g} {:>7} {:>10.1f}  {:<14}  {}\n",
               x.point.fixed / fixed_unit, f.limit() / unit, f.stopped() / unit,
               f.perforated() / unit, f.trials(), x.wall, started_from(x, by_diameter),
               status_of(x));
  }
}

void write_experiments(const BallisticLimitOptions& o, const std::vector<Shot>& shots) {
  std::ofstream out(fs::path(o.out) / "experiments.csv");
  out << "run,speed_km_s,diameter_mm,outcome\n";
  for (const Shot& shot : shots)
    out << fmt::format("{},{:g},{:g},{}\n", shot.run_name(), shot.v_p / km_s, shot.d_p / mm,
                       shot.perforated ? "P" : "NP");
}

// The SRL curve from 0.5 km/s to 1 km/s past the fastest speed.
void write_srl(const Setup& s, const BallisticLimitOptions& o, const std::vector<double>& speeds) {
  std::ofstream out(fs::path(o.out) / "srl.csv");
  out << "speed_km_s,critical_diameter_mm,regime\n";
  const double top = *std::max_element(speeds.begin(), speeds.end()) + km_s;
  for (double v = 0.5 * km_s; v <= top + 1; v += 0.05 * km_s) {
    const auto d = analysis::srl_critical_diameter(s.panel, s.projectile_density, v);
    out << fmt::format("{:.4g},{:.6g},{}\n", v / km_s, d.diameter / mm,
                       analysis::to_string(d.regime));
  }
}

// ballistic_limit.png (scripts/plot_ballistic_limit.py, matplotlib); a failed plot is a warning.
void plot(const BallisticLimitOptions& o) {
  const std::string cmd =
      "/usr/bin/python3 " +
      shell_quote(std::string(HVI_SOURCE_DIR) + "/scripts/plot_ballistic_limit.py") + " " +
      shell_quote(o.out);
  if (std::system(cmd.c_str()) != 0)
    fmt::print(stderr, "hvi ballistic-limit: warning: no plot (needs python3-matplotlib)\n");
}

}  // namespace

int run_ballistic_limit(const BallisticLimitOptions& o, const parallel::Ranks& ranks) {
  if (!parse_criterion(o.criterion) || (o.vary != "diameter" && o.vary != "velocity"))
    throw std::invalid_argument(fmt::format(
        "--criterion {} --vary {}: expected hole, spall or either, and diameter or velocity",
        o.criterion, o.vary));
  if (o.start_from != "neighbour" && o.start_from != "srl")
    throw std::invalid_argument(
        fmt::format("--start-from {}: expected neighbour or srl", o.start_from));
  const Setup s = read_setup(o);
  const bool by_diameter = o.vary == "diameter";
  const std::vector<double> speeds = parse_speeds(o.speeds);
  std::vector<CurvePoint> points;
  if (by_diameter) {
    for (const double v : speeds)
      points.push_back(
          {v, analysis::srl_critical_diameter(s.panel, s.projectile_density, v).diameter});
  } else {
    if (o.diameter.empty() || speeds.size() != 2)
      throw std::invalid_argument(
          "--vary velocity: give --diameter and --speeds LOW,HIGH (the first trial at their "
          "geometric mean)");
    points.push_back(
        {quantity("--diameter", o.diameter, "length"), std::sqrt(speeds[0] * speeds[1])});
  }
  // With carry, --parallel-searches at a time (1: on one rank a round runs its trials one after
  // the other, so waiting for a neighbour costs nothing). Not the ranks' count: the trials must
  // not depend on it.
  CurveSearch curve(points, {.search = {.tolerance = o.tolerance,
                                        .max_trials = o.max_trials,
                                        .quantum = by_diameter ? 1e-6 : 1.0},
                             .carry = o.start_from == "neighbour",
                             .in_flight = o.parallel_searches});
  fs::create_directories(fs::path(o.out) / "trials");
  Study all{fmt::format("ballistic limit of {}", o.scene), o.scene, {}};
  // Under mpirun every rank runs the same searches: each round's trials are shared among the
  // ranks (run_study), and every rank reads their outcomes when all have ended; rank 0 writes.
  const bool root = ranks.root();
  if (root)
    fmt::print("hvi ballistic-limit: {} — {} search{}, tolerance {:g}%{}\n", o.scene, points.size(),
               points.size() == 1 ? "" : "es", o.tolerance * 100,
               ranks.size() > 1
                   ? fmt::format(", each round's trials shared among {} ranks", ranks.size())
                   : "");
  for (auto round = curve.round(); !round.empty(); round = curve.round()) {
    const int code = run_round(s, o, round, curve, all, by_diameter, ranks);
    if (code != success) {
      if (root)
        fmt::print("hvi ballistic-limit: interrupted; run the same command again to resume\n");
      return code;
    }
    if (root) write_limits(s, o, curve, by_diameter);
  }
  if (root) {
    write_limits(s, o, curve, by_diameter);
    print_limits(curve, by_diameter);
    write_experiments(o, matching_shots(s, o));
    write_srl(s, o, speeds);
    plot(o);
  }
  return std::all_of(curve.entries().begin(), curve.entries().end(),
                     [](auto& x) { return x.failed.empty() && x.search.converged(); })
             ? success
             : run_failed;
}

}  // namespace hvi::driver
