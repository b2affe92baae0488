#pragma once
// The searches of a ballistic-limit curve, one LimitSearch per speed, and where each one starts.
//
// A search's first trial is its first guess g (the SRL equation's d_c), stepping by 1.5 to a
// bracket, unless another speed's search has converged when it starts. Then it starts from the
// nearest such speed n (nearest in ln v), whose limit d_n tells how far hvi's limit lies from the
// guess there: the first trial is g d_n / g_n, and the bracketing steps are (1 + tol)^1.8 (a
// bracket that one bisection brings within the tolerance), squared after each miss (1.09, 1.19,
// 1.42, 2.02, ... for 5%), so a guess that is far off costs a few trials more, not many.
//
// With `carry`, at most `in_flight` searches run at once (under mpirun a round's trials share the
// ranks), the first from the fastest speed, whose trials end soonest (the end time is
// proportional to 1 / v); later ones start as earlier ones end, the fastest waiting first.
// Without it every search starts from its guess in the first round. Either way the trials of a
// round are decided by the outcomes so far alone, so a curve replayed from its finished trials
// asks for the same ones.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cases/cli/limit_search.hpp"

namespace hvi::driver {

struct CurvePoint {
  double fixed = 0;  // what the search holds fixed: the speed, m/s (or a diameter)
  double guess = 0;  // its first guess of the limit (the SRL equation's)
};

struct CurveOptions {
  LimitSearchOptions search;  // tolerance, step, max_trials, quantum (start: the guess)
  bool carry = true;          // start later searches from a converged neighbour
  int in_flight = 1;          // with carry: searches running at once
};

class CurveSearch {
 public:
  struct Entry {
    Entry(const CurvePoint& p, const LimitSearch& s) : point(p), search(s) {}
    CurvePoint point;
    LimitSearch search;
    bool started = false;
    std::optional<double> started_from;  // the neighbour's fixed value, if carried
    std::string failed;                  // a trial that did not finish
    double wall = 0;                     // seconds of its trials
  };

  CurveSearch(const std::vector<CurvePoint>& points, const CurveOptions& options);

  // The next round: the next trial (entry, value) of every search running, starting searches as
  // the options allow. Empty once every search has converged, given up or failed.
  std::vector<std::pair<std::size_t, double>> round();
  void record(std::size_t entry, double value, bool perforated) {
    entries_[entry].search.record(value, perforated);
  }
  Entry& entry(std::size_t k) { return entries_[k]; }
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  bool running(const Entry& e) const;
  void start(std::size_t k);
  CurveOptions o_;
  std::vector<Entry> entries_;
  std::vector<std::size_t> order_;  // fastest first
};

}  // namespace hvi::driver
