// hvi: hypervelocity impact on honeycomb sandwich panels with the Material Point Method.
//
//   hvi check SCENE [--set key=value]...          validate a scene and show what it will simulate
//   hvi run SCENE --out DIR [--threads N] [--set key=value]... [--overwrite]
//   hvi run --resume DIR [--threads N] [--set key=value]...
//   hvi geometry SCENE --out DIR [--threads N] [--set key=value]...
//                                                  build and sample the bodies; write STL and points
//   hvi keys                                       every scene key (Markdown)
//   hvi measure RUN_DIR [--snapshot N|last] [--axis x0,y0] [--resolution R]...
//                                                  hole sizes, bulge, debris (measurements.json)
//   hvi fit CSV_OR_DIR... --form front|rear|taper  the dimensional-analysis power laws
//   hvi report DIR                                 Markdown report with figures (scripts/report.py)
//   hvi compare RUN_A RUN_B                        two runs' measures and costs side by side
//   hvi sweep STUDY --out DIR [--threads N] [--set key=value]... [--only RUN]...
//                                                  a grid of runs, resumable; DIR/sweep.csv
#include <omp.h>
#include <sys/wait.h>

#include <filesystem>
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cases/driver/analysis_cli.hpp"
#include "cases/driver/build_solver.hpp"
#include "cases/driver/child_run.hpp"
#include "cases/driver/compare_command.hpp"
#include "cases/driver/convergence_command.hpp"
#include "cases/driver/geometry_command.hpp"
#include "cases/driver/hybrid.hpp"
#include "cases/driver/run.hpp"
#include "cases/driver/sweep_command.hpp"
#include "cases/driver/scene.hpp"
#include "cases/driver/scene_schema.hpp"
#include "hvi_git_revision.hpp"

namespace {

using hvi::driver::ExitCode;

void print_errors(const hvi::scene::SceneError& e) {
  for (const auto& d : e.diagnostics()) fmt::print(stderr, "{}\n", d.text());
  fmt::print(stderr, "hvi: {} error{} in the scene; nothing was run or written\n", e.diagnostics().size(),
             e.diagnostics().size() == 1 ? "" : "s");
}

int check(const std::string& path, const std::vector<std::string>& overrides) {
  const hvi::scene::Scene scene = hvi::scene::load_scene(path, overrides);
  auto solver = hvi::driver::make_solver(scene);
  const auto hybrid = hvi::driver::make_hybrid(scene, *solver);
  const auto counts = hvi::driver::add_bodies(scene, *solver);
  solver->initialise();
  if (hybrid) hybrid->record_reference_positions(*solver);
  fmt::print("{}: valid{}\n", path, scene.title.empty() ? "" : " — " + scene.title);
  for (const auto& w : scene.warnings) fmt::print("  warning: {}\n", w);
  const auto& g = scene.grid;
  fmt::print("  grid: {} x {} x {} cells of {:.4g} m from ({:.4g}, {:.4g}, {:.4g}) m; {} shape functions, {}, flip {}, cfl {}\n",
             g.cells[0], g.cells[1], g.cells[2], g.cell_size, g.lower[0], g.lower[1], g.lower[2],
             g.shape_function, g.scheme, g.flip, g.cfl);
  for (const auto& b : scene.boundaries)
    fmt::print("  boundary: {} plane {} = {:.4g} m\n", b.type, "xyz"[b.axis], b.position);
  for (const auto& m : scene.materials)
    fmt::print("  material '{}'{}: {} (density {:.4g} kg/m^3, E {:.4g} Pa, nu {})\n", m.name,
               m.library.empty() ? "" : " (library " + m.library + ")", m.effects(), m.models.density,
               m.models.youngs_modulus, m.models.poisson_ratio);
  if (scene.contact) {
    std::string names;
    for (const auto b : scene.contact->bodies) names += (names.empty() ? "'" : ", '") + scene.bodies[b].name + "'";
    fmt::print("  contact: {} on a velocity field of their own, the other bodies on another; friction {}\n", names,
               scene.contact->friction);
  }
  if (hybrid)
    fmt::print("  far field of panel '{}' outside the MPM zone x in [{:.4g}, {:.4g}], y in [{:.4g}, {:.4g}] m: {}\n",
               scene.panels[scene.far_field->panel].name, scene.far_field->zone[0], scene.far_field->zone[2],
               scene.far_field->zone[1], scene.far_field->zone[3], hybrid->describe());
  double mass = 0;
  for (double m : solver->particles().mass) mass += m;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b)
    fmt::print("  body '{}': {} particles, material '{}'\n", scene.bodies[b].name, counts[b],
               scene.materials[scene.bodies[b].material].name);
  const double dt = solver->next_time_step();
  fmt::print("  {} particles, {:.6g} kg; first time step {:.4g} s, about {:.0f} steps to t = {:.4g} s\n",
             solver->particles().size(), mass, dt, scene.end_time / dt, scene.end_time);
  const auto o = hvi::driver::output_size(*solver, scene, 0.0, true);
  fmt::print("  output: {:.0f} snapshots of about {} and a checkpoint of {}, {} in all (at this particle count)\n",
             o.snapshots, hvi::driver::format_bytes(o.snapshot), hvi::driver::format_bytes(o.checkpoint),
             hvi::driver::format_bytes(o.total));
  return ExitCode::success;
}

// hvi report: scripts/report.py (matplotlib, h5py) with the paper's reference tables of the source tree.
int report(const std::string& dir, bool no_run_figures) {
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string source = HVI_SOURCE_DIR;
  using hvi::driver::shell_quote;
  std::string cmd = python + " " + shell_quote(source + "/scripts/report.py") + " " + shell_quote(dir) + " --reference " +
                    shell_quote(source + "/cases/paper/reference");
  if (no_run_figures) cmd += " --no-run-figures";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? ExitCode::success : ExitCode::input_error;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hvi: hypervelocity impact on honeycomb sandwich panels (Material Point Method)"};
  app.set_version_flag("--version", fmt::format("hvi 0.1.0 ({})", hvi::git_revision));
  app.require_subcommand(1);

  std::string scene_path, out_dir, resume_dir;
  std::vector<std::string> overrides;
  int threads = 0;
  bool overwrite = false;

  auto* check_cmd = app.add_subcommand("check", "Validate a scene and print what it will simulate");
  check_cmd->add_option("scene", scene_path, "Scene file (TOML)")->required();
  check_cmd->add_option("--set", overrides, "Override a scene key: key.path=value (repeatable)");

  auto* run_cmd = app.add_subcommand("run", "Run a scene");
  auto* scene_opt = run_cmd->add_option("scene", scene_path, "Scene file (TOML)");
  auto* out_opt = run_cmd->add_option("--out", out_dir, "Output directory");
  auto* resume_opt = run_cmd->add_option("--resume", resume_dir, "Continue the run in this directory from its checkpoint");
  run_cmd->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(CLI::Range(1, 1024));
  run_cmd->add_option("--set", overrides, "Override a scene key: key.path=value (repeatable)");
  run_cmd->add_flag("--overwrite", overwrite, "Replace a previous run in the output directory");
  scene_opt->excludes(resume_opt);
  out_opt->excludes(resume_opt);

  auto* geometry_cmd = app.add_subcommand(
      "geometry", "Build and sample the bodies; write each as STL and the points as HDF5/XDMF (ParaView)");
  geometry_cmd->add_option("scene", scene_path, "Scene file (TOML)")->required();
  geometry_cmd->add_option("--out", out_dir, "Output directory")->required();
  geometry_cmd->add_option("--threads", threads, "OpenMP threads (default: all cores)")->check(CLI::Range(1, 1024));
  geometry_cmd->add_option("--set", overrides, "Override a scene key: key.path=value (repeatable)");

  auto* keys_cmd = app.add_subcommand("keys", "Print every scene key with its type, unit, range and default (Markdown)");

  hvi::driver::ConvergenceOptions convergence;
  auto* convergence_cmd = app.add_subcommand(
      "convergence", "Run a scene at a ladder of resolutions: each [[measure]] with its error, wall time and memory");
  convergence_cmd->add_option("scene", convergence.scene, "Scene file (TOML)")->required();
  convergence_cmd->add_option("--out", convergence.out, "Output directory (one run per level inside)")->required();
  convergence_cmd->add_option("--levels", convergence.levels, "Number of cell sizes, from the scene's down")
      ->check(CLI::Range(1, 8));
  convergence_cmd->add_option("--ratio", convergence.ratio, "Cell size ratio from one level to the next (2: halving; 1.41421 puts a level between)")
      ->check(CLI::Range(1.05, 4.0));
  convergence_cmd->add_option("--ppc", convergence.particles_per_cell, "Particles per cell per axis to try at each level (e.g. 1 2 3)");
  convergence_cmd->add_option("--reference", convergence.references, "A known value name=value to measure errors against");
  convergence_cmd->add_option("--threads", convergence.threads, "OpenMP threads of each run")->check(CLI::Range(1, 1024));
  convergence_cmd->add_option("--set", convergence.overrides, "Override a scene key: key.path=value (repeatable)");

  hvi::driver::SweepOptions sweep;
  auto* sweep_cmd = app.add_subcommand("sweep", "Run a study (a grid of scenes), resumably; one row per run in DIR/sweep.csv");
  sweep_cmd->add_option("study", sweep.study, "Study file (TOML: scene, [[axis]] levels, [[run]]s)")->required();
  sweep_cmd->add_option("--out", sweep.out, "Output directory (one run per directory inside)")->required();
  sweep_cmd->add_option("--threads", sweep.threads, "OpenMP threads of each run")->check(CLI::Range(1, 1024));
  sweep_cmd->add_option("--set", sweep.overrides, "Override a scene key in every run: key.path=value (repeatable)");
  sweep_cmd->add_option("--only", sweep.only, "Run only these runs (names)");
  sweep_cmd->add_flag("--list", sweep.list, "Print the runs with their overrides and exit");

  std::string report_dir;
  bool report_no_run_figures = false;
  auto* report_cmd = app.add_subcommand(
      "report", "A Markdown report with figures of a study (hvi sweep) or a measured run: tables against the paper's Tables 2 and 5");
  report_cmd->add_option("dir", report_dir, "Study directory (sweep.csv) or run directory (measurements.csv)")->required();
  report_cmd->add_flag("--no-run-figures", report_no_run_figures, "Skip the per-run top views (quicker for large runs)");

  hvi::driver::CompareOptions compare;
  auto* compare_cmd = app.add_subcommand("compare", "Two runs side by side: their measures, cost and energy balance (Markdown)");
  compare_cmd->add_option("run_a", compare.a, "Run directory A")->required();
  compare_cmd->add_option("run_b", compare.b, "Run directory B")->required();

  const auto measure = hvi::driver::add_measure_command(app);
  const auto fit = hvi::driver::add_fit_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : ExitCode::input_error;
  }

  std::string command_line;
  for (int i = 0; i < argc; ++i) command_line += (i ? " " : "") + std::string(argv[i]);

  try {
    if (*keys_cmd) {
      fmt::print("{}", hvi::scene::markdown_reference(hvi::scene::scene_schema()));
      return ExitCode::success;
    }
    if (*check_cmd) return check(scene_path, overrides);
    if (*measure->command) return hvi::driver::measure_command(measure->options());
    if (*fit->command) return hvi::driver::fit_command(fit->options);
    if (*convergence_cmd) {
      convergence.hvi = std::filesystem::canonical("/proc/self/exe").string();
      return hvi::driver::run_convergence(convergence);
    }
    if (*report_cmd) return report(report_dir, report_no_run_figures);
    if (*compare_cmd) return hvi::driver::compare_command(compare);
    if (*sweep_cmd) {
      sweep.hvi = std::filesystem::canonical("/proc/self/exe").string();
      return hvi::driver::run_sweep(sweep);
    }
    if (*geometry_cmd) {
      if (threads > 0) omp_set_num_threads(threads);
      return hvi::driver::geometry_command(hvi::scene::load_scene(scene_path, overrides), out_dir);
    }
    if (*run_cmd) {
      hvi::driver::RunOptions options;
      options.threads = threads;
      options.overwrite = overwrite;
      options.command_line = command_line;
      if (!resume_dir.empty()) {
        options.resume = true;
        options.out = resume_dir;
        scene_path = (options.out / "scene.resolved.toml").string();
      } else {
        if (scene_path.empty() || out_dir.empty()) {
          fmt::print(stderr, "hvi run: give a scene and --out DIR, or --resume DIR\n");
          return ExitCode::input_error;
        }
        options.out = out_dir;
      }
      const hvi::scene::Scene scene = hvi::scene::load_scene(scene_path, overrides);
      return hvi::driver::run_scene(scene, options);
    }
  } catch (const hvi::scene::SceneError& e) {
    print_errors(e);
    return ExitCode::input_error;
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "hvi: {}\n", e.what());
    return ExitCode::input_error;
  } catch (const std::exception& e) {
    fmt::print(stderr, "hvi: {}\n", e.what());
    return ExitCode::run_failed;
  }
  return ExitCode::success;
}
