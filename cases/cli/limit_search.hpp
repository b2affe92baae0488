#pragma once
// The search for one ballistic limit: the projectile size (or speed) at which the rear facesheet
// starts to fail. Trials bracket it first, stepping by a factor from a first guess (the ballistic
// limit equation's, usually) until one trial perforates and one does not, then bisect the bracket
// (geometric midpoint) until its width, upper / lower - 1, is within the tolerance. The search is
// deterministic: the same outcomes give the same trials, so a search replayed from its finished
// trials resumes where it stopped. Values are rounded to `quantum` so that trial names are stable.
#include <optional>
#include <string>
#include <vector>

namespace hvi::driver {

struct LimitSearchOptions {
  double start = 0;              // first trial value (> 0)
  double tolerance = 0.05;       // bracket width upper / lower - 1
  double step = 1.5;             // bracketing factor of the second trial
  double growth = 1.0;           // each later factor is the one before to this power (1: constant)
  int max_trials = 16;           // give up after this many trials
  double quantum = 1e-6;         // values rounded to a multiple of this
  bool perforates_above = true;  // larger values perforate (diameter, speed)
};

class LimitSearch {
 public:
  explicit LimitSearch(const LimitSearchOptions& options);

  // The next value to try; nullopt once converged or out of trials.
  std::optional<double> next() const;
  // The outcome of the trial at `value` (the one next() gave).
  void record(double value, bool perforated);

  bool converged() const;
  // The bracket: the largest value that did not perforate and the smallest that did (NaN until
  // there is one of each).
  double stopped() const { return stopped_; }
  double perforated() const { return perforated_; }
  // The limit: the bracket's arithmetic midpoint (NaN without a bracket).
  double limit() const;
  int trials() const { return static_cast<int>(history_.size()); }
  // Every trial so far: its value and whether it perforated.
  const std::vector<std::pair<double, bool>>& history() const { return history_; }
  // "converged", "searching", or why the search gave up.
  std::string status() const;

 private:
  double round(double v) const;
  LimitSearchOptions o_;
  double stopped_, perforated_;
  std::vector<std::pair<double, bool>> history_;
};

}  // namespace hvi::driver
