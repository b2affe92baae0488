#include "cases/driver/run.hpp"

#include <malloc.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "cases/driver/build_solver.hpp"
#include "cases/driver/hybrid.hpp"
#include "cases/driver/probes.hpp"
#include "cases/driver/hole_history.hpp"
#include "cases/driver/measure_command.hpp"
#include "cases/driver/measures.hpp"
#include "hvi_git_revision.hpp"
#include "mpm/io/checkpoint.hpp"
#include "mpm/io/energy_log.hpp"
#include "mpm/io/snapshot_writer.hpp"
#include "mpm/materials/hydro_material.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

namespace {

// The signal (SIGINT or SIGTERM) that asked the run to stop at the end of its step; 0: none.
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int number) { stop_signal = number; }

// Snapshot/checkpoint times: multiples of an interval; due once the run has reached them.
struct Schedule {
  double interval, next;
  bool due(double t) const { return t >= next - 1e-9 * interval; }
  void advance(double t) { next = (std::floor(t / interval + 1e-9) + 1.0) * interval; }
};

// What the rest of a run writes (output_size), against the space left on its output's disk. A
// warning, not an error: snapshots may be deleted as the run goes.
void report_disk(const fs::path& dir, const mpm::Solver& s, const scene::Scene& scene, double next_output, bool fresh) {
  const OutputSize o = output_size(s, scene, next_output, fresh);
  std::error_code error;
  const auto space = fs::space(dir, error);
  fmt::print("  output: {:.0f} snapshot{} of about {} and a checkpoint of {} to come, {} in all{}\n", o.snapshots,
             o.snapshots == 1.0 ? "" : "s", format_bytes(o.snapshot), format_bytes(o.checkpoint), format_bytes(o.total),
             error ? std::string() : fmt::format("; {} free on the disk", format_bytes(static_cast<double>(space.available))));
  if (!error && o.total > static_cast<double>(space.available))
    fmt::print("  warning: the output needs about {} and {}'s disk has {} free: the run will stop when the disk is "
               "full (its last checkpoint kept, to resume from); free space, keep only the newest snapshots "
               "(output.keep_snapshots), or raise output.interval\n",
               format_bytes(o.total), dir.string(), format_bytes(static_cast<double>(space.available)));
}

std::string format_duration(double seconds) {
  const auto s = static_cast<long>(seconds);
  return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}

// Progress: on a terminal one line rewritten in place; otherwise (a batch job's log) one line per
// snapshot written.
class Progress {
 public:
  explicit Progress(double end_time) : end_time_(end_time), tty_(isatty(STDERR_FILENO)) {}
  void update(const mpm::Solver& s, bool force = false) {
    if (!tty_) return;
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - last_ < std::chrono::milliseconds(500)) return;
    fmt::print(stderr, "\r{}   ", line(s, now));
    std::fflush(stderr);
    last_ = now;
    active_ = true;
  }
  void snapshot_written(const mpm::Solver& s) {
    if (tty_) return;
    const auto now = std::chrono::steady_clock::now();
    fmt::print("{}  (wall {})\n", line(s, now), format_duration(std::chrono::duration<double>(now - start_).count()));
    std::fflush(stdout);
  }
  void start(const mpm::Solver& s) {
    first_step_ = s.step_count();
    first_time_ = s.time();
  }
  void finish() {
    if (active_) fmt::print(stderr, "\n");
    active_ = false;
  }

 private:
  std::string line(const mpm::Solver& s, std::chrono::steady_clock::time_point now) const {
    const double wall = std::chrono::duration<double>(now - start_).count();
    const double steps_per_s = (s.step_count() - first_step_) / std::max(wall, 1e-9);
    const double sim_rate = (s.time() - first_time_) / std::max(wall, 1e-9);
    const double eta = sim_rate > 0 ? (end_time_ - s.time()) / sim_rate : 0.0;
    const std::string rate = steps_per_s >= 100 ? fmt::format("{:.0f}", steps_per_s) : fmt::format("{:.3g}", steps_per_s);
    return fmt::format("  t = {:.4g} / {:.4g} s  step {}  dt {:.3g} s  {} steps/s  ETA {}", s.time(), end_time_,
                       s.step_count(), s.next_time_step(), rate, format_duration(eta));
  }
  double end_time_;
  bool tty_, active_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
  std::int64_t first_step_ = 0;
  double first_time_ = 0.0;
};

void report_removals(const mpm::Solver& solver, std::vector<mpm::RemovalEvent> events, std::int64_t& reported) {
  constexpr std::int64_t detailed = 5;
  for (const auto& e : events) {
    if (reported < detailed)
      fmt::print("  step {}, t = {:.6g} s: particle {} (body '{}', material '{}') left the grid at "
                 "({:.4g}, {:.4g}, {:.4g}) m; removed with mass {:.4g} kg, kinetic energy {:.4g} J\n",
                 e.step, e.time, e.id, solver.body_names().at(e.body), solver.materials().at(e.material)->name(),
                 e.position[0], e.position[1], e.position[2], e.mass,
                 0.5 * e.mass * (e.velocity[0] * e.velocity[0] + e.velocity[1] * e.velocity[1] + e.velocity[2] * e.velocity[2]));
    else if (reported == detailed)
      fmt::print("  (further removals are counted in energy.csv and the summary)\n");
    ++reported;
  }
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

// run.json: what made the run, and the names behind the snapshots' integer `body` and `material`
// fields (index k is bodies[k], materials[k]).
void write_run_info(const fs::path& dir, const RunOptions& options, int threads, const scene::Scene& scene,
                    const std::vector<std::string>& body_names) {
  toml::array bodies, materials;
  for (const auto& b : body_names) bodies.push_back(b);
  for (const auto& m : scene.materials) materials.push_back(m.name);
  toml::table info{{"hvi_version", "0.1.0"},
                   {"git_revision", hvi::git_revision},
                   {"command", options.command_line},
                   {"threads", threads},
                   {"bodies", bodies},
                   {"materials", materials}};
  std::ofstream out(dir / "run.json");
  out << toml::json_formatter(info) << '\n';
}

// resumes.jsonl: one line per resume, appended, so a run resumed or run on several times (perhaps
// by other builds) keeps what made each part: revision, command, threads, and the step and time
// it continued from.
void append_resume_record(const fs::path& dir, const RunOptions& options, int threads, std::int64_t step, double time) {
  const toml::table info{{"git_revision", hvi::git_revision},
                         {"command", options.command_line},
                         {"threads", threads},
                         {"step", step},
                         {"time", time}};
  std::ostringstream json;
  json << toml::json_formatter(info);
  // One line: the formatter's line breaks and indents lie between tokens (a newline inside a
  // string is written as \n), so dropping them leaves the same JSON.
  std::string line;
  bool indent = false;
  for (const char c : json.str()) {
    if (c == '\n') {
      indent = true;
      continue;
    }
    if (indent && c == ' ') continue;
    indent = false;
    line.push_back(c);
  }
  std::ofstream(dir / "resumes.jsonl", std::ios::app) << line << '\n';
}

// The zone's sides (x0, y0, x1, y1) that `sides` names, as "x = 28 mm, y = 28 mm".
std::string side_names(const std::array<bool, 4>& sides, const std::array<double, 4>& zone) {
  std::string names;
  for (int side = 0; side < 4; ++side)
    if (sides[side]) names += fmt::format("{}{} = {:.4g} mm", names.empty() ? "" : ", ", side % 2 ? 'y' : 'x', 1e3 * zone[side]);
  return names;
}

void write_timing(const fs::path& dir, const mpm::PhaseTimer& timer) {
  std::ofstream out(dir / "timing.csv");
  out << "phase,seconds,calls\n";
  for (const auto& e : timer.entries()) out << fmt::format("\"{}\",{:.6f},{}\n", e.name, e.seconds, e.calls);
}

}  // namespace

std::string format_bytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.3g} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.3g} MB", bytes / 1e6);
  return fmt::format("{:.3g} kB", bytes / 1e3);
}

OutputSize output_size(const mpm::Solver& s, const scene::Scene& scene, double next_output, bool fresh) {
  OutputSize o;
  const double end = scene.end_time;
  o.snapshots = 1.0;  // the last step's
  if (next_output < end * (1 - 1e-12)) o.snapshots += std::ceil((end - next_output) / scene.output_interval - 1e-9);
  // Keeping only the newest N, at most N + 1 besides the first are on the disk at once (the newest is
  // written before the oldest goes); the count from t = 0 (next_output 0) includes the first.
  if (scene.keep_snapshots > 0)
    o.snapshots = std::min(o.snapshots, static_cast<double>(scene.keep_snapshots) + (next_output > 0 ? 1 : 2));
  o.snapshot = static_cast<double>(mpm::io::snapshot_bytes_per_particle(s.particles()) * s.particles().size());
  o.checkpoint = static_cast<double>(mpm::io::checkpoint_bytes(s));
  o.total = o.snapshots * o.snapshot + (fresh ? 2.0 : 1.0) * o.checkpoint;
  return o;
}

std::size_t peak_memory_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;
  return 0;
}

int run_scene(const scene::Scene& scene, const RunOptions& options) {
  const fs::path dir = options.out;
  if (!options.resume && !options.overwrite && fs::exists(dir / "scene.resolved.toml")) {
    fmt::print(stderr, "hvi: {} holds a previous run; use --overwrite to replace it or --resume to continue it\n", dir.string());
    return input_error;
  }
  if (options.resume && !fs::exists(dir / "checkpoint.h5")) {
    fmt::print(stderr, "hvi: {} has no checkpoint.h5 to resume from\n", dir.string());
    return input_error;
  }
  if (options.threads > 0) omp_set_num_threads(options.threads);
  const int threads = omp_get_max_threads();

  // Build everything before writing anything: a scene that cannot be built leaves no output.
  std::unique_ptr<mpm::Solver> solver = make_solver(scene);
  std::vector<std::size_t> counts;
  mpm::io::CheckpointExtras extras;
  std::unique_ptr<Hybrid> hybrid;  // only when the scene names a [far_field]
  std::unique_ptr<Probes> probes;
  try {
    hybrid = make_hybrid(scene, *solver);
    if (options.resume) {
      extras = mpm::io::read_checkpoint(dir / "checkpoint.h5", *solver);
    } else {
      counts = add_bodies(scene, *solver);
      solver->initialise();
      if (hybrid) hybrid->record_reference_positions(*solver);
    }
    probes = std::make_unique<Probes>(scene, *solver, hybrid.get());
    if (options.resume) probes->load(extras);
  } catch (const std::exception& e) {
    fmt::print(stderr, "hvi: {}: {}\n", scene.file, e.what());
    return input_error;
  }
  // A field measure needs a model that declares the field: check before anything is written.
  for (const auto& m : scene.measures)
    if (!m.field.empty() && (m.kind == "field_max" || m.kind == "field_min") && !solver->particles().has_field(m.field)) {
      fmt::print(stderr, "hvi: {}: measure '{}': no particle field '{}' in this scene (is its model named?)\n",
                 scene.file, m.name, m.field);
      return input_error;
    }

  // What `hvi measure` wrote is stale once the run is replaced or continued: a sweep then measures
  // the run again; by hand, `hvi measure` does.
  if (options.overwrite || options.resume) remove_measurements(dir);
  if (options.overwrite && !options.resume) {
    for (const char* f : {"particles.xmf", "energy.csv", "checkpoint.h5", "summary.json", "summary.toml", "timing.csv",
                          "run.resumed.json", "resumes.jsonl", "failure.h5", "far_field.pvd", "probes.csv",
                          hole_history_file})
      fs::remove(dir / f);
    fs::remove_all(dir / "snapshots");
    fs::remove_all(dir / "far_field");
  }
  fs::create_directories(dir);
  write_text(dir / "scene.resolved.toml", scene::resolved_text(scene));
  if (options.resume)
    append_resume_record(dir, options, threads, solver->step_count(), solver->time());
  else
    write_run_info(dir, options, threads, scene, solver->body_names());

  mpm::Solver& s = *solver;
  mpm::PhaseTimer& timer = s.timer();
  mpm::io::SnapshotWriter snapshots(dir);
  snapshots.keep_newest(static_cast<std::size_t>(scene.keep_snapshots));
  // The holes at every snapshot, when the holes measure asks for its history.
  const auto holes = std::find_if(scene.measures.begin(), scene.measures.end(), [](const auto& m) { return m.kind == "holes"; });
  std::optional<HoleHistory> history;
  if (holes != scene.measures.end() && holes->history)
    history.emplace(dir, holes->body, options.resume ? s.step_count() : -1);
  auto measure_holes = [&] {
    auto t = timer.scope("measure the holes");
    const Measurements& m = history->add();
    fmt::print("  holes at t = {:.4g} us: {}\n", m.time * 1e6, hole_summary(m));
  };
  mpm::io::EnergyLog energy_log(dir / "energy.csv", options.resume ? s.step_count() : -1, hybrid != nullptr,
                                s.contact() != nullptr);
  probes->open(dir, options.resume ? s.step_count() : -1);
  auto write_snapshots = [&] {
    snapshots.write(s);
    if (hybrid) hybrid->write_snapshot(dir, s.step_count(), s.time());
  };
  Schedule output{scene.output_interval, 0.0}, checkpoints{scene.checkpoint_interval, scene.checkpoint_interval};
  double initial_energy = 0.0;
  RunRecord record;  // what the scene's [[measure]]s need beyond the final state
  const auto particle_count = s.particles().size();
  // Wall time of the time loop in all the invocations that made this state (a run resumed, run on
  // or interrupted several times costs their sum); NaN: a checkpoint from before hvi recorded it.
  double earlier_wall = 0.0;

  if (options.resume) {
    snapshots.resume(s.step_count());
    if (hybrid) {
      hybrid->resume(dir, s.step_count());
      hybrid->load(extras);
    }
    output.next = extras.at("next_output_time");
    checkpoints.next = extras.at("next_checkpoint_time");
    initial_energy = extras.at("initial_energy");
    record.peak_pressure = extras.at("peak_pressure");
    const auto recorded = extras.find("wall_seconds");
    earlier_wall = recorded != extras.end() ? recorded->second : std::numeric_limits<double>::quiet_NaN();
    fmt::print("hvi: resuming {} at step {}, t = {:.6g} s ({} particles, {} threads)\n", dir.string(),
               s.step_count(), s.time(), particle_count, threads);
  } else {
    fmt::print("hvi: {}{}\n", scene.file, scene.title.empty() ? "" : " — " + scene.title);
    for (const auto& w : scene.warnings) fmt::print("  warning: {}\n", w);
    for (std::size_t b = 0; b < scene.bodies.size(); ++b)
      fmt::print("  body '{}': {} particles, material '{}'\n", scene.bodies[b].name, counts[b],
                 scene.materials[scene.bodies[b].material].name);
    fmt::print("  grid {} x {} x {} cells of {:.4g} m; {} threads; first dt {:.4g} s\n", scene.grid.cells[0],
               scene.grid.cells[1], scene.grid.cells[2], scene.grid.cell_size, threads, s.next_time_step());
    if (hybrid) fmt::print("  {}\n", hybrid->describe());
    const mpm::EnergyReport e0 = s.energy();
    initial_energy = e0.total();
    energy_log.write(s, e0);
    probes->record(s);
    track(s, record);
    write_snapshots();
    output.advance(s.time());
    // A holes history that cannot be measured (no panel to find, say) stops the run at t = 0.
    if (history) try {
        measure_holes();
      } catch (const std::exception& e) {
        fmt::print(stderr, "hvi: {}: measure '{}' (history = true): {}\n", scene.file, holes->name, e.what());
        return input_error;
      }
  }

  std::int64_t last_checkpoint_step = s.step_count();
  auto wall_start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count(); };
  // wall: this invocation's time-loop seconds up to the state written.
  auto checkpoint = [&](double wall) {
    auto t = timer.scope("write checkpoint");
    last_checkpoint_step = s.step_count();
    mpm::io::CheckpointExtras extras{{"next_output_time", output.next},
                                     {"next_checkpoint_time", checkpoints.next},
                                     {"initial_energy", initial_energy},
                                     {"peak_pressure", record.peak_pressure}};
    if (!std::isnan(earlier_wall)) extras["wall_seconds"] = earlier_wall + wall;
    probes->save(extras);
    if (hybrid) hybrid->save(extras);
    mpm::io::write_checkpoint(dir / "checkpoint.h5", s, extras);
  };
  report_disk(dir, s, scene, output.next, !options.resume);
  // A checkpoint exists from the start, so a run that fails always leaves one from before.
  if (!options.resume) checkpoint(0.0);

  stop_signal = 0;
  auto previous_sigint = std::signal(SIGINT, on_stop_signal);
  auto previous_sigterm = std::signal(SIGTERM, on_stop_signal);
  const auto restore_signals = [&] {
    std::signal(SIGINT, previous_sigint);
    std::signal(SIGTERM, previous_sigterm);
  };
  Progress progress(scene.end_time);
  progress.start(s);
  wall_start = std::chrono::steady_clock::now();
  const std::int64_t first_step = s.step_count();
  double particle_steps = 0.0;  // a zone that grows adds particles
  std::int64_t reported_removals = 0;
  int code = success;
  const double end = scene.end_time;
  try {
    while (s.time() < end * (1 - 1e-12)) {
      if (stop_signal != 0) {
        code = stop_signal == SIGTERM ? terminated : interrupted;
        break;
      }
      if (scene.max_steps > 0 && s.step_count() >= scene.max_steps) break;
      s.step(end - s.time());
      particle_steps += static_cast<double>(s.particles().size());
      report_removals(s, s.take_removal_events(), reported_removals);
      if (hybrid && hybrid->growing()) {
        auto t = timer.scope("grow the MPM zone");
        const std::array<bool, 4> held_before = hybrid->held_at_limit().sides;
        const auto r = hybrid->grow(s);
        if (hybrid->held_at_limit().sides != held_before) {
          std::array<bool, 4> now{};
          for (int side = 0; side < 4; ++side) now[side] = hybrid->held_at_limit().sides[side] && !held_before[side];
          fmt::print("  step {}, t = {:.6g} s: the panel's damage reached the MPM zone's edge at {}, its limit "
                     "(far_field.zone.grow): the far field there holds damage it cannot; a wider limit lets the zone go on\n",
                     s.step_count(), s.time(), side_names(now, hybrid->zone()));
        }
        if (r) {
          probes->zone_grew(s, r->first_id);
          const auto& z = hybrid->zone();
          fmt::print("  step {}, t = {:.6g} s: the MPM zone grew to [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] mm: {} points "
                     "took over {} far-field elements; energy not carried over {:.3g} J of {:.3g} J (kinetic "
                     "{:.3g} J of {:.3g} J)\n",
                     s.step_count(), s.time(), 1e3 * z[0], 1e3 * z[2], 1e3 * z[1], 1e3 * z[3], r->points, r->cells,
                     r->far_field_energy - r->point_energy, r->far_field_energy,
                     r->far_field_kinetic - r->point_kinetic, r->far_field_kinetic);
        }
      }
      const bool last = s.time() >= end * (1 - 1e-12);
      if (s.step_count() % scene.energy_every == 0 || last) {
        auto t = timer.scope("energy");
        const mpm::EnergyReport e = s.energy();
        energy_log.write(s, e);
        probes->record(s);
        track(s, record);
        if (scene.max_energy_growth > 0 && e.total() - initial_energy > scene.max_energy_growth * std::fabs(initial_energy))
          s.fail(s.fastest_particle(),
                 fmt::format("the total energy grew by {:.0f}% (run.max_energy_growth = {:.0f}%): the run is unstable; "
                             "this particle moves fastest, at {:.4g} m/s",
                             100 * (e.total() / initial_energy - 1), 100 * scene.max_energy_growth,
                             mpm::speed(s.particles(), s.fastest_particle())));
      }
      if (output.due(s.time()) || last) {
        auto t = timer.scope("write snapshots");
        write_snapshots();
        output.advance(s.time());
        progress.snapshot_written(s);
        if (history) try {
            measure_holes();
          } catch (const std::exception& e) {
            fmt::print(stderr, "hvi: warning: the holes could not be measured at t = {:.6g} s: {}; no more rows in {}\n",
                       s.time(), e.what(), hole_history_file);
            history.reset();
          }
      }
      if (checkpoints.due(s.time())) {
        checkpoints.advance(s.time());
        checkpoint(elapsed());
      }
      progress.update(s);
    }
  } catch (const mpm::SolverError& e) {
    progress.finish();
    fmt::print(stderr, "hvi: the run failed: {}\n", e.what());
    // The state at the failure, for a look in ParaView or h5py (not a restart point).
    mpm::io::write_snapshot_file(dir / "failure.h5", s);
    fmt::print(stderr, "hvi: {} holds the state at the failure; checkpoint.h5 (step {}) the last state before it\n",
               (dir / "failure.h5").string(), last_checkpoint_step);
    restore_signals();
    return run_failed;
  }
  const double wall = elapsed();
  checkpoint(wall);  // the end state, or where an interruption or max_steps stopped the run
  progress.update(s, true);
  progress.finish();
  restore_signals();

  const std::int64_t steps = s.step_count() - first_step;
  const mpm::EnergyReport e = s.energy();
  const double balance = initial_energy != 0.0 ? (e.total() - initial_energy) / initial_energy : 0.0;
  const double rate = particle_steps / std::max(wall, 1e-9);
  const std::size_t peak_memory = peak_memory_bytes();  // of the run, before the hole measurement reads snapshots
  fmt::print("hvi: {} at t = {:.6g} s, step {}: {} steps in {:.2f} s ({:.3g} particle-steps/s, {} threads, peak memory {:.0f} MB)\n",
             stopped_by_signal(code) ? "interrupted" : (s.time() >= end * (1 - 1e-12) ? "finished" : "stopped (run.max_steps)"),
             s.time(), s.step_count(), steps, wall, rate, threads, peak_memory / 1e6);
  if (options.resume)
    fmt::print("  wall time of all the invocations that made this run: {}\n",
               std::isnan(earlier_wall) ? std::string("unknown (its checkpoint predates the record)")
                                        : fmt::format("{:.2f} s", earlier_wall + wall));
  fmt::print("  energy: initial {:.6g} J, now {:.6g} J = kinetic {:.6g} + internal {:.6g} + dissipated {:.6g} + removed {:.6g}{}{}; balance {:+.3f}%\n",
             initial_energy, e.total(), e.kinetic, e.internal, e.dissipated, e.removed,
             hybrid ? fmt::format(" + far field kinetic {:.6g} + strain {:.6g}", e.coupled_kinetic, e.coupled_strain) : "",
             s.contact() ? fmt::format(" + contact {:.6g}", e.contact) : "", 100 * balance);
  fmt::print("  momentum (incl. removed): ({:.6g}, {:.6g}, {:.6g}) kg m/s\n", e.momentum[0] + e.removed_momentum[0],
             e.momentum[1] + e.removed_momentum[1], e.momentum[2] + e.removed_momentum[2]);
  if (s.removed().particles > 0)
    fmt::print("  left the grid: {} particles, {:.6g} kg, {:.6g} J\n", s.removed().particles, s.removed().mass, e.removed);
  if (hybrid && hybrid->far_field().plastic()) {
    const double alpha = hybrid->far_field().max_equivalent_plastic_strain();
    fmt::print("  far field: largest plastic strain {:.4g}{}{}, plastic work {:.6g} J\n", alpha,
               scene.far_field->failing_faces
                   ? fmt::format(" (facesheets: {:.4g} mm^3 torn)", 1e9 * hybrid->far_field().facesheet_failed_volume())
                   : std::string(),
               scene.far_field->yielding_core
                   ? fmt::format(" (core: {:.4g}{})", hybrid->far_field().max_core_plastic_strain(),
                                 scene.far_field->failing_core
                                     ? fmt::format(", {:.4g} mm^3 torn", 1e9 * hybrid->far_field().core_failed_volume())
                                     : std::string())
                   : std::string(),
               hybrid->far_field().plastic_work());
    // Beyond a few percent the damage has reached the zone's edge, which the far field cannot tear
    // (and small-strain J2 stops meaning much).
    if (alpha > 0.05)
      fmt::print("  warning: the far field's facesheets yield to a plastic strain of {:.3g}{}; the damage reaches "
                 "the MPM zone's edge: {} would hold it\n",
                 alpha, hybrid->far_field().finite_strain() ? "" : " (small-strain theory)",
                 hybrid->growing() ? "a larger limit of [far_field.zone.grow]" : "a larger [far_field] zone, or one that grows,");
  }
  if (hybrid && hybrid->growing()) {
    const auto& z = hybrid->zone();
    const Hybrid::LimitRecord& held = hybrid->held_at_limit();
    fmt::print("  MPM zone: [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] mm, {} far-field elements taken over; {}\n", 1e3 * z[0],
               1e3 * z[2], 1e3 * z[1], 1e3 * z[3], hybrid->far_field().removed_cell_count(),
               held.steps == 0 ? std::string("the damage never reached a side at its limit")
                               : fmt::format("the damage held it at its limit ({}) at {} steps, from t = {:.4g} to {:.4g} s",
                                             side_names(held.sides, z), held.steps, held.first_time, held.last_time));
  }
  record.initial_energy = initial_energy;
  auto measured = evaluate(scene.measures, s, record);
  measured.merge(probes->values(s));
  for (const auto& [name, value] : measured) fmt::print("  measure {} = {:.8g}\n", name, value);
  fmt::print("\n{}\n", timer.table());
  write_timing(dir, timer);
  const bool finished = !stopped_by_signal(code) && s.time() >= end * (1 - 1e-12);
  const char* status = stopped_by_signal(code) ? "interrupted" : (finished ? "finished" : "stopped");
  toml::table summary{{"time", s.time()},
                      {"steps", s.step_count()},
                      {"particles", static_cast<std::int64_t>(s.particles().size())},
                      {"wall_seconds", wall},
                      {"particle_steps_per_second", rate},
                      {"threads", threads},
                      {"peak_memory_bytes", static_cast<std::int64_t>(peak_memory)},
                      {"initial_energy", initial_energy},
                      {"energy_balance", balance},
                      {"removed_particles", s.removed().particles},
                      {"removed_mass", s.removed().mass},
                      {"status", status}};
  if (!std::isnan(earlier_wall)) summary.insert("wall_seconds_total", earlier_wall + wall);
  if (std::any_of(scene.materials.begin(), scene.materials.end(), [](const auto& m) { return m.erosion != "none"; })) {
    // What erosion took out of the stress field (the points stay, as point masses).
    const auto& P = s.particles();
    const auto& state = P.field("failed");
    std::int64_t count = 0;
    double mass = 0.0;
    for (std::size_t p = 0; p < P.size(); ++p)
      if (state[p] == mpm::failure_state::eroded) {
        ++count;
        mass += P.mass[p];
      }
    summary.insert("eroded_particles", count);
    summary.insert("eroded_mass", mass);
  }
  if (hybrid) {
    summary.insert("far_field_nodes", static_cast<std::int64_t>(hybrid->far_field().node_count()));
    summary.insert("far_field_elements", static_cast<std::int64_t>(hybrid->far_field().cell_count()));
    if (hybrid->growing()) {  // only when the scene asks for a zone that grows
      const auto& z = hybrid->zone();
      summary.insert("mpm_zone", toml::array{z[0], z[1], z[2], z[3]});
      summary.insert("far_field_elements_taken_over", static_cast<std::int64_t>(hybrid->far_field().removed_cell_count()));
      summary.insert("energy_not_carried_over", hybrid->coupling().converted_energy());
      // Whether the limit, not the damage, stopped the zone: the steps at which the panel's
      // damage reached a side at its limit, and the first and last time it did.
      const Hybrid::LimitRecord& held = hybrid->held_at_limit();
      summary.insert("mpm_zone_limit_reached_steps", held.steps);
      if (held.steps > 0) {
        summary.insert("mpm_zone_limit_reached_first_time", held.first_time);
        summary.insert("mpm_zone_limit_reached_last_time", held.last_time);
      }
    }
    if (hybrid->far_field().plastic()) {  // only when the scene asks for J2 facesheets or a yielding core
      summary.insert("far_field_max_plastic_strain", hybrid->far_field().max_equivalent_plastic_strain());
      if (scene.far_field->yielding_core)
        summary.insert("far_field_max_core_plastic_strain", hybrid->far_field().max_core_plastic_strain());
      if (scene.far_field->failing_core)
        summary.insert("far_field_core_failed_volume", hybrid->far_field().core_failed_volume());
      if (scene.far_field->failing_faces)
        summary.insert("far_field_facesheet_failed_volume", hybrid->far_field().facesheet_failed_volume());
      summary.insert("far_field_plastic_work", hybrid->far_field().plastic_work());
    }
  }
  const bool stopped_early = stopped_by_signal(code) || (scene.max_steps > 0 && s.time() < end * (1 - 1e-12));
  // The panel's holes, from the final snapshot (as hvi measure RUN_DIR does). The solver and the
  // far field go first, their memory back to the system: the measure reads the snapshots and on a
  // large model needs memory of its own, which then does not come on top of the run's.
  if (holes != scene.measures.end() && finished) {
    // The history has measured the final snapshot already.
    const Measurements* final_holes = history ? history->at_step(s.step_count()) : nullptr;
    probes.reset();
    hybrid.reset();
    solver.reset();
    malloc_trim(0);
    try {
      MeasureOptions mo;
      mo.run = dir;
      mo.front = holes->body;  // empty: the panel's front facesheet
      const Measurements m = final_holes ? *final_holes : measure_run(mo);
      fmt::print("\n");
      print_measurements(m);
      write_measurements(m, dir);
      for (const auto& [name, value] : headline_quantities(m)) measured[name] = value;
    } catch (const std::exception& e) {
      fmt::print(stderr, "hvi: the holes could not be measured: {}\n", e.what());
    }
    // The command's peak: the run's, or the measurement's where that is larger (the kernel's
    // counters can read a fraction of a MB lower after memory was returned).
    summary.insert("peak_memory_with_measure_bytes", static_cast<std::int64_t>(std::max(peak_memory, peak_memory_bytes())));
  }
  toml::table measures;
  for (const auto& [name, value] : measured) measures.insert(name, value);
  summary.insert("measures", measures);
  {
    // JSON for scripts and Python; the same as TOML for hvi's own tools (hvi convergence).
    std::ofstream json(dir / "summary.json");
    json << toml::json_formatter(summary) << '\n';
    std::ofstream tml(dir / "summary.toml");
    tml << toml::toml_formatter(summary) << '\n';
  }
  fmt::print("output: {}  (particles.xmf for ParaView, energy.csv, summary.json, scene.resolved.toml)\n", dir.string());
  if (stopped_early) fmt::print("resume with: hvi run --resume {}\n", dir.string());
  return code;
}

}  // namespace hvi::driver
