#pragma once
// hvi convergence SCENE --levels N --out DIR: what accuracy costs in time. Runs the scene at a
// ladder of resolutions (the grid cell divided by `ratio` level by level, 2 unless asked, and
// optionally several particle
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
  double ratio = 2.0;                   // cell size of level k: the scene's / ratio^k
  std::vector<int> particles_per_cell;  // empty: the scene's own
  int threads = 0;
  std::vector<std::string> overrides;
  std::vector<std::string> references;  // name=value: compare with a known value instead
  std::string hvi;                      // this executable, to run the levels
};

int run_convergence(const ConvergenceOptions& options);

// Observed order and Richardson extrapolation from three levels q0, q1, q2 whose cell sizes
// shrink by `ratio` from one to the next (Roache, Verification and Validation in Computational
// Science and Engineering, ch. 5): with q(h) = q* + C h^p,
//   p = ln(|q1 - q0| / |q2 - q1|) / ln(ratio),  q* = q2 + (q2 - q1) / (ratio^p - 1).
// NaN when the three do not converge monotonically (a difference zero or changing sign).
struct Extrapolation {
  double order;
  double value;
};
Extrapolation richardson(double q0, double q1, double q2, double ratio);

}  // namespace hvi::driver
