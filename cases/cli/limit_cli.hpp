#pragma once
// The command-line front of hvi validate and hvi ballistic-limit: their options, registered on the
// hvi app.
#include <memory>

#include "cases/cli/ballistic_limit_command.hpp"
#include "cases/cli/validate_command.hpp"

namespace CLI {
class App;
}

namespace hvi::driver {

struct ValidateCli {
  CLI::App* command = nullptr;
  ValidateOptions options;
};

struct BallisticLimitCli {
  CLI::App* command = nullptr;
  BallisticLimitOptions options;
};

std::unique_ptr<ValidateCli> add_validate_command(CLI::App& app);
std::unique_ptr<BallisticLimitCli> add_ballistic_limit_command(CLI::App& app);

}  // namespace hvi::driver
