#pragma once
// hvi ballistic-limit SCENE --speeds 2,3,4,5,6,7km/s --out DIR: the panel's ballistic-limit curve
// by simulation. For each speed, trials bracket and bisect the projectile diameter (limit_search)
// until the largest diameter the rear facesheet stopped and the smallest that failed it are within
// the tolerance; with --vary velocity, the speed at a fixed diameter. Each trial is an ordinary run
// in DIR/trials/<trial>/ (hvi sweep: resumable, DIR/trials/sweep.csv); the trials of the speeds
// searching run together, one round at a time, so an interrupted search resumes from the trials
// it finished. The rear facesheet fails as rear_outcome.hpp says (--criterion).
//
// The scene's projectile is a sphere body (--projectile, default "projectile"): a trial scales it
// about its leading point, sets its speed along its own direction and ends at the scene's end time
// times v_scene / v. The first trial of the fastest speed is the SRL equation's critical
// diameter (analysis/ballistic_limit_equation.hpp) for the scene's first panel; with
// --start-from neighbour (the default) the speeds are searched --parallel-searches at a time (1),
// fastest first, and each later one starts from its nearest converged neighbour's limit
// (curve_search.hpp); with --start-from srl every speed starts from the SRL equation's, all in
// the first round. The trials do not depend on the ranks' count.
//
// Writes DIR/ballistic_limit.csv (speed, critical diameter, bracket, trials, wall time, status,
// SRL), DIR/trials.csv (every trial and its outcome), DIR/srl.csv (the SRL curve), DIR/
// experiments.csv (the database's shots on this panel) and DIR/ballistic_limit.png.
#include <string>
#include <vector>

#include "cases/parallel/ranks.hpp"

namespace hvi::driver {

struct BallisticLimitOptions {
  std::string scene;
  std::string out;
  std::string speeds;             // "2,3,4.5km/s" or "2 km/s,3 km/s"
  std::string vary = "diameter";  // diameter | velocity
  std::string diameter;           // with --vary velocity: the fixed diameter ("1 mm")
  std::string projectile = "projectile";
  std::string criterion = "either";
  std::string rear_yield;  // for the SRL equation; default: the rear sheet's Johnson-Cook A
  std::string database;    // experiments to plot; default: hcsp_shots.csv beside the scene
  std::string start_from = "neighbour";  // neighbour | srl
  int parallel_searches = 1;             // with neighbour: searches running at once
  double tolerance = 0.05;
  int max_trials = 16;
  int threads = 0;
  std::vector<std::string> overrides;
  std::string hvi;
};

// One rank: the searches run their trials one at a time with the machine's threads.
int run_ballistic_limit(const BallisticLimitOptions& options, const parallel::Ranks& ranks);

// "2,3,4.5km/s", "2 km/s, 3000 m/s": speeds in m/s (a unit on the last applies to those without
// one). Throws std::invalid_argument naming the option.
std::vector<double> parse_speeds(const std::string& text);

}  // namespace hvi::driver
