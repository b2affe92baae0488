#include "cases/cli/rear_outcome.hpp"

#include <cmath>

#include "analysis/table.hpp"

namespace hvi::driver {

std::optional<Criterion> parse_criterion(const std::string& text) {
  if (text == "hole") return Criterion::hole;
  if (text == "spall") return Criterion::spall;
  if (text == "either") return Criterion::either;
  return std::nullopt;
}

std::string RearOutcome::text(Criterion c) const {
  if (!perforated(c)) return "NP";
  const bool h = hole && c != Criterion::spall, s = spall && c != Criterion::hole;
  return h && s ? "P (hole and spall)" : h ? "P (hole)" : "P (spall)";
}

std::optional<RearOutcome> read_rear_outcome(const std::filesystem::path& run_dir,
                                             long spall_min_points) {
  const std::filesystem::path file = run_dir / "measurements.csv";
  if (!std::filesystem::exists(file)) return std::nullopt;
  const analysis::Table t = analysis::read_csv(file);
  const int perforated = t.column("rear_perforated"), D = t.column("D_r"),
            mass = t.column("rear_spall_mass"), points = t.column("rear_spall_particles");
  if (t.rows.empty() || perforated < 0 || points < 0) return std::nullopt;
  RearOutcome o;
  o.hole = t.number(0, perforated) == 1;
  const double d = D >= 0 ? t.number(0, D) : NAN;
  o.D_r = o.hole && std::isfinite(d) ? d : 0;
  const double n = t.number(0, points);
  o.spall_points = std::isfinite(n) ? static_cast<long>(n) : 0;
  o.spall_mass = mass >= 0 && std::isfinite(t.number(0, mass)) ? t.number(0, mass) : 0;
  o.spall = o.spall_points >= spall_min_points;
  return o;
}

}  // namespace hvi::driver
