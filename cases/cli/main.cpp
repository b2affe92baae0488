// hvi: hypervelocity impact on honeycomb sandwich panels with the Material Point Method.
//
//   hvi check SCENE [--set key=value]...          validate a scene and show what it will simulate
//   hvi run SCENE --out DIR [--threads N] [--set key=value]... [--overwrite]
//   hvi run --resume DIR [--threads N] [--set key=value]...
//   hvi geometry SCENE --out DIR [--threads N] [--set key=value]...
//                                                  build and sample the bodies; write STL and
//                                                  points
//   hvi keys                                       every scene key (Markdown)
//   hvi measure RUN_DIR [--snapshot N|last] [--axis x0,y0] [--resolution R]...
//                                                  hole sizes, bulge, debris (measurements.json)
//   hvi fit CSV_OR_DIR... --form front|rear|taper  the dimensional-analysis power laws
//   hvi probe RUN_DIR --point X,Y,Z [--axis z]     a displacement history from the snapshots
//   hvi units VALUE... [--expect DIMENSION]        values with units in SI
//   hvi report DIR                                 Markdown report with figures (scripts/report.py)
//   hvi compare RUN_A RUN_B                        two runs' measures and costs side by side
//   hvi sweep STUDY --out DIR [--threads N] [--set key=value]... [--only RUN]...
//                                                  a grid of runs, resumable; DIR/sweep.csv
//   hvi validate DATABASE --out DIR [--only SHOT]...
//                                                  run an experiment database's shots; outcomes
//                                                  beside the SRL equation's and the experiments'
//   hvi ballistic-limit SCENE --speeds 2,4,6km/s --out DIR
//                                                  the critical diameter at each speed by trials
//   mpirun -np N hvi run SCENE --out DIR           one run spread over N ranks
//   mpirun -np N hvi sweep ...                     the runs handed out among N ranks
//   hvi sweep ... --ranks-per-run K [--launcher 'srun -n {ranks}']
//                                                  each run an MPI job of K ranks
#include <omp.h>
#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "cases/cli/analysis_cli.hpp"
#include "cases/cli/child_run.hpp"
#include "cases/cli/compare_command.hpp"
#include "cases/cli/convergence_command.hpp"
#include "cases/cli/geometry_command.hpp"
#include "cases/cli/limit_cli.hpp"
#include "cases/cli/probe_command.hpp"
#include "cases/cli/settled_command.hpp"
#include "cases/cli/sweep_command.hpp"
#include "cases/parallel/mpi_communicator.hpp"
#include "cases/parallel/mpi_file_access.hpp"
#include "cases/parallel/ranks.hpp"
#include "cases/run/build_solver.hpp"
#include "cases/run/hybrid.hpp"
#include "cases/run/run.hpp"
#include "cases/scene/scene.hpp"
#include "cases/scene/scene_schema.hpp"
#include "hvi_git_revision.hpp"

namespace {

using hvi::driver::ExitCode;

void print_errors(const hvi::scene::SceneError& e) {
  for (const auto& d : e.diagnostics()) fmt::print(stderr, "{}\n", d.text());
  fmt::print(stderr, "hvi: {} error{} in the scene; nothing was run or written\n",
             e.diagnostics().size(), e.diagnostics().size() == 1 ? "" : "s");
}

// "16GB", "512 MiB", "2e9": bytes; throws std::invalid_argument naming the option.
double memory_bytes(const std::string& text) {
  if (text.empty()) return 0;
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string unit = text.substr(used);
  unit.erase(0, unit.find_first_not_of(' '));
  static const std::map<std::string, double> units{
      {"", 1},      {"B", 1},       {"kB", 1e3},      {"MB", 1e6},      {"GB", 1e9},
      {"TB", 1e12}, {"KiB", 1024.}, {"MiB", 1 << 20}, {"GiB", 1 << 30}, {"TiB", 1099511627776.}};
  const auto u = units.find(unit);
  if (used == 0 || u == units.end() || !(value > 0) || !std::isfinite(value))
    throw std::invalid_argument(
        fmt::format("--max-memory {}: expected a positive size such as 16GB or 512MiB", text));
  return value * u->second;
}

int check(const std::string& path, const std::vector<std::string>& overrides,
          const std::string& max_memory) {
  const hvi::scene::Scene scene = hvi::scene::load_scene(path, overrides);
  const double memory_limit = memory_bytes(max_memory);
  auto solver = hvi::driver::make_solver(scene);
  const auto hybrid = hvi::driver::make_hybrid(scene, *solver);
  std::vector<std::string> overlaps;
  const auto counts = hvi::driver::add_bodies(scene, *solver, memory_limit, &overlaps);
  solver->initialise();
  if (hybrid) hybrid->record_reference_positions(*solver);
  fmt::print("{}: valid{}\n", path, scene.title.empty() ? "" : " — " + scene.title);
  for (const auto& w : scene.warnings) fmt::print("  warning: {}\n", w);
  for (const auto& w : overlaps) fmt::print("  warning: {}\n", w);
  const auto& g = scene.grid;
  fmt::print(
      "  grid: {} x {} x {} cells of {:.4g} m from ({:.4g}, {:.4g}, {:.4g}) m; {} shape functions, "
      "{}, flip {}, cfl {}\n",
      g.cells[0], g.cells[1], g.cells[2], g.cell_size, g.lower[0], g.lower[1], g.lower[2],
      g.shape_function, g.scheme, g.flip, g.cfl);
  for (const auto& b : scene.boundaries)
    fmt::print("  boundary: {} plane {} = {:.4g} m\n", b.type, "xyz"[b.axis], b.position);
  for (const auto& m : scene.materials)
    fmt::print("  material '{}'{}: {} (density {:.4g} kg/m^3, E {:.4g} Pa, nu {})\n", m.name,
               m.library.empty() ? "" : " (library " + m.library + ")", m.effects(),
               m.models.density, m.models.youngs_modulus, m.models.poisson_ratio);
  if (scene.contact) {
    std::string names;
    for (const auto b : scene.contact->bodies)
      names += (names.empty() ? "'" : ", '") + scene.bodies[b].name + "'";
    fmt::print(
        "  contact: {} on a velocity field of their own, the other bodies on another; friction "
        "{}\n",
        names, scene.contact->friction);
  }
  if (hybrid)
    fmt::print(
        "  far field of panel '{}' outside the MPM zone x in [{:.4g}, {:.4g}], y in [{:.4g}, "
        "{:.4g}] m: {}\n",
        scene.panels[scene.far_field->panel].name, scene.far_field->zone[0],
        scene.far_field->zone[2], scene.far_field->zone[1], scene.far_field->zone[3],
        hybrid->describe());
  double mass = 0;
  for (double m : solver->particles().mass) mass += m;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    fmt::print("  body '{}': {} particles, material '{}'\n", scene.bodies[b].name, counts[b],
               scene.materials[scene.bodies[b].material].name);
  const double dt = solver->next_time_step();
  fmt::print(
      "  {} particles, {:.6g} kg; first time step {:.4g} s, about {:.0f} steps to t = {:.4g} s\n",
      solver->particles().size(), mass, dt, scene.end_time / dt, scene.end_time);
  const auto o = hvi::driver::output_size(*solver, scene, 0.0, true);
  fmt::print(
      "  output: {:.0f} snapshots of about {} and a checkpoint of {}, {} in all (at this particle "
      "count)\n",
      o.snapshots, hvi::driver::format_bytes(o.snapshot), hvi::driver::format_bytes(o.checkpoint),
      hvi::driver::format_bytes(o.total));
  return ExitCode::success;
}

// hvi report: scripts/report.py (matplotlib, h5py) with the paper's reference tables of the source
// tree.
int report(const std::string& dir, bool no_run_figures) {
  const std::string python =
      std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string source = HVI_SOURCE_DIR;
  using hvi::driver::shell_quote;
  std::string cmd = python + " " + shell_quote(source + "/scripts/report.py") + " " +
                    shell_quote(dir) + " --reference " +
                    shell_quote(source + "/cases/paper/reference") + " --hvi " +
                    shell_quote(std::filesystem::canonical("/proc/self/exe").string());
  if (no_run_figures) cmd += " --no-run-figures";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? ExitCode::success : ExitCode::input_error;
}

// What the command line asked for: each subcommand and the options it fills.
struct Commands {
  CLI::App *check = nullptr, *run = nullptr, *geometry = nullptr, *keys = nullptr,
           *convergence_cmd = nullptr, *sweep_cmd = nullptr, *report = nullptr,
           *compare_cmd = nullptr;
  std::string scene_path, out_dir, resume_dir;
  std::vector<std::string> overrides;
  int threads = 0;
  std::string max_memory;  // "16 GB"; empty: the memory the machine has available
  bool overwrite = false;
  hvi::driver::ConvergenceOptions convergence;
  hvi::driver::SweepOptions sweep;
  std::string report_dir;
  bool report_no_run_figures = false;
  hvi::driver::CompareOptions compare;
  std::unique_ptr<hvi::driver::MeasureCli> measure;
  std::unique_ptr<hvi::driver::FitCli> fit;
  std::unique_ptr<hvi::driver::ProbeCli> probe;
  std::unique_ptr<hvi::driver::UnitsCli> units;
  std::unique_ptr<hvi::driver::SettledCli> settled;
  std::unique_ptr<hvi::driver::ValidateCli> validate;
  std::unique_ptr<hvi::driver::BallisticLimitCli> ballistic_limit;
};

// check, run, geometry, keys: the commands of one scene.
void add_scene_commands(CLI::App& app, Commands& c) {
  c.check = app.add_subcommand("check", "Validate a scene and print what it will simulate");
  c.check->add_option("scene", c.scene_path, "Scene file (TOML)")->required();
  c.check->add_option("--set", c.overrides, "Override a scene key: key.path=value (repeatable)");
  c.check->add_option("--max-memory", c.max_memory,
                      "Refuse bodies whose points would need more (e.g. 16GB; default: the "
                      "memory this machine has available)");

  c.run = app.add_subcommand("run", "Run a scene");
  auto* scene_opt = c.run->add_option("scene", c.scene_path, "Scene file (TOML)");
  auto* out_opt = c.run->add_option("--out", c.out_dir, "Output directory");
  auto* resume_opt = c.run->add_option("--resume", c.resume_dir,
                                       "Continue the run in this directory from its checkpoint");
  c.run->add_option("--threads", c.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  c.run->add_option("--set", c.overrides, "Override a scene key: key.path=value (repeatable)");
  c.run->add_option("--max-memory", c.max_memory,
                    "Refuse bodies whose points would need more (e.g. 16GB; default: the memory "
                    "this machine has available)");
  c.run->add_flag("--overwrite", c.overwrite, "Replace a previous run in the output directory");
  scene_opt->excludes(resume_opt);
  out_opt->excludes(resume_opt);

  c.geometry = app.add_subcommand(
      "geometry",
      "Build and sample the bodies; write each as STL and the points as HDF5/XDMF (ParaView)");
  c.geometry->add_option("scene", c.scene_path, "Scene file (TOML)")->required();
  c.geometry->add_option("--out", c.out_dir, "Output directory")->required();
  c.geometry->add_option("--threads", c.threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  c.geometry->add_option("--set", c.overrides, "Override a scene key: key.path=value (repeatable)");

  c.keys = app.add_subcommand(
      "keys", "Print every scene key with its type, unit, range and default (Markdown)");
}

// convergence and sweep: the commands of many runs.
void add_study_commands(CLI::App& app, Commands& c) {
  hvi::driver::ConvergenceOptions& convergence = c.convergence;
  c.convergence_cmd = app.add_subcommand("convergence",
                                         "Run a scene at a ladder of resolutions: each [[measure]] "
                                         "with its error, wall time and memory");
  c.convergence_cmd->add_option("scene", convergence.scene, "Scene file (TOML)")->required();
  c.convergence_cmd
      ->add_option("--out", convergence.out, "Output directory (one run per level inside)")
      ->required();
  c.convergence_cmd
      ->add_option("--levels", convergence.levels, "Number of cell sizes, from the scene's down")
      ->check(CLI::Range(1, 8));
  c.convergence_cmd
      ->add_option(
          "--ratio", convergence.ratio,
          "Cell size ratio from one level to the next (2: halving; 1.41421 puts a level between)")
      ->check(CLI::Range(1.05, 4.0));
  c.convergence_cmd->add_option("--ppc", convergence.particles_per_cell,
                                "Particles per cell per axis to try at each level (e.g. 1 2 3)");
  c.convergence_cmd->add_option("--reference", convergence.references,
                                "A known value name=value to measure errors against");
  c.convergence_cmd->add_option("--threads", convergence.threads, "OpenMP threads of each run")
      ->check(CLI::Range(1, 1024));
  c.convergence_cmd->add_option("--set", convergence.overrides,
                                "Override a scene key: key.path=value (repeatable)");

  hvi::driver::SweepOptions& sweep = c.sweep;
  c.sweep_cmd = app.add_subcommand(
      "sweep", "Run a study (a grid of scenes), resumably; one row per run in DIR/sweep.csv");
  c.sweep_cmd
      ->add_option("study", sweep.study, "Study file (TOML: scene, [[axis]] levels, [[run]]s)")
      ->required();
  c.sweep_cmd->add_option("--out", sweep.out, "Output directory (one run per directory inside)")
      ->required();
  c.sweep_cmd->add_option("--threads", sweep.threads, "OpenMP threads of each run")
      ->check(CLI::Range(1, 1024));
  c.sweep_cmd->add_option("--set", sweep.overrides,
                          "Override a scene key in every run: key.path=value (repeatable)");
  c.sweep_cmd->add_option("--only", sweep.only, "Run only these runs (names)");
  c.sweep_cmd->add_flag("--list", sweep.list, "Print the runs with their overrides and exit");
  c.sweep_cmd
      ->add_option("--ranks-per-run", sweep.ranks_per_run,
                   "Start each run as an MPI job of this many ranks (through --launcher)")
      ->check(CLI::Range(1, 1 << 20));
  c.sweep_cmd->add_option("--launcher", sweep.launcher,
                          "With --ranks-per-run: the command that starts a run's ranks, {ranks} "
                          "replaced by their count (default: mpiexec -n {ranks})");
  c.validate = hvi::driver::add_validate_command(app);
  c.ballistic_limit = hvi::driver::add_ballistic_limit_command(app);
}

// report, compare, measure, fit: the commands that read what runs wrote.
void add_analysis_commands(CLI::App& app, Commands& c) {
  c.report = app.add_subcommand("report",
                                "A Markdown report with figures of a study (hvi sweep) or a "
                                "measured run: tables against the paper's Tables 2 and 5");
  c.report
      ->add_option("dir", c.report_dir,
                   "Study directory (sweep.csv) or run directory (measurements.csv)")
      ->required();
  c.report->add_flag("--no-run-figures", c.report_no_run_figures,
                     "Skip the per-run top views (quicker for large runs)");

  c.compare_cmd = app.add_subcommand(
      "compare", "Two runs side by side: their measures, cost and energy balance (Markdown)");
  c.compare_cmd->add_option("run_a", c.compare.a, "Run directory A")->required();
  c.compare_cmd->add_option("run_b", c.compare.b, "Run directory B")->required();

  c.measure = hvi::driver::add_measure_command(app);
  c.fit = hvi::driver::add_fit_command(app);
  c.probe = hvi::driver::add_probe_command(app);
  c.units = hvi::driver::add_units_command(app);
  c.settled = hvi::driver::add_settled_command(app);
}

// hvi run: a scene, or the run in --resume DIR with its resolved scene; under an MPI launcher,
// spread over its ranks.
int run(Commands& c, const std::string& command_line, const hvi::parallel::Ranks& ranks) {
  const auto communicator = hvi::parallel::make_communicator(ranks);
  const auto shared_files = hvi::parallel::make_file_access(ranks);
  hvi::driver::RunOptions options;
  options.ranks = communicator.get();
  options.shared_files = shared_files.get();
  options.threads = c.threads;
  options.overwrite = c.overwrite;
  options.max_memory = memory_bytes(c.max_memory);
  options.command_line = command_line;
  if (!c.resume_dir.empty()) {
    options.resume = true;
    options.out = c.resume_dir;
    c.scene_path = (options.out / "scene.resolved.toml").string();
  } else {
    if (c.scene_path.empty() || c.out_dir.empty()) {
      fmt::print(stderr, "hvi run: give a scene and --out DIR, or --resume DIR\n");
      return ExitCode::input_error;
    }
    options.out = c.out_dir;
  }
  const hvi::scene::Scene scene = hvi::scene::load_scene(c.scene_path, c.overrides);
  return hvi::driver::run_scene(scene, options);
}

// Under an MPI launcher, the commands but hvi run, sweep, validate and ballistic-limit run on one
// rank: say so before doing anything.
bool refuse_ranks(const Commands& c, const hvi::parallel::Ranks& ranks) {
  if (ranks.size() == 1 || *c.sweep_cmd || *c.run || *c.validate->command ||
      *c.ballistic_limit->command)
    return false;
  if (ranks.root())
    fmt::print(stderr,
               "hvi: started as {} ranks of an MPI job; only `hvi run` (one run spread over the "
               "ranks), `hvi sweep`, `hvi validate` and `hvi ballistic-limit` (one run per rank at "
               "a time) share their work among ranks. "
               "Start this command without mpirun, or with -np 1\n",
               ranks.size());
  return true;
}

int dispatch(Commands& c, const std::string& command_line, const hvi::parallel::Ranks& ranks) {
  if (refuse_ranks(c, ranks)) return ExitCode::input_error;
  if (*c.keys) {
    fmt::print("{}", hvi::scene::markdown_reference(hvi::scene::scene_schema()));
    return ExitCode::success;
  }
  if (*c.check) return check(c.scene_path, c.overrides, c.max_memory);
  if (*c.measure->command) return hvi::driver::measure_command(c.measure->options());
  if (*c.fit->command) return hvi::driver::fit_command(c.fit->options);
  if (*c.probe->command) return c.probe->execute();
  if (*c.units->command) return c.units->execute();
  if (*c.settled->command) return c.settled->execute();
  if (*c.convergence_cmd) {
    c.convergence.hvi = std::filesystem::canonical("/proc/self/exe").string();
    return hvi::driver::run_convergence(c.convergence);
  }
  if (*c.report) return report(c.report_dir, c.report_no_run_figures);
  if (*c.compare_cmd) return hvi::driver::compare_command(c.compare);
  const std::string self = std::filesystem::canonical("/proc/self/exe").string();
  if (*c.sweep_cmd) {
    c.sweep.hvi = self;
    return hvi::driver::run_sweep(c.sweep, ranks);
  }
  if (*c.validate->command) {
    c.validate->options.hvi = self;
    return hvi::driver::run_validate(c.validate->options, ranks);
  }
  if (*c.ballistic_limit->command) {
    c.ballistic_limit->options.hvi = self;
    return hvi::driver::run_ballistic_limit(c.ballistic_limit->options, ranks);
  }
  if (*c.geometry) {
    if (c.threads > 0) omp_set_num_threads(c.threads);
    return hvi::driver::geometry_command(hvi::scene::load_scene(c.scene_path, c.overrides),
                                         c.out_dir);
  }
  if (*c.run) return run(c, command_line, ranks);
  return ExitCode::success;
}

}  // namespace

int main(int argc, char** argv) {
  const hvi::parallel::Ranks ranks(argc, argv);  // one rank unless an MPI launcher started hvi
  CLI::App app{"hvi: hypervelocity impact on honeycomb sandwich panels (Material Point Method)"};
  app.set_version_flag("--version", fmt::format("hvi 0.1.0 ({})", hvi::git_revision));
  app.require_subcommand(1);
  Commands commands;
  add_scene_commands(app, commands);
  add_study_commands(app, commands);
  add_analysis_commands(app, commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = ranks.root() ? app.exit(e) : e.get_exit_code();
    return code == 0 ? 0 : ExitCode::input_error;
  }

  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);

  try {
    return dispatch(commands, command_line, ranks);
  } catch (const hvi::scene::SceneError& e) {
    if (ranks.root()) print_errors(e);  // every rank read the same files and found the same
    return ExitCode::input_error;
  } catch (const std::invalid_argument& e) {
    if (ranks.root()) fmt::print(stderr, "hvi: {}\n", e.what());
    return ExitCode::input_error;
  } catch (const std::exception& e) {
    fmt::print(stderr, "hvi: {}\n", e.what());
    return ExitCode::run_failed;
  }
}
