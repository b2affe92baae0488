#include "cases/cli/validate_command.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "analysis/ballistic_limit_equation.hpp"
#include "cases/cli/experiments.hpp"
#include "cases/cli/sweep_command.hpp"
#include "cases/run/run.hpp"
#include "cases/scene/scene.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

void Confusion::add(bool observed, bool predicted) {
  (observed ? (predicted ? true_p : false_np) : (predicted ? false_p : true_np)) += 1;
}

namespace {

constexpr double mm = 1e-3;

analysis::CriticalDiameter ble(const Shot& s) {
  const analysis::SandwichPanel panel{s.t_f, s.t_r, s.S, s.rear_yield, s.rear_density};
  return analysis::srl_critical_diameter(panel, s.projectile_density, s.v_p);
}

// The shots --only names (by shot id or run name), or all; empty after saying which is unknown.
std::vector<Shot> select(const std::vector<Shot>& shots, const ValidateOptions& o) {
  if (o.only.empty()) return shots;
  std::vector<Shot> kept;
  for (const auto& name : o.only) {
    std::vector<const Shot*> match;
    for (const auto& s : shots)
      if (s.id == name || s.run_name() == name) match.push_back(&s);
    if (match.size() != 1) {
      fmt::print(stderr, "hvi validate: --only {}: {} in {}{}\n", name,
                 match.empty() ? "no such shot" : "several shots match", o.database,
                 match.empty() ? "" : " (name it source_shot, as its run directory)");
      return {};
    }
    kept.push_back(*match.front());
  }
  return kept;
}

void print_confusion(const char* who, const Confusion& c) {
  fmt::print("{}: {} of {} outcomes right\n", who, c.right(), c.total());
  fmt::print("                    predicted P   predicted NP\n");
  fmt::print("  observed P        {:>11}   {:>12}\n", c.true_p, c.false_np);
  fmt::print("  observed NP       {:>11}   {:>12}\n", c.false_p, c.true_np);
}

// One line per shot on the console and one row of validate.csv; the two confusion tables.
int report(const std::vector<Shot>& shots, const ValidateOptions& o, Criterion criterion) {
  std::ofstream csv(fs::path(o.out) / "validate.csv");
  csv << "run,source,shot,d_p_mm,v_km_s,observed,srl_d_c_mm,srl_regime,srl,hvi,hvi_D_r_mm,"
         "hvi_spall_mg,right\n";
  fmt::print("\n{:<34} {:>5} {:>5} {:>4} {:>9} {:>4} {:>22} {:>7}\n", "shot", "d_p", "v_p", "exp",
             "SRL d_c", "SRL", "hvi", "D_r");
  fmt::print("{:<34} {:>5} {:>5} {:>4} {:>9} {:>4} {:>22} {:>7}\n", "", "mm", "km/s", "", "mm", "",
             "", "mm");
  Confusion srl, hvi;
  int unmeasured = 0;
  for (const Shot& s : shots) {
    const analysis::CriticalDiameter d = ble(s);
    const bool srl_p = s.d_p >= d.diameter;
    srl.add(s.perforated, srl_p);
    const auto outcome = read_rear_outcome(fs::path(o.out) / s.run_name());
    std::string said = "not measured", D_r;
    if (outcome) {
      const bool p = outcome->perforated(criterion);
      hvi.add(s.perforated, p);
      said = outcome->text(criterion) + (p == s.perforated ? "" : " x");
      if (outcome->hole) D_r = fmt::format("{:.6g}", outcome->D_r / mm);
    } else {
      ++unmeasured;
    }
    fmt::print("{:<34} {:>5.2f} {:>5.2f} {:>4} {:>9.3f} {:>4} {:>22} {:>7}\n", s.run_name(),
               s.d_p / mm, s.v_p / 1e3, s.perforated ? "P" : "NP", d.diameter / mm,
               srl_p ? "P" : "NP", said,
               outcome && outcome->hole ? fmt::format("{:.2f}", outcome->D_r / mm) : "");
    csv << fmt::format("{},{},{},{:g},{:g},{},{:.6g},{},{},{},{},{},{}\n", s.run_name(), s.source,
                       s.id, s.d_p / mm, s.v_p / 1e3, s.perforated ? "P" : "NP", d.diameter / mm,
                       analysis::to_string(d.regime), srl_p ? "P" : "NP",
                       outcome ? (outcome->perforated(criterion) ? "P" : "NP") : "", D_r,
                       outcome ? fmt::format("{:.6g}", outcome->spall_mass * 1e6) : "",
                       outcome ? (outcome->perforated(criterion) == s.perforated ? "1" : "0") : "");
  }
  fmt::print("(x: hvi's outcome differs from the experiment's)\n\n");
  print_confusion("SRL ballistic limit equation", srl);
  print_confusion(fmt::format("hvi (rear sheet failed by: {})", o.criterion).c_str(), hvi);
  if (unmeasured)
    fmt::print("{} shot{} not run or not measured yet\n", unmeasured, unmeasured == 1 ? "" : "s");
  fmt::print("hvi validate: {}\n", (fs::path(o.out) / "validate.csv").string());
  return success;
}

}  // namespace

int run_validate(const ValidateOptions& options, const parallel::Ranks& ranks) {
  ValidateOptions o = options;
  const auto criterion = parse_criterion(o.criterion);
  if (!criterion) {
    fmt::print(stderr, "hvi validate: --criterion {}: expected hole, spall or either\n",
               o.criterion);
    return input_error;
  }
  const fs::path folder = fs::path(o.database).parent_path();
  if (o.template_scene.empty()) o.template_scene = (folder / "shot.toml").string();
  std::vector<Shot> all, shots;
  try {
    all = read_shots(o.database, read_material_names(folder / "material_names.csv"));
  } catch (const std::exception& e) {
    fmt::print(stderr, "hvi validate: {}\n", e.what());
    return input_error;
  }
  shots = select(all, o);
  if (shots.empty()) return input_error;
  Study study;
  study.title =
      fmt::format("{} shot{} of {}", shots.size(), shots.size() == 1 ? "" : "s", o.database);
  study.scene = o.template_scene;
  for (const Shot& s : shots) {
    SweepRun run{s.run_name(), {{"shot", s.id}}, shot_overrides(s)};
    run.overrides.insert(run.overrides.end(), o.overrides.begin(), o.overrides.end());
    study.runs.push_back(std::move(run));
  }
  SweepOptions sweep;
  sweep.study = o.database;
  sweep.out = o.out;
  sweep.threads = o.threads;
  sweep.list = o.list;
  sweep.hvi = o.hvi;
  sweep.quiet_end = true;
  const int code = run_study(study, sweep, ranks);
  if (o.list || !ranks.root()) return code;
  // The table: the shots run now and those earlier calls (other --only) ran into the same DIR.
  std::vector<Shot> table;
  for (const Shot& s : all)
    if (fs::exists(fs::path(o.out) / s.run_name()) ||
        std::any_of(shots.begin(), shots.end(), [&](auto& x) { return x.label == s.label; }))
      table.push_back(s);
  const int reported = report(table, o, *criterion);
  return code != success ? code : reported;
}

}  // namespace hvi::driver
