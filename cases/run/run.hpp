#pragma once
// Runs a scene: writes the resolved scene and the code revision, then steps the solver to the end
// time while writing snapshots, energy.csv and checkpoints; resumes from a checkpoint; reports
// progress, removals, the energy balance and the time per phase.
#include <filesystem>
#include <string>
#include <vector>

#include "cases/scene/scene.hpp"
#include "mpm/io/hdf5_file.hpp"
#include "mpm/solver.hpp"

namespace hvi::driver {

struct RunOptions {
  std::filesystem::path out;
  int threads = 0;           // 0: the OpenMP default
  bool overwrite = false;    // replace a previous run in `out`
  bool resume = false;       // continue the run in `out` from its checkpoint
  std::string command_line;  // recorded in run.json
  double max_memory = 0;     // bytes the bodies' points may take; 0: what the machine has free
  // The ranks of an MPI job the run is spread over (mpm/solver_ranks.cpp), or nullptr: one rank.
  // Rank 0 runs the driver; the others step with it.
  mpm::Communicator* ranks = nullptr;
  // How they write each snapshot and checkpoint together, each its own points (nullptr: rank 0
  // gathers every point and writes alone).
  const mpm::io::SharedFileAccess* shared_files = nullptr;
};

// Exit codes of `hvi run`: 128 + the signal for a run stopped by SIGINT (Ctrl-C) or SIGTERM (what a
// batch scheduler sends before its time limit), each after a checkpoint.
enum ExitCode : int {
  success = 0,
  input_error = 2,
  run_failed = 3,
  interrupted = 130,
  terminated = 143
};

// Whether an exit code is that of a run stopped by a signal (and resumable from its checkpoint).
constexpr bool stopped_by_signal(int code) {
  return code == interrupted || code == terminated;
}

// Runs `scene` (for a resume: the run directory's resolved scene, possibly with overrides).
int run_scene(const scene::Scene& scene, const RunOptions& options);

// Peak resident memory of this process, bytes (VmHWM), or 0 if unknown.
std::size_t peak_memory_bytes();

// What the rest of a run writes at the solver's current particle count: the snapshots still due
// (one at each output time from `next_output` before the end, and one at the end) and the
// checkpoint, written aside before it replaces the last one (`fresh`: none on the disk yet, so
// twice). Bytes.
struct OutputSize {
  double snapshots = 0, snapshot = 0, checkpoint = 0, total = 0;
};
OutputSize output_size(const mpm::Solver& solver, const scene::Scene& scene, double next_output,
                       bool fresh);
// "1.95 GB", "340 MB", "12 kB".
std::string format_bytes(double bytes);

}  // namespace hvi::driver
