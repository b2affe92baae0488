#pragma once
// The command-line front of hvi measure and hvi fit: their options, registered on the hvi app and
// turned into MeasureOptions / FitOptions (lengths and angles with units, as in scenes: "0.01 mm",
// "60 deg"; a plain number is SI: m, rad).
#include <memory>
#include <string>

#include "cases/cli/fit_command.hpp"
#include "cases/run/measure_command.hpp"

namespace CLI {
class App;
}

namespace hvi::driver {

struct MeasureCli {
  CLI::App* command = nullptr;
  std::string run, snapshot = "last", axis, resolution, front, rear, core_height, rotation, out;
  std::string front_rule = "two-chords", rear_rule = "six-directions";
  bool no_mirror = false, images = false;
  double gap_closing = 0.375, link_factor = 1.75;
  // Throws std::invalid_argument for a malformed value.
  MeasureOptions options() const;
};

struct FitCli {
  CLI::App* command = nullptr;
  FitOptions options;
};

std::unique_ptr<MeasureCli> add_measure_command(CLI::App& app);
std::unique_ptr<FitCli> add_fit_command(CLI::App& app);

}  // namespace hvi::driver
