#pragma once
// A run's holes measured at each snapshot as the run writes it (a [[measure]] of kind "holes" with
// history = true): one row per snapshot in RUN/holes_history.csv, the columns of hvi measure's
// measurements_history.csv, and a line on the console. Whether the holes have settled is then
// known while the run goes, and with only the newest snapshots kept on the disk
// (output.keep_snapshots), which a paper-resolution shot of hours needs.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "cases/run/measure_command.hpp"

namespace hvi::driver {

// Detached spall counts from 2 x 2 x 2 points, the smallest resolved fragment (the experiments' P
// by spall, cases/cli/rear_outcome.hpp).
inline constexpr long default_spall_min_points = 8;

class HoleHistory {
 public:
  // `front`: the holes measure's body (empty: the panel's facesheets). resume_step < 0: a new run,
  // whose file starts empty; otherwise the rows up to that step stay and later ones go.
  HoleHistory(std::filesystem::path run, std::string front, std::int64_t resume_step);
  // Measures the run's newest snapshot and appends its row; throws what measure_run throws.
  const Measurements& add();
  // The last measurement if it is of `step`, else null.
  const Measurements* at_step(std::int64_t step) const;

 private:
  MeasureOptions options_;
  std::optional<Measurements> last_;
};

// One line of a measurement: the front and rear holes (or NP and the bulge) and the debris, in mm
// and mg.
std::string hole_summary(const Measurements& m);

}  // namespace hvi::driver
