#pragma once
// Runs a scene: writes the resolved scene and the code revision, then steps the solver to the end
// time while writing snapshots, energy.csv and checkpoints; resumes from a checkpoint; reports
// progress, removals, the energy balance and the time per phase.
#include <filesystem>
#include <string>
#include <vector>

#include "cases/driver/scene.hpp"

namespace hvi::driver {

struct RunOptions {
  std::filesystem::path out;
  int threads = 0;          // 0: the OpenMP default
  bool overwrite = false;   // replace a previous run in `out`
  bool resume = false;      // continue the run in `out` from its checkpoint
  std::string command_line; // recorded in run.json
};

// Exit codes of `hvi run`.
enum ExitCode : int { success = 0, input_error = 2, run_failed = 3, interrupted = 130 };

// Runs `scene` (for a resume: the run directory's resolved scene, possibly with overrides).
int run_scene(const scene::Scene& scene, const RunOptions& options);

// Peak resident memory of this process, bytes (VmHWM), or 0 if unknown.
std::size_t peak_memory_bytes();

}  // namespace hvi::driver
