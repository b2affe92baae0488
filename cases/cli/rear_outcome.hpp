#pragma once
// Did the rear facesheet fail? The test the experiments apply (cases/experiments/README.md): the
// rear facesheet is perforated (P) when it has a through-opening at the impact point (the hole
// measurement, analysis/hole.hpp) or when material has come off its back face (detached spall:
// intact rear-sheet points outside the attached sheet, more than one point spacing behind the back
// face, at least `spall_min_points` of them). Read from a run's measurements.csv (hvi measure).
#include <filesystem>
#include <optional>
#include <string>

#include "cases/run/hole_history.hpp"  // default_spall_min_points

namespace hvi::driver {

enum class Criterion { hole, spall, either };
// "hole", "spall", "either"; nullopt for anything else.
std::optional<Criterion> parse_criterion(const std::string& text);

struct RearOutcome {
  bool hole = false;   // a through-opening
  bool spall = false;  // detached spall
  double D_r = 0;      // m (0 without a hole)
  double spall_mass = 0;
  long spall_points = 0;
  bool perforated(Criterion c) const {
    return c == Criterion::hole ? hole : c == Criterion::spall ? spall : hole || spall;
  }
  // "P (hole)", "P (spall)", "P (hole and spall)" or "NP", under criterion c.
  std::string text(Criterion c) const;
};

// nullopt when the run has no measurements.csv or it lacks the rear sheet's columns.
std::optional<RearOutcome> read_rear_outcome(const std::filesystem::path& run_dir,
                                             long spall_min_points = default_spall_min_points);

}  // namespace hvi::driver
