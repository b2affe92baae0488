#include "cases/cli/settled_command.hpp"

#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "cases/cli/option_value.hpp"
#include "cases/run/hole_history.hpp"
#include "cases/run/measure_command.hpp"
#include "cases/run/settle.hpp"

namespace hvi::driver {

int SettledCli::execute() const {
  const double w = si_value(window, "time", "--window ");
  if (!(w > 0))
    throw std::invalid_argument(fmt::format("--window '{}': expected a time > 0", window));
  const auto states = read_rear_states(std::filesystem::path(run) / hole_history_file);
  if (states.empty())
    throw std::invalid_argument(fmt::format("{}: its holes history has no rear sheet", run));
  SettleCheck check(w, tolerance);
  const auto& [end, end_step] = states.back();
  constexpr double us = 1e-6;
  for (const auto& [state, step] : states) {
    check.add(state);
    if (!check.settled()) continue;
    fmt::print(
        "{}: settled at t = {:.4g} us, step {} of {} ({:.1f}% of the steps): {}; at the end, "
        "t = {:.4g} us: {}\n",
        run, state.time / us, step, end_step,
        100.0 * static_cast<double>(step) / static_cast<double>(end_step), describe(state),
        end.time / us, describe(end));
    return 0;
  }
  fmt::print("{}: not settled by the end, t = {:.4g} us: {}\n", run, end.time / us, describe(end));
  return 0;
}

std::unique_ptr<SettledCli> add_settled_command(CLI::App& app) {
  auto s = std::make_unique<SettledCli>();
  CLI::App* c = s->command = app.add_subcommand(
      "settled",
      "When a run with a holes history could have stopped once its rear sheet settled "
      "(measure.<holes>.stop_when_settled), replayed on its holes_history.csv");
  c->add_option("run", s->run, "Run directory (hvi run --out)")->required();
  c->add_option("--window", s->window, "stop_when_settled to replay (e.g. \"3 us\")")->required();
  c->add_option("--tolerance", s->tolerance, "settle_tolerance to replay")
      ->check(CLI::Range(1e-6, 0.5))
      ->capture_default_str();
  return s;
}

}  // namespace hvi::driver
