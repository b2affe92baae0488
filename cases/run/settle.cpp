#include "cases/run/settle.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "analysis/table.hpp"
#include "cases/run/hole_history.hpp"

namespace hvi::driver {

std::optional<RearState> rear_state(const Measurements& m) {
  if (!m.rear) return std::nullopt;
  RearState s;
  s.time = m.time;
  s.hole = m.rear->hole.perforated;
  s.spall = m.spall && static_cast<long>(m.spall->particles) >= default_spall_min_points;
  if (s.hole) {
    s.D = m.rear->hole.D;
    s.equivalent = m.rear->hole.equivalent_diameter;
  }
  if (m.bulge) s.bulge = m.bulge->displacement;
  for (const auto& [name, value] : m.variables)
    if (name == "t_r") s.thickness = value;
  return s;
}

std::vector<std::pair<RearState, long long>> read_rear_states(
    const std::filesystem::path& history_file) {
  if (!std::filesystem::exists(history_file))
    throw std::invalid_argument(fmt::format("{}: no such file", history_file.string()));
  const analysis::Table t = analysis::read_csv(history_file);
  const int time = t.column("time"), step = t.column("step"), hole = t.column("rear_perforated"),
            D = t.column("D_r"), equivalent = t.column("D_r_equivalent"), bulge = t.column("bulge"),
            spall = t.column("rear_spall_particles");
  const int thickness = t.column("t_r");  // absent or empty: the scene does not give it
  if (time < 0 || step < 0 || hole < 0 || D < 0 || equivalent < 0 || bulge < 0 || spall < 0)
    throw std::invalid_argument(fmt::format(
        "{}: not a holes history (a column of the rear sheet is missing)", history_file.string()));
  auto value = [&](std::size_t row, int column) {
    const double v = t.number(row, column);
    return std::isfinite(v) ? v : 0.0;
  };
  std::vector<std::pair<RearState, long long>> out;
  for (std::size_t r = 0; r < t.rows.size(); ++r) {
    if (t.rows[r][hole].empty()) continue;  // no rear sheet measured in this row
    RearState s;
    s.time = value(r, time);
    s.hole = t.rows[r][hole] == "true";
    s.spall = value(r, spall) >= static_cast<double>(default_spall_min_points);
    s.D = value(r, D);
    s.equivalent = value(r, equivalent);
    s.bulge = value(r, bulge);
    if (thickness >= 0) s.thickness = value(r, thickness);
    out.emplace_back(s, static_cast<long long>(value(r, step)));
  }
  return out;
}

std::string describe(const RearState& s) {
  constexpr double mm = 1e-3;
  if (s.hole)
    return fmt::format("P, D_r {:.3f} mm (equivalent {:.3f} mm){}", s.D / mm, s.equivalent / mm,
                       s.spall ? " with detached spall" : "");
  if (s.spall) return fmt::format("P by detached spall, bulge {:.3f} mm", s.bulge / mm);
  return fmt::format("NP, bulge {:.3f} mm", s.bulge / mm);
}

void SettleCheck::load(const std::filesystem::path& history_file) {
  states_.clear();
  if (!std::filesystem::exists(history_file)) return;
  for (const auto& [state, step] : read_rear_states(history_file)) states_.push_back(state);
}

// b, an earlier state, is the same as the newest, a, to within the tolerance. Spall that comes off
// a sheet with a hole and later leaves the grid changes no outcome: with a hole only the hole
// counts; without one, P by detached spall stays P.
bool SettleCheck::same(const RearState& a, const RearState& b) const {
  auto near = [this](double x, double reference) {
    return std::fabs(x - reference) <= tolerance_ * std::fabs(reference);
  };
  if (a.hole) return b.hole && near(b.D, a.D) && near(b.equivalent, a.equivalent);
  if (b.hole) return false;
  if (a.spall || b.spall) return a.spall && b.spall;
  return near(b.bulge, a.bulge);
}

std::optional<std::string> SettleCheck::settled() const {
  if (states_.empty()) return std::nullopt;
  const RearState& now = states_.back();
  if (!now.reached()) return std::nullopt;
  const double start = now.time - window_ * (1 - 1e-9);  // a snapshot at t - W counts
  bool covered = false;
  for (auto s = states_.rbegin() + 1; s != states_.rend(); ++s) {
    if (!same(now, *s)) return std::nullopt;
    if (s->time <= start) {
      covered = true;
      break;
    }
  }
  if (!covered) return std::nullopt;
  constexpr double us = 1e-6;
  return fmt::format("{}, within {:g}% over the last {:g} us", describe(now), 100 * tolerance_,
                     window_ / us);
}

}  // namespace hvi::driver
