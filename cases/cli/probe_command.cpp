#include "cases/cli/probe_command.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "cases/cli/option_value.hpp"
#include "cases/run/probe_history.hpp"
#include "cases/scene/units.hpp"

namespace hvi::driver {

int ProbeCli::execute() const {
  std::array<double, 3> x{};
  std::size_t from = 0;
  for (int d = 0; d < 3; ++d) {
    const std::size_t comma = point.find(',', from);
    if ((d < 2) == (comma == std::string::npos))
      throw std::invalid_argument(fmt::format(
          "--point '{}': expected three lengths X,Y,Z (e.g. \"0 mm,20 mm,-15.2 mm\")", point));
    x[d] = si_value(point.substr(from, comma - from), "length", "--point ");
    from = comma + 1;
  }
  const int component = static_cast<int>(axis[0] - 'x');
  const ProbeReading r = read_probe(run, x, component);
  fmt::print("time_s,displacement_{}_m\n", axis);
  const std::array<double, 2>* peak = nullptr;
  for (const auto& row : r.rows) {
    fmt::print("{:.17g},{:.17g}\n", row[0], row[1]);
    if (std::isfinite(row[1]) && (!peak || std::abs(row[1]) > std::abs((*peak)[1]))) peak = &row;
  }
  fmt::print(stderr, "read {}", r.source);
  if (peak) fmt::print(stderr, "; largest |u| {:.6g} m at {:.6g} s", (*peak)[1], (*peak)[0]);
  fmt::print(stderr, "\n");
  return 0;
}

int UnitsCli::execute() const {
  for (const std::string& v : values) fmt::print("{:.17g}\n", si_value(v, expect, ""));
  return 0;
}

std::unique_ptr<ProbeCli> add_probe_command(CLI::App& app) {
  auto p = std::make_unique<ProbeCli>();
  CLI::App* c = p->command = app.add_subcommand(
      "probe",
      "A displacement history read from a run's snapshots at an undeformed point, as a "
      "[[measure]] of kind \"displacement\" reads it (CSV)");
  c->add_option("run", p->run, "Run directory (hvi run --out)")->required();
  c->add_option("--point", p->point, "Undeformed position X,Y,Z (e.g. \"0 mm,20 mm,-15.2 mm\")")
      ->required();
  c->add_option("--axis", p->axis, "Displacement component")
      ->check(CLI::IsMember({"x", "y", "z"}))
      ->capture_default_str();
  return p;
}

std::unique_ptr<UnitsCli> add_units_command(CLI::App& app) {
  auto u = std::make_unique<UnitsCli>();
  CLI::App* c = u->command = app.add_subcommand(
      "units",
      "Values with units (\"0.5 mm\", \"4.5 km/s\") in SI, one per line, as hvi reads them");
  c->add_option("values", u->values, "Values, each a number and a unit")->required();
  c->add_option("--expect", u->expect,
                "Refuse a value of another dimension (length, velocity, time, pressure, ...; a "
                "plain number passes as SI)");
  return u;
}

}  // namespace hvi::driver
