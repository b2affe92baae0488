#pragma once
// hvi settled RUN --window W [--tolerance TOL]: when a finished run with a holes history could have
// stopped under measure.<holes>.stop_when_settled = W (cases/run/settle.hpp), replayed on its
// holes_history.csv: the time and step, the rear sheet then and at the run's end, and the share of
// the steps a stopped run would have taken. For choosing the window on runs already made.
#include <memory>
#include <string>

namespace CLI {
class App;
}

namespace hvi::driver {

struct SettledCli {
  CLI::App* command = nullptr;
  std::string run, window;
  double tolerance = 0.02;
  // Prints one line; throws std::invalid_argument for a bad option or a run without the history.
  int execute() const;
};

std::unique_ptr<SettledCli> add_settled_command(CLI::App& app);

}  // namespace hvi::driver
