#pragma once
// hvi probe: a displacement history read from a run's snapshots at any undeformed point
// (cases/run/probe_history.hpp); hvi units: how hvi reads values with units, in SI (what a scene
// key or a command option gets from "0.5 mm"), for scripts and for checking a unit.
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace hvi::driver {

struct ProbeCli {
  CLI::App* command = nullptr;
  std::string run, point, axis = "z";
  // Prints the history as CSV on standard output, what was read on standard error; throws
  // std::invalid_argument for a malformed option.
  int execute() const;
};

struct UnitsCli {
  CLI::App* command = nullptr;
  std::vector<std::string> values;
  std::string expect;  // a dimension name ("length"), or empty: any
  int execute() const;
};

std::unique_ptr<ProbeCli> add_probe_command(CLI::App& app);
std::unique_ptr<UnitsCli> add_units_command(CLI::App& app);

}  // namespace hvi::driver
