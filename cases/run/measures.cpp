#include "cases/run/measures.hpp"

#include <algorithm>
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

double measure(const scene::MeasureSettings& m, const mpm::Solver& solver,
               const RunRecord& record) {
  const auto& P = solver.particles();
  const std::int64_t body = body_index(solver, m.body);
  auto counted = [&](std::size_t p) { return body < 0 || P.body[p] == body; };
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (m.kind == "energy_error") return solver.energy().total() / record.initial_energy - 1.0;
  if (m.kind == "peak_pressure") return record.peak_pressure;
  if (m.kind == "extent_max" || m.kind == "extent_min") {
    const double sign = m.kind == "extent_max" ? 1.0 : -1.0;
    double best = -inf, half_spacing = 0.0;
    for (std::size_t p = 0; p < P.size(); ++p)
      if (counted(p) && sign * P.position[3 * p + m.axis] > best) {
        best = sign * P.position[3 * p + m.axis];
        half_spacing = 0.5 * std::cbrt(P.volume0[p]);
      }
    return sign * (best + m.offset + (m.surface ? half_spacing : 0.0));
  }
  if (m.kind == "diameter") {
    double r = -inf, half_spacing = 0.0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      const double* x = &P.position[3 * p];
      if (!counted(p) || (m.from && x[m.axis] < *m.from) || (m.to && x[m.axis] > *m.to)) continue;
      double r2 = 0.0;
      for (int d = 0; d < 3; ++d)
        if (d != m.axis) r2 += (x[d] - m.center[d]) * (x[d] - m.center[d]);
      if (std::sqrt(r2) > r) {
        r = std::sqrt(r2);
        half_spacing = 0.5 * std::cbrt(P.volume0[p]);
      }
    }
    return 2.0 * (r + m.offset + (m.surface ? half_spacing : 0.0));
  }
  if (m.kind == "field_max" || m.kind == "field_min") {
    if (!P.has_field(m.field)) return std::numeric_limits<double>::quiet_NaN();  // model not named
    const auto& f = P.field(m.field);
    const double sign = m.kind == "field_max" ? 1.0 : -1.0;
    double best = -inf;
    for (std::size_t p = 0; p < P.size(); ++p)
      if (counted(p)) best = std::max(best, sign * f[p]);
    return sign * best;
  }
  throw std::logic_error("unknown measure kind " + m.kind);
}

}  // namespace

std::map<std::string, double> evaluate(const std::vector<scene::MeasureSettings>& measures,
                                       const mpm::Solver& solver, const RunRecord& record) {
  std::map<std::string, double> values;
  for (const auto& m : measures)
    // holes: from the snapshot (run.cpp); displacement: from the probes (probes.hpp)
    if (m.kind != "holes" && m.kind != "displacement") values[m.name] = measure(m, solver, record);
  return values;
}

}  // namespace hvi::driver
