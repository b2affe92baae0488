#include "cases/cli/limit_search.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace hvi::driver {

LimitSearch::LimitSearch(const LimitSearchOptions& options)
    : o_(options),
      stopped_(std::numeric_limits<double>::quiet_NaN()),
      perforated_(std::numeric_limits<double>::quiet_NaN()) {}

double LimitSearch::round(double v) const {
  return std::max(1.0, std::round(v / o_.quantum)) * o_.quantum;
}

bool LimitSearch::converged() const {
  if (std::isnan(stopped_) || std::isnan(perforated_)) return false;
  const double lo = std::min(stopped_, perforated_), hi = std::max(stopped_, perforated_);
  // Within the tolerance, or as close as the rounding allows.
  return hi / lo - 1 <= o_.tolerance || hi - lo <= 1.5 * o_.quantum;
}

double LimitSearch::limit() const {
  if (std::isnan(stopped_) || std::isnan(perforated_))
    return std::numeric_limits<double>::quiet_NaN();
  return 0.5 * (stopped_ + perforated_);
}

std::optional<double> LimitSearch::next() const {
  if (converged() || trials() >= o_.max_trials) return std::nullopt;
  if (history_.empty()) return round(o_.start);
  const bool have_p = !std::isnan(perforated_), have_np = !std::isnan(stopped_);
  if (have_p && have_np) return round(std::sqrt(stopped_ * perforated_));
  // Bracketing: move away from the outcome seen, toward the other, by step^(growth^(n - 1)) after
  // n trials of the one outcome.
  const bool up = have_np == o_.perforates_above;
  const double from = have_np ? stopped_ : perforated_;
  const double factor = std::pow(o_.step, std::pow(o_.growth, trials() - 1));
  return round(up ? from * factor : from / factor);
}

void LimitSearch::record(double value, bool perforated) {
  history_.emplace_back(value, perforated);
  // Larger values perforate (or smaller, with perforates_above false): keep the tightest of each.
  const bool above = o_.perforates_above;
  if (perforated) {
    if (std::isnan(perforated_) || (above ? value < perforated_ : value > perforated_))
      perforated_ = value;
  } else if (std::isnan(stopped_) || (above ? value > stopped_ : value < stopped_)) {
    stopped_ = value;
  }
}

std::string LimitSearch::status() const {
  if (converged()) return "converged";
  if (trials() < o_.max_trials) return "searching";
  return fmt::format(
      "no {} after {} trials",
      std::isnan(stopped_) || std::isnan(perforated_) ? "bracket" : "converged bracket", trials());
}

}  // namespace hvi::driver
