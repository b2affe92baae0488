#include "mpm/phase_timer.hpp"

#include <fmt/format.h>

namespace hvi::mpm {

std::size_t PhaseTimer::index_of(const std::string& name) {
  for (std::size_t i = 0; i < entries_.size(); ++i)
    if (entries_[i].name == name) return i;
  entries_.push_back({name, 0.0, 0});
  return entries_.size() - 1;
}

double PhaseTimer::total() const {
  double t = 0.0;
  for (const auto& e : entries_) t += e.seconds;
  return t;
}

std::string PhaseTimer::table() const {
  const double sum = total();
  std::string out =
      fmt::format("{:<28} {:>10} {:>7} {:>9}\n", "phase", "seconds", "share", "calls");
  for (const auto& e : entries_)
    out += fmt::format("{:<28} {:>10.3f} {:>6.1f}% {:>9}\n", e.name, e.seconds,
                       sum > 0 ? 100.0 * e.seconds / sum : 0.0, e.calls);
  out += fmt::format("{:<28} {:>10.3f}\n", "total", sum);
  return out;
}

}  // namespace hvi::mpm
