#include "cases/cli/curve_search.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace hvi::driver {

CurveSearch::CurveSearch(const std::vector<CurvePoint>& points, const CurveOptions& options)
    : o_(options), order_(points.size()) {
  for (const CurvePoint& p : points) {
    LimitSearchOptions s = o_.search;
    s.start = p.guess;
    entries_.emplace_back(p, LimitSearch(s));
  }
  std::iota(order_.begin(), order_.end(), std::size_t{0});
  std::stable_sort(order_.begin(), order_.end(),
                   [&](std::size_t a, std::size_t b) { return points[a].fixed > points[b].fixed; });
}

bool CurveSearch::running(const Entry& e) const {
  return e.started && e.failed.empty() && e.search.next().has_value();
}

// From the nearest converged neighbour, if there is one: first trial g d_n / g_n, steps
// (1 + tol)^1.8 growing by squares.
void CurveSearch::start(std::size_t k) {
  Entry& e = entries_[k];
  e.started = true;
  if (!o_.carry) return;
  const Entry* nearest = nullptr;
  double distance = 0;
  for (const Entry& n : entries_) {
    if (&n == &e || !n.search.converged()) continue;
    const double d = std::fabs(std::log(n.point.fixed / e.point.fixed));
    if (!nearest || d < distance) nearest = &n, distance = d;
  }
  if (!nearest) return;
  LimitSearchOptions s = o_.search;
  s.start = e.point.guess * nearest->search.limit() / nearest->point.guess;
  s.step = std::pow(1.0 + s.tolerance, 1.8);
  s.growth = 2.0;
  e.search = LimitSearch(s);
  e.started_from = nearest->point.fixed;
}

std::vector<std::pair<std::size_t, double>> CurveSearch::round() {
  if (!o_.carry)
    for (Entry& e : entries_) e.started = true;
  const auto count = [&] {
    return std::count_if(entries_.begin(), entries_.end(),
                         [&](const Entry& e) { return running(e); });
  };
  for (const std::size_t k : order_)
    if (!entries_[k].started && count() < std::max(o_.in_flight, 1)) start(k);
  std::vector<std::pair<std::size_t, double>> trials;
  for (std::size_t k = 0; k < entries_.size(); ++k)
    if (running(entries_[k])) trials.emplace_back(k, *entries_[k].search.next());
  return trials;
}

}  // namespace hvi::driver
