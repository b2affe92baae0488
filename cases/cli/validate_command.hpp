#pragma once
// hvi validate DATABASE --out DIR: runs every shot of an experiment database
// (cases/experiments/hcsp_shots.csv) from one scene template (shot.toml beside it) as an ordinary
// study (hvi sweep: DIR/<source>_<shot>/, DIR/sweep.csv, resumable), measures each run's rear
// facesheet, and prints, shot by shot, the experiment's outcome and hole beside the Schaefer-Ryan-
// Lambert ballistic limit equation's prediction and hvi's, then the two confusion tables.
// Writes DIR/validate.csv (one row per shot: those run now and those earlier calls ran into DIR).
//   hvi validate cases/experiments/hcsp_shots.csv --out runs/validate
//   hvi validate cases/experiments/hcsp_shots.csv --out runs/validate --only 1-008 --only B002
#include <string>
#include <vector>

#include "cases/cli/rear_outcome.hpp"
#include "cases/parallel/ranks.hpp"

namespace hvi::driver {

struct ValidateOptions {
  std::string database;
  std::string out;
  std::string template_scene;          // default: shot.toml beside the database
  std::vector<std::string> only;       // shot ids or run names; empty: all
  std::vector<std::string> overrides;  // for every shot, after the shot's own
  int threads = 0;
  bool list = false;
  std::string criterion = "either";  // hole | spall | either
  std::string hvi;                   // this executable
};

int run_validate(const ValidateOptions& options, const parallel::Ranks& ranks);

// The confusion table of predicted against observed outcomes.
struct Confusion {
  int true_p = 0, false_np = 0, false_p = 0, true_np = 0;  // observed P/P, P/NP, NP/P, NP/NP
  void add(bool observed, bool predicted);
  int right() const { return true_p + true_np; }
  int total() const { return true_p + false_np + false_p + true_np; }
};

}  // namespace hvi::driver
