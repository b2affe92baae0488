#include "cases/run/measures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mpm/solver.hpp"
#include "mpm/types.hpp"

namespace hvi::driver {

void track(const mpm::Solver& solver, RunRecord& record) {
  record.peak_pressure = std::max(record.peak_pressure, solver.peak_pressure());
}

namespace {

std::int64_t body_index(const mpm::Solver& solver, const std::string& name) {
  if (name.empty()) return -1;
  const auto& names = solver.body_names();
  return std::find(names.begin(), names.end(), name) - names.begin();
}

bool reads_points(const scene::MeasureSettings& m) {
  return m.kind == "extent_max" || m.kind == "extent_min" || m.kind == "diameter" ||
         m.kind == "field_max" || m.kind == "field_min";
}

// The largest (value, tie) over this rank's points of a measure that reads points.
std::array<double, 2> extremum(const scene::MeasureSettings& m, const mpm::Solver& solver) {
  const auto& P = solver.particles();
  const std::int64_t body = body_index(solver, m.body);
  auto counted = [&](std::size_t p) { return body < 0 || P.body[p] == body; };
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<double, 2> best{-inf, 0.0};
  const auto keep = [&](double value, double tie) {
    if (value > best[0] || (value == best[0] && tie > best[1])) best = {value, tie};
  };
  const double sign = m.kind == "extent_max" || m.kind == "field_max" ? 1.0 : -1.0;
  const auto half_spacing = [&](std::size_t p) { return 0.5 * std::cbrt(P.volume0[p]); };
  if (m.kind == "extent_max" || m.kind == "extent_min") {
    for (std::size_t p = 0; p < P.size(); ++p)
      if (counted(p)) keep(sign * P.position[3 * p + m.axis], half_spacing(p));
  } else if (m.kind == "diameter") {
    for (std::size_t p = 0; p < P.size(); ++p) {
      const double* x = &P.position[3 * p];
      if (!counted(p) || (m.from && x[m.axis] < *m.from) || (m.to && x[m.axis] > *m.to)) continue;
      double r2 = 0.0;
      for (int d = 0; d < 3; ++d)
        if (d != m.axis) r2 += (x[d] - m.center[d]) * (x[d] - m.center[d]);
      keep(std::sqrt(r2), half_spacing(p));
    }
  } else if (P.has_field(m.field)) {  // field_max, field_min
    const auto& f = P.field(m.field);
    for (std::size_t p = 0; p < P.size(); ++p)
      if (counted(p)) keep(sign * f[p], 0.0);
  }
  return best;
}

// The measure from its extremum over every point.
double from_extremum(const scene::MeasureSettings& m, const mpm::Solver& solver, double best,
                     double tie) {
  if (m.kind == "extent_max" || m.kind == "extent_min") {
    const double sign = m.kind == "extent_max" ? 1.0 : -1.0;
    return sign * (best + m.offset + (m.surface ? tie : 0.0));
  }
  if (m.kind == "diameter") return 2.0 * (best + m.offset + (m.surface ? tie : 0.0));
  // field_max, field_min; a model not named: not a number
  if (!solver.particles().has_field(m.field)) return std::numeric_limits<double>::quiet_NaN();
  return (m.kind == "field_max" ? 1.0 : -1.0) * best;
}

double measure(const scene::MeasureSettings& m, const mpm::Solver& solver,
               const RunRecord& record) {
  if (m.kind == "energy_error") return solver.energy().total() / record.initial_energy - 1.0;
  if (m.kind == "peak_pressure") return record.peak_pressure;
  throw std::logic_error("unknown measure kind " + m.kind);
}

}  // namespace

std::vector<double> point_extrema(const std::vector<scene::MeasureSettings>& measures,
                                  const mpm::Solver& solver) {
  std::vector<double> pairs;
  for (const auto& m : measures)
    if (reads_points(m)) {
      const auto best = extremum(m, solver);
      pairs.insert(pairs.end(), best.begin(), best.end());
    }
  return pairs;
}

std::map<std::string, double> evaluate(const std::vector<scene::MeasureSettings>& measures,
                                       const mpm::Solver& solver, const RunRecord& record,
                                       const std::vector<double>& extrema) {
  std::map<std::string, double> values;
  std::size_t k = 0;
  for (const auto& m : measures) {
    // holes: from the snapshot (run.cpp); displacement: from the probes (probes.hpp)
    if (m.kind == "holes" || m.kind == "displacement") continue;
    if (reads_points(m)) {
      values[m.name] = from_extremum(m, solver, extrema.at(k), extrema.at(k + 1));
      k += 2;
    } else {
      values[m.name] = measure(m, solver, record);
    }
  }
  return values;
}

}  // namespace hvi::driver
