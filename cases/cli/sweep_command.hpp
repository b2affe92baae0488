#pragma once
// hvi sweep STUDY.toml --out DIR: runs a grid of scenes (a parameter study, a validation set) as
// ordinary `hvi run`s in DIR/<run>/, measures each (hvi measure), and writes DIR/sweep.csv with one
// row per run: its name, the label of each axis level, its status, wall time, steps, particles,
// peak memory and energy balance, every [[measure]] of its summary and every column of its
// measurements.csv. Resumable: a run whose summary says "finished" is not run again; an
// interrupted one is resumed from its checkpoint.
//
// A study file:
//   title = "..."
//   scene = "panel.toml"              # relative to the study file
//   set = ["resolution=coarse"]       # overrides for every run (the command line's --set add to
//   them)
//   [[axis]]                          # runs: the product of the axes' levels, named label_label...
//   name = "mass"
//   [[axis.level]]
//   label = "m1g"
//   set = ["body.projectile.sphere.radius=4.405 mm", ...]
//   [[run]]                           # and/or runs listed one by one
//   name = "case1"
//   set = [...]
#include <string>
#include <vector>

#include "cases/parallel/ranks.hpp"

namespace hvi::driver {

struct SweepOptions {
  std::string study;
  std::string out;
  int threads = 0;
  std::vector<std::string> overrides;  // for every run, after the study's own
  std::vector<std::string> only;       // run only these (names); empty: all
  bool list = false;                   // print the runs and exit
  std::string hvi;                     // this executable
  int rank = 0, ranks = 1;             // of the MPI job (set by run_sweep)
  // More than 1: each run is an MPI job of its own, started by `launcher` ({ranks} replaced by
  // this count), one at a time, from a sweep that is not itself under an MPI launcher. A run that
  // fails is its job's alone.
  int ranks_per_run = 1;
  std::string launcher = "mpiexec -n {ranks}";
  bool quiet_end = false;    // no closing line pointing at hvi fit and hvi report (for callers)
  bool quiet_start = false;  // no opening line naming the study (for callers)
};

// With several ranks (mpirun -np N hvi sweep ...), rank 0 hands the runs out one at a time to the
// first free rank and writes sweep.csv; each rank runs one run at a time with its threads.
int run_sweep(const SweepOptions& options, const parallel::Ranks& ranks);

// One study's runs, resolved (for tests).
struct SweepRun {
  std::string name;
  std::vector<std::pair<std::string, std::string>> labels;  // axis name, level label
  std::vector<std::string> overrides;                       // the study's, then the run's
};
struct Study {
  std::string title, scene;  // scene: a path relative to the working directory
  std::vector<SweepRun> runs;
};
// Throws scene::SceneError (file:line diagnostics) for a bad study file.
Study load_study(const std::string& path, const std::vector<std::string>& overrides = {});

// run_sweep on a study built in memory (hvi validate, hvi ballistic-limit): options.study only
// names it in messages; options.overrides are not applied again (they belong in the runs').
int run_study(const Study& study, const SweepOptions& options, const parallel::Ranks& ranks);

}  // namespace hvi::driver
