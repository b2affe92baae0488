#include "cases/cli/compare_command.hpp"

#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "cases/run/run.hpp"

namespace hvi::driver {

namespace {

toml::table read_summary(const std::filesystem::path& run) {
  const auto file = run / "summary.toml";
  if (!std::filesystem::exists(file))
    throw std::invalid_argument(
        fmt::format("{} holds no summary.toml: not a finished hvi run", run.string()));
  try {
    return toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    throw std::invalid_argument(fmt::format("{}: {}", file.string(), e.description()));
  }
}

std::optional<double> number(const toml::table& t, const std::string& path) {
  return t.at_path(path).value<double>();
}

std::string cell(std::optional<double> v) {
  if (!v) return "—";
  if (std::isnan(*v)) return "nan";
  return fmt::format("{:.6g}", *v);
}

// B relative to A, in percent; only where both are numbers and A is not zero.
std::string difference(std::optional<double> a, std::optional<double> b) {
  if (!a || !b || !std::isfinite(*a) || !std::isfinite(*b) || *a == 0.0) return "";
  return fmt::format("{:+.2f}%", 100.0 * (*b - *a) / std::abs(*a));
}

}  // namespace

std::string compare_runs(const CompareOptions& options) {
  const toml::table a = read_summary(options.a), b = read_summary(options.b);
  std::string out = fmt::format("| quantity | A: {} | B: {} | B - A |\n|---|---|---|---|\n",
                                options.a.string(), options.b.string());
  // A value marked as a bound (a hole reaching its sheet's edge) shows as "≥ v", and so does the
  // difference it enters.
  auto row = [&](const std::string& name, std::optional<double> x, std::optional<double> y,
                 bool x_bound = false, bool y_bound = false) {
    std::string d = difference(x, y);
    if (!d.empty() && (x_bound || y_bound))
      d += x_bound && y_bound ? " (both lower bounds)"
           : x_bound          ? " (A a lower bound)"
                              : " (B a lower bound)";
    out += fmt::format("| {} | {}{} | {}{} | {} |\n", name, x_bound && x ? "≥ " : "", cell(x),
                       y_bound && y ? "≥ " : "", cell(y), d);
  };
  out += fmt::format("| status | {} | {} | |\n", a["status"].value_or(std::string("?")),
                     b["status"].value_or(std::string("?")));
  std::set<std::string> measures;
  for (const auto* t : {&a, &b})
    if (const auto* m = (*t)["measures"].as_table())
      for (const auto& [key, value] : *m) measures.insert(std::string(key.str()));
  // D_f and D_r are lower bounds where the run's front_hole_open / rear_hole_open is 1.
  auto open = [](const toml::table& t, const std::string& m) {
    const auto flag = m == "D_f"   ? "measures.front_hole_open"
                      : m == "D_r" ? "measures.rear_hole_open"
                                   : "";
    return *flag && number(t, flag).value_or(0.0) == 1.0;
  };
  for (const auto& m : measures)
    row(m, number(a, "measures." + m), number(b, "measures." + m), open(a, m), open(b, m));
  row("time (s)", number(a, "time"), number(b, "time"));
  row("particles", number(a, "particles"), number(b, "particles"));
  row("far-field nodes", number(a, "far_field_nodes"), number(b, "far_field_nodes"));
  // Rows of keys only some runs have, shown where one of the two has them.
  auto row_if_any = [&](const std::string& name, const std::string& key, double scale = 1.0) {
    auto x = number(a, key), y = number(b, key);
    if (!x && !y) return;
    if (x) *x *= scale;
    if (y) *y *= scale;
    row(name, x, y);
  };
  // A growing zone that the damage held at its limit: the far field holds damage there.
  row_if_any("steps the damage held the MPM zone at its limit", "mpm_zone_limit_reached_steps");
  row("steps", number(a, "steps"), number(b, "steps"));
  row("threads", number(a, "threads"), number(b, "threads"));
  // A resumed run's cost is all its invocations (wall_seconds_total), where its checkpoints
  // recorded them.
  auto wall = [&](const toml::table& t) {
    const auto total = number(t, "wall_seconds_total");
    return total ? total : number(t, "wall_seconds");
  };
  row("wall time (s)", wall(a), wall(b));
  row("particle-steps/s", number(a, "particle_steps_per_second"),
      number(b, "particle_steps_per_second"));
  auto mb = [](std::optional<double> bytes) {
    return bytes ? std::optional<double>(*bytes / 1e6) : std::nullopt;
  };
  row("peak memory (MB)", mb(number(a, "peak_memory_bytes")), mb(number(b, "peak_memory_bytes")));
  row_if_any("peak memory with the hole measurement (MB)", "peak_memory_with_measure_bytes", 1e-6);
  row("energy balance", number(a, "energy_balance"), number(b, "energy_balance"));
  return out;
}

int compare_command(const CompareOptions& options) {
  fmt::print("{}", compare_runs(options));
  return ExitCode::success;
}

}  // namespace hvi::driver
