#pragma once
// hvi compare RUN_A RUN_B: two finished runs side by side (a pure MPM run and its hybrid, two
// resolutions, two versions of hvi): every measure either run has, then the cost (particles,
// far-field nodes, steps, wall time, particle-steps per second, peak memory) and the energy
// balance, with B's difference from A. Read from each run's summary.toml; writes nothing.
#include <filesystem>
#include <string>

namespace hvi::driver {

struct CompareOptions {
  std::filesystem::path a, b;
};

// The table as Markdown. Throws std::invalid_argument when a run has no summary.toml.
std::string compare_runs(const CompareOptions& options);

int compare_command(const CompareOptions& options);

}  // namespace hvi::driver
