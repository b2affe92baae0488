#pragma once
// When a shot's outcome can no longer change: a holes measure's `stop_when_settled = W` stops the
// run once the rear facesheet has settled, judged on the holes history (one state per snapshot):
//   P (a through-hole): the hole's diameter D_r and its equivalent diameter stay within
//     `settle_tolerance` (relative) of the newest snapshot's over the last W;
//   P by detached spall alone: spall, and no hole, at every snapshot of the last W;
//   NP: the cloud has reached the sheet (a bulge of a quarter of the sheet's thickness t_r or more,
//     where the scene gives t_r: the wave the walls carry ahead of the cloud bends it microns),
//     and no hole and no spall and a bulge within the same tolerance at every snapshot of the
//     last W: the sheet's deepest point is at rest.
// Spall that comes off a sheet with a hole and later leaves the grid changes nothing. The
// window must be covered: a snapshot at or before t - W is needed, so W should span at least two
// output intervals. A run that stops so is "settled"; its last snapshot is the full run's snapshot
// at that time (the steps before it are the same).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cases/run/measure_command.hpp"

namespace hvi::driver {

struct RearState {
  double time = 0;
  bool hole = false, spall = false;
  double D = 0, equivalent = 0;  // the hole's, m (0 without one)
  double bulge = 0;              // m (0 with a hole)
  double thickness = 0;          // the rear sheet's, t_r, m (0: not known)
  // The cloud has reached the sheet: a hole, spall, or a bulge of t_r / 4 (any bulge if t_r is
  // not known).
  bool reached() const { return hole || spall || (bulge > 0 && bulge >= thickness / 4); }
};

// The rear sheet's state in a measurement; nullopt for a run without a rear sheet.
std::optional<RearState> rear_state(const Measurements& m);
// The rear sheet's states in a run's holes_history.csv, with each row's step; throws
// std::invalid_argument for a file that is not one.
std::vector<std::pair<RearState, long long>> read_rear_states(
    const std::filesystem::path& history_file);
// "P, D_r 4.890 mm (equivalent 4.512 mm)" (and " with detached spall"), "P by detached spall,
// bulge 0.5 mm" or "NP, bulge 0.460 mm".
std::string describe(const RearState& s);

class SettleCheck {
 public:
  SettleCheck(double window, double tolerance) : window_(window), tolerance_(tolerance) {}
  // States in time order.
  void add(const RearState& state) { states_.push_back(state); }
  // The rows of a resumed run's holes_history.csv (those up to its checkpoint).
  void load(const std::filesystem::path& history_file);
  // Why the rear sheet has settled at the newest state ("P: D_r 4.89 mm within 2% since 16 us"),
  // or nullopt while it may still change.
  std::optional<std::string> settled() const;

 private:
  bool same(const RearState& a, const RearState& b) const;
  double window_, tolerance_;
  std::vector<RearState> states_;
};

}  // namespace hvi::driver
