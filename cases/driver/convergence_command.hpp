#pragma once
// hvi convergence SCENE --levels N --out DIR: what accuracy costs in time. Runs the scene at a
// ladder of resolutions (the grid cell halving level by level, and optionally several particle
// counts per cell) as ordinary `hvi run`s in DIR/<level>/ (so each is inspectable and a finished
// level is not run again), collects each [[measure]] with the wall time, peak memory and particle
// count from their summaries, estimates the observed order of convergence and a Richardson-
// extrapolated value, and writes convergence.csv, convergence.md and error-versus-time plots.
#include <string>
#include <vector>

namespace hvi::driver {

struct ConvergenceOptions {
  std::string scene;
  std::string out;
  int levels = 3;
  std::vector<int> particles_per_cell;  // empty: the scene's own
  int threads = 0;
  std::vector<std::string> overrides;
  std::vector<std::string> references;  // name=value: compare with a known value instead
  std::string hvi;                      // this executable, to run the levels
};

int run_convergence(const ConvergenceOptions& options);

}  // namespace hvi::driver
