#include "cases/run/run.hpp"

#include <malloc.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "cases/run/build_solver.hpp"
#include "cases/run/hole_history.hpp"
#include "cases/run/hybrid.hpp"
#include "cases/run/measure_command.hpp"
#include "cases/run/measures.hpp"
#include "cases/run/probes.hpp"
#include "cases/run/run_output.hpp"
#include "cases/run/settle.hpp"
#include "mpm/io/checkpoint.hpp"
#include "mpm/io/energy_log.hpp"
#include "mpm/io/snapshot_writer.hpp"
#include "mpm/materials/hydro_material.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

namespace {

// The signal (SIGINT or SIGTERM) that asked the run to stop at the end of its step; 0: none.
volatile std::sig_atomic_t stop_signal = 0;
extern "C" void on_stop_signal(int number) {
  stop_signal = number;
}

// Snapshot/checkpoint times: multiples of an interval; due once the run has reached them.
struct Schedule {
  double interval, next;
  bool due(double t) const { return t >= next - 1e-9 * interval; }
  void advance(double t) { next = (std::floor(t / interval + 1e-9) + 1.0) * interval; }
};

// SIGINT and SIGTERM stop the run at the end of its step while this lives.
class StopSignals {
 public:
  StopSignals() {
    stop_signal = 0;
    sigint_ = std::signal(SIGINT, on_stop_signal);
    sigterm_ = std::signal(SIGTERM, on_stop_signal);
  }
  ~StopSignals() {
    std::signal(SIGINT, sigint_);
    std::signal(SIGTERM, sigterm_);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  void (*sigint_)(int) = nullptr;
  void (*sigterm_)(int) = nullptr;
};

// One invocation of `hvi run`: its phases in the order run_scene calls them. Everything is built
// before anything is written, so a scene that cannot be built leaves no output.
class SceneRun {
 public:
  SceneRun(const scene::Scene& scene, const RunOptions& options)
      : scene_(scene), options_(options), dir_(options.out), end_(scene.end_time) {}

  int check_directory() const;
  int build();
  void prepare_directory();
  void open_logs();
  int start();
  int time_loop();
  int finish(int code);

 private:
  bool at_end() const { return solver_->time() >= end_ * (1 - 1e-12); }
  bool done() const { return at_end() || settled_.has_value(); }  // the end time, or settled
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  }
  void resume_state();
  int start_at_zero();
  void step();
  void grow_zone();
  void log_energy();
  void write_output();
  void measure_holes();
  void write_snapshots();
  void checkpoint(double wall);
  void check_same_state() const;
  void print_result(int code, double rate, std::size_t peak_memory, const mpm::EnergyReport& e,
                    double balance) const;
  void print_far_field() const;
  toml::table summary(const char* status, double rate, std::size_t peak_memory,
                      double balance) const;
  void add_far_field_summary(toml::table& summary) const;
  void measure_final_holes(toml::table& summary, std::map<std::string, double>& measured,
                           std::size_t peak_memory);

  const scene::Scene& scene_;
  const RunOptions& options_;
  const fs::path dir_;
  const double end_;
  int threads_ = 0;
  std::unique_ptr<mpm::Solver> solver_;
  std::vector<std::size_t> counts_;    // points per body, of a new run
  std::vector<std::string> overlaps_;  // bodies that overlap at the start
  mpm::io::CheckpointExtras extras_;   // of a resumed run
  std::unique_ptr<Hybrid> hybrid_;     // only when the scene names a [far_field]
  std::unique_ptr<Probes> probes_;
  std::optional<mpm::io::SnapshotWriter> snapshots_;
  const scene::MeasureSettings* holes_ = nullptr;  // the holes measure, if any
  std::optional<HoleHistory> history_;  // the holes at every snapshot, when it asks for them
  std::optional<SettleCheck> settle_;   // measure.<holes>.stop_when_settled only
  std::optional<std::string> settled_;  // why the rear sheet has settled, once it has
  std::optional<mpm::io::EnergyLog> energy_log_;
  std::optional<mpm::io::LedgerLog> ledger_log_;  // output.energy_ledger only
  Schedule output_{0, 0}, checkpoints_{0, 0};
  double initial_energy_ = 0.0;
  RunRecord record_;  // what the scene's [[measure]]s need beyond the final state
  // Wall time of the time loop in all the invocations that made this state (a run resumed, run on
  // or interrupted several times costs their sum); NaN: a checkpoint from before hvi recorded it.
  double earlier_wall_ = 0.0;
  std::int64_t last_checkpoint_step_ = 0, first_step_ = 0, reported_removals_ = 0;
  std::chrono::steady_clock::time_point wall_start_ = std::chrono::steady_clock::now();
  double particle_steps_ = 0.0;  // a zone that grows adds particles
  double wall_ = 0.0;            // this invocation's time loop, s
  std::optional<Progress> progress_;
};

int SceneRun::check_directory() const {
  if (!options_.resume && !options_.overwrite && fs::exists(dir_ / "scene.resolved.toml")) {
    fmt::print(
        stderr,
        "hvi: {} holds a previous run; use --overwrite to replace it or --resume to continue it\n",
        dir_.string());
    return input_error;
  }
  if (options_.resume && !fs::exists(dir_ / "checkpoint.h5")) {
    fmt::print(stderr, "hvi: {} has no checkpoint.h5 to resume from\n", dir_.string());
    return input_error;
  }
  return success;
}

// The solver with its bodies (or its checkpoint), the far field, the probes; and the check that
// every field measure has a model that declares its field.
int SceneRun::build() {
  if (options_.threads > 0) omp_set_num_threads(options_.threads);
  threads_ = omp_get_max_threads();
  solver_ = make_solver(scene_);
  try {
    if (options_.ranks) {
      solver_->distribute(options_.ranks);
      solver_->lead();
    }
    hybrid_ = make_hybrid(scene_, *solver_);
    if (options_.resume) {
      extras_ = mpm::io::read_checkpoint(dir_ / "checkpoint.h5", *solver_);
      check_same_state();
    } else {
      const PointShare share{0, options_.ranks ? options_.ranks->size() : 1};
      counts_ = add_bodies(scene_, *solver_, options_.max_memory, &overlaps_, share);
      solver_->initialise();
      if (hybrid_) hybrid_->record_reference_positions(*solver_);
    }
    // Probes choose their points among all of them: a spread run's are gathered on rank 0 once;
    // the first step spreads them, and each row asks the ranks for the probes' points alone.
    if (has_probes(scene_)) solver_->gather_to_root();
    probes_ = std::make_unique<Probes>(scene_, *solver_, hybrid_.get());
    if (options_.resume) probes_->load(extras_);
  } catch (const std::exception& e) {
    fmt::print(stderr, "hvi: {}: {}\n", scene_.file, e.what());
    return input_error;
  }
  for (const auto& m : scene_.measures)
    if (!m.field.empty() && (m.kind == "field_max" || m.kind == "field_min") &&
        !solver_->particles().has_field(m.field)) {
      fmt::print(
          stderr,
          "hvi: {}: measure '{}': no particle field '{}' in this scene (is its model named?)\n",
          scene_.file, m.name, m.field);
      return input_error;
    }
  return success;
}

// The run's directory: what an earlier run or `hvi measure` left goes, the resolved scene and
// run.json (or a line of resumes.jsonl) come.
void SceneRun::prepare_directory() {
  // What `hvi measure` wrote is stale once the run is replaced or continued: a sweep then measures
  // the run again; by hand, `hvi measure` does.
  if (options_.overwrite || options_.resume) remove_measurements(dir_);
  if (options_.overwrite && !options_.resume) {
    for (const char* f :
         {"particles.xmf", "energy.csv", "energy_ledger.csv", "checkpoint.h5", "summary.json",
          "summary.toml", "timing.csv", "run.resumed.json", "resumes.jsonl", "failure.h5",
          "far_field.pvd", "probes.csv", hole_history_file})
      fs::remove(dir_ / f);
    fs::remove_all(dir_ / "snapshots");
    fs::remove_all(dir_ / "far_field");
  }
  fs::create_directories(dir_);
  write_text(dir_ / "scene.resolved.toml", scene::resolved_text(scene_));
  if (options_.resume)
    append_resume_record(dir_, options_, threads_, solver_->step_count(), solver_->time());
  else
    write_run_info(dir_, options_, threads_, scene_, solver_->body_names());
}

void SceneRun::open_logs() {
  const mpm::Solver& s = *solver_;
  const std::int64_t resume_step = options_.resume ? s.step_count() : -1;
  snapshots_.emplace(dir_, options_.shared_files);
  snapshots_->keep_newest(static_cast<std::size_t>(scene_.keep_snapshots));
  const auto holes = std::find_if(scene_.measures.begin(), scene_.measures.end(),
                                  [](const auto& m) { return m.kind == "holes"; });
  if (holes != scene_.measures.end()) holes_ = &*holes;
  if (holes_ && holes_->history) history_.emplace(dir_, holes_->body, resume_step);
  if (history_ && holes_->stop_when_settled) {
    settle_.emplace(*holes_->stop_when_settled, holes_->settle_tolerance);
    if (options_.resume) {
      settle_->load(dir_ / hole_history_file);  // the rows up to the checkpoint
      settled_ = settle_->settled();
    }
  }
  energy_log_.emplace(dir_ / "energy.csv", resume_step, hybrid_ != nullptr, s.contact() != nullptr);
  if (scene_.energy_ledger)
    ledger_log_.emplace(dir_ / "energy_ledger.csv", s.body_names(), resume_step);
  probes_->open(dir_, resume_step);
  output_ = {scene_.output_interval, 0.0};
  checkpoints_ = {scene_.checkpoint_interval, scene_.checkpoint_interval};
}

// The state at the start of the time loop: a checkpoint's, or t = 0 written out. Then the disk
// estimate and, for a new run, its first checkpoint (a run that fails always leaves one).
int SceneRun::start() {
  if (options_.resume) {
    resume_state();
  } else if (const int code = start_at_zero(); code != success) {
    return code;
  }
  last_checkpoint_step_ = solver_->step_count();
  report_disk(dir_, *solver_, scene_, output_.next, !options_.resume);
  if (!options_.resume) checkpoint(0.0);
  return success;
}

void SceneRun::resume_state() {
  const mpm::Solver& s = *solver_;
  snapshots_->resume(s.step_count());
  if (hybrid_) {
    hybrid_->resume(dir_, s.step_count());
    hybrid_->load(extras_);
  }
  output_.next = extras_.at("next_output_time");
  checkpoints_.next = extras_.at("next_checkpoint_time");
  initial_energy_ = extras_.at("initial_energy");
  record_.peak_pressure = extras_.at("peak_pressure");
  const auto recorded = extras_.find("wall_seconds");
  earlier_wall_ =
      recorded != extras_.end() ? recorded->second : std::numeric_limits<double>::quiet_NaN();
  fmt::print("hvi: resuming {} at step {}, t = {:.6g} s ({} particles, {} threads)\n",
             dir_.string(), s.step_count(), s.time(), s.point_count(), threads_);
}

int SceneRun::start_at_zero() {
  mpm::Solver& s = *solver_;
  fmt::print("hvi: {}{}\n", scene_.file, scene_.title.empty() ? "" : " — " + scene_.title);
  for (const auto& w : scene_.warnings) fmt::print("  warning: {}\n", w);
  for (const auto& w : overlaps_) fmt::print("  warning: {}\n", w);
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b)
    fmt::print("  body '{}': {} particles, material '{}'\n", scene_.bodies[b].name, counts_[b],
               scene_.materials[scene_.bodies[b].material].name);
  fmt::print("  grid {} x {} x {} cells of {:.4g} m; {} threads{}; first dt {:.4g} s\n",
             scene_.grid.cells[0], scene_.grid.cells[1], scene_.grid.cells[2],
             scene_.grid.cell_size, threads_,
             options_.ranks ? fmt::format(" on each of {} ranks", options_.ranks->size()) : "",
             s.next_time_step());
  if (hybrid_) fmt::print("  {}\n", hybrid_->describe());
  const mpm::EnergyReport e0 = s.energy();
  initial_energy_ = e0.total();
  energy_log_->write(s, e0);
  if (ledger_log_) ledger_log_->write(s, e0);
  probes_->record(s);
  track(s, record_);
  write_snapshots();
  output_.advance(s.time());
  // A holes history that cannot be measured (no panel to find, say) stops the run at t = 0.
  if (history_) try {
      measure_holes();
    } catch (const std::exception& e) {
      fmt::print(stderr, "hvi: {}: measure '{}' (history = true): {}\n", scene_.file, holes_->name,
                 e.what());
      return input_error;
    }
  return success;
}

// Steps to the end time, or until a signal or run.max_steps stops the run; checkpoints where it
// stopped. A solver error leaves its state in failure.h5 and the last checkpoint from before it.
int SceneRun::time_loop() {
  mpm::Solver& s = *solver_;
  StopSignals signals;
  progress_.emplace(scene_.end_time);
  progress_->start(s);
  wall_start_ = std::chrono::steady_clock::now();
  first_step_ = s.step_count();
  int code = success;
  try {
    while (!done()) {
      if (stop_signal != 0) {
        code = stop_signal == SIGTERM ? terminated : interrupted;
        break;
      }
      if (scene_.max_steps > 0 && s.step_count() >= scene_.max_steps) break;
      step();
    }
  } catch (const mpm::SolverError& e) {
    progress_->finish();
    fmt::print(stderr, "hvi: the run failed: {}\n", e.what());
    if (options_.ranks && !e.every_rank()) {  // the others wait inside the step: the job ends
      fmt::print(stderr, "hvi: checkpoint.h5 (step {}) holds the last state before it\n",
                 last_checkpoint_step_);
      std::fflush(nullptr);
      options_.ranks->abort(run_failed);
    }
    // The state at the failure, for a look in ParaView or h5py (not a restart point); a spread
    // run's every rank failed alike and now waits for rank 0, which gathers the points.
    s.gather_to_root();
    mpm::io::write_snapshot_file(dir_ / "failure.h5", s);
    fmt::print(stderr,
               "hvi: {} holds the state at the failure; checkpoint.h5 (step {}) the last state "
               "before it\n",
               (dir_ / "failure.h5").string(), last_checkpoint_step_);
    return run_failed;
  }
  wall_ = elapsed();
  checkpoint(wall_);  // the end state, or where an interruption or max_steps stopped the run
  progress_->update(s, true);
  progress_->finish();
  return code;
}

// One step and what follows it: the zone's growth, energy.csv, snapshots, checkpoints, progress.
void SceneRun::step() {
  mpm::Solver& s = *solver_;
  const std::int64_t cuts = s.sharing().cuts;
  s.step(end_ - s.time());
  particle_steps_ += static_cast<double>(s.point_count());
  if (s.sharing().cuts > cuts && cuts > 0)
    fmt::print(
        "  step {}: the partition among ranks cut anew: the fullest rank held {:.1f}% over "
        "the mean, now {:.1f}%\n",
        s.sharing().cut_step, 100 * s.sharing().imbalance_before,
        100 * s.sharing().imbalance_after);
  report_removals(s, s.take_removal_events(), reported_removals_);
  if (hybrid_ && hybrid_->growing()) grow_zone();
  const bool last = at_end();
  const bool logged = s.step_count() % scene_.energy_every == 0 || last;
  if (logged) log_energy();
  if (output_.due(s.time()) || last) write_output();
  if (settled_ && !logged) log_energy();  // the run ends here: its energy.csv row
  if (checkpoints_.due(s.time())) {
    checkpoints_.advance(s.time());
    checkpoint(elapsed());
  }
  progress_->update(s);
}

void SceneRun::grow_zone() {
  mpm::Solver& s = *solver_;
  auto t = s.timer().scope("grow the MPM zone");
  s.announce_grow();
  const std::array<bool, 4> held_before = hybrid_->held_at_limit().sides;
  const auto r = hybrid_->grow(s);
  if (hybrid_->held_at_limit().sides != held_before) {
    std::array<bool, 4> now{};
    for (int side = 0; side < 4; ++side)
      now[side] = hybrid_->held_at_limit().sides[side] && !held_before[side];
    fmt::print(
        "  step {}, t = {:.6g} s: the panel's damage reached the MPM zone's edge at {}, its limit "
        "(far_field.zone.grow): the far field there holds damage it cannot; a wider limit lets the "
        "zone go on\n",
        s.step_count(), s.time(), side_names(now, hybrid_->zone()));
  }
  if (!r) return;
  probes_->zone_grew(s, r->first_id);
  const auto& z = hybrid_->zone();
  fmt::print(
      "  step {}, t = {:.6g} s: the MPM zone grew to [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] mm: {} "
      "points "
      "took over {} far-field elements; energy not carried over {:.3g} J of {:.3g} J (kinetic "
      "{:.3g} J of {:.3g} J)\n",
      s.step_count(), s.time(), 1e3 * z[0], 1e3 * z[2], 1e3 * z[1], 1e3 * z[3], r->points, r->cells,
      r->far_field_energy - r->point_energy, r->far_field_energy,
      r->far_field_kinetic - r->point_kinetic, r->far_field_kinetic);
}

// energy.csv, the probes and the measures' records; a total energy grown past
// run.max_energy_growth stops the run as unstable.
void SceneRun::log_energy() {
  mpm::Solver& s = *solver_;
  auto t = s.timer().scope("energy");
  const mpm::EnergyReport e = s.energy();
  energy_log_->write(s, e);
  if (ledger_log_) ledger_log_->write(s, e);
  probes_->record(s);
  track(s, record_);
  if (scene_.max_energy_growth > 0 &&
      e.total() - initial_energy_ > scene_.max_energy_growth * std::fabs(initial_energy_)) {
    s.gather_to_root();  // to name the fastest point of all
    // The other ranks of a spread run wait for rank 0's next command: the run can end cleanly.
    throw mpm::SolverError(
        s.failure(
            s.fastest_particle(),
            fmt::format("the total energy grew by {:.0f}% (run.max_energy_growth = {:.0f}%): the "
                        "run is unstable; "
                        "this particle moves fastest, at {:.4g} m/s",
                        100 * (e.total() / initial_energy_ - 1), 100 * scene_.max_energy_growth,
                        mpm::speed(s.particles(), s.fastest_particle()))),
        true);
  }
}

void SceneRun::write_output() {
  mpm::Solver& s = *solver_;
  auto t = s.timer().scope("write snapshots");
  if (!options_.shared_files) s.gather_to_root();  // else every rank writes its points
  write_snapshots();
  output_.advance(s.time());
  progress_->snapshot_written(s);
  if (history_) try {
      measure_holes();
    } catch (const std::exception& e) {
      fmt::print(
          stderr,
          "hvi: warning: the holes could not be measured at t = {:.6g} s: {}; no more rows in {}\n",
          s.time(), e.what(), hole_history_file);
      history_.reset();
    }
}

void SceneRun::measure_holes() {
  auto t = solver_->timer().scope("measure the holes");
  const Measurements& m = history_->add();
  fmt::print("  holes at t = {:.4g} us: {}\n", m.time * 1e6, hole_summary(m));
  if (!settle_) return;
  if (const auto state = rear_state(m)) settle_->add(*state);
  settled_ = settle_->settled();
  if (settled_)
    fmt::print("  the rear sheet has settled ({}): the run stops (measure.{}.stop_when_settled)\n",
               *settled_, holes_->name);
}

void SceneRun::write_snapshots() {
  snapshots_->write(*solver_);
  if (!hybrid_) return;
  solver_->gather_coupled_state();  // spread: the far field's plastic state, to rank 0
  hybrid_->write_snapshot(dir_, solver_->step_count(), solver_->time());
}

// The scene's state hash in two halves of 32 bits: the checkpoint's extras are doubles.
static std::pair<double, double> hash_halves(std::uint64_t h) {
  return {static_cast<double>(h >> 32), static_cast<double>(h & 0xffffffffull)};
}

// A resumed run goes on with the physics its checkpoint was computed with: a scene changed in any
// key but when to stop, what to write and what to measure is refused before anything is written.
// (A checkpoint from before the hash was kept is trusted.)
void SceneRun::check_same_state() const {
  const auto hi = extras_.find("scene_state_hi"), lo = extras_.find("scene_state_lo");
  if (hi == extras_.end() || lo == extras_.end()) return;
  const auto [h, l] = hash_halves(scene::state_hash(scene_));
  if (hi->second == h && lo->second == l) return;
  throw std::invalid_argument(fmt::format(
      "{}: the scene differs from the one its checkpoint was computed with (in scene.resolved.toml "
      "or a --set): resuming would change the physics mid-run. Only {} may change on resume; "
      "start a new run for the rest",
      dir_.string(), scene::resumable_keys));
}

// wall: this invocation's time-loop seconds up to the state written.
void SceneRun::checkpoint(double wall) {
  auto t = solver_->timer().scope("write checkpoint");
  if (!options_.shared_files) solver_->gather_to_root();  // else every rank writes its points
  last_checkpoint_step_ = solver_->step_count();
  mpm::io::CheckpointExtras extras{{"next_output_time", output_.next},
                                   {"next_checkpoint_time", checkpoints_.next},
                                   {"initial_energy", initial_energy_},
                                   {"peak_pressure", record_.peak_pressure}};
  if (!std::isnan(earlier_wall_)) extras["wall_seconds"] = earlier_wall_ + wall;
  std::tie(extras["scene_state_hi"], extras["scene_state_lo"]) =
      hash_halves(scene::state_hash(scene_));
  probes_->save(extras);
  if (hybrid_) hybrid_->save(extras);
  solver_->gather_coupled_state();
  mpm::io::write_checkpoint(dir_ / "checkpoint.h5", *solver_, extras, options_.shared_files);
}

// The closing account: the result, the energy ledger, the far field, the measures and the time
// per phase on the console; timing.csv, the holes of the final snapshot and summary.json/.toml.
int SceneRun::finish(int code) {
  mpm::Solver& s = *solver_;
  const mpm::EnergyReport e = s.energy();
  const double balance =
      initial_energy_ != 0.0 ? (e.total() - initial_energy_) / initial_energy_ : 0.0;
  const double rate = particle_steps_ / std::max(wall_, 1e-9);
  const std::size_t peak_memory =
      peak_memory_bytes();  // of the run, before the hole measurement reads snapshots
  print_result(code, rate, peak_memory, e, balance);
  s.gather_coupled_state();  // the far field's closing figures and summary, on rank 0
  print_far_field();
  record_.initial_energy = initial_energy_;
  s.announce_measure();  // the other ranks give their points' extrema too
  const std::vector<double> extrema = s.max_pairs_over_ranks(point_extrema(scene_.measures, s));
  auto measured = evaluate(scene_.measures, s, record_, extrema);
  measured.merge(probes_->values(s));
  for (const auto& [name, value] : measured) fmt::print("  measure {} = {:.8g}\n", name, value);
  fmt::print("\n{}\n", s.timer().table());
  write_timing(dir_, s.timer());
  const bool finished = !stopped_by_signal(code) && done();
  const bool stopped_early = stopped_by_signal(code) || (scene_.max_steps > 0 && !done());
  const char* status = stopped_by_signal(code) ? "interrupted"
                       : !finished             ? "stopped"
                       : at_end()              ? "finished"
                                               : "settled";
  toml::table summary_table = summary(status, rate, peak_memory, balance);
  if (holes_ && finished) measure_final_holes(summary_table, measured, peak_memory);
  toml::table measures;
  for (const auto& [name, value] : measured) measures.insert(name, value);
  summary_table.insert("measures", measures);
  {
    // JSON for scripts and Python; the same as TOML for hvi's own tools (hvi convergence).
    std::ofstream json(dir_ / "summary.json");
    json << toml::json_formatter(summary_table) << '\n';
    std::ofstream tml(dir_ / "summary.toml");
    tml << toml::toml_formatter(summary_table) << '\n';
  }
  fmt::print(
      "output: {}  (particles.xmf for ParaView, energy.csv, summary.json, scene.resolved.toml)\n",
      dir_.string());
  if (stopped_early) fmt::print("resume with: hvi run --resume {}\n", dir_.string());
  return code;
}

void SceneRun::print_result(int code, double rate, std::size_t peak_memory,
                            const mpm::EnergyReport& e, double balance) const {
  const mpm::Solver& s = *solver_;
  fmt::print(
      "hvi: {} at t = {:.6g} s, step {}: {} steps in {:.2f} s ({:.3g} particle-steps/s, {} "
      "threads, peak memory {:.0f} MB)\n",
      stopped_by_signal(code) ? "interrupted"
      : at_end()              ? "finished"
      : settled_              ? "settled"
                              : "stopped (run.max_steps)",
      s.time(), s.step_count(), s.step_count() - first_step_, wall_, rate, threads_,
      peak_memory / 1e6);
  if (options_.resume)
    fmt::print("  wall time of all the invocations that made this run: {}\n",
               std::isnan(earlier_wall_)
                   ? std::string("unknown (its checkpoint predates the record)")
                   : fmt::format("{:.2f} s", earlier_wall_ + wall_));
  fmt::print(
      "  energy: initial {:.6g} J, now {:.6g} J = kinetic {:.6g} + internal {:.6g} + dissipated "
      "{:.6g} + removed {:.6g}{}{}; balance {:+.3f}%\n",
      initial_energy_, e.total(), e.kinetic, e.internal, e.dissipated, e.removed,
      hybrid_ ? fmt::format(" + far field kinetic {:.6g} + strain {:.6g}", e.coupled_kinetic,
                            e.coupled_strain)
              : "",
      s.contact() ? fmt::format(" + contact {:.6g}", e.contact) : "", 100 * balance);
  fmt::print("  momentum (incl. removed): ({:.6g}, {:.6g}, {:.6g}) kg m/s\n",
             e.momentum[0] + e.removed_momentum[0], e.momentum[1] + e.removed_momentum[1],
             e.momentum[2] + e.removed_momentum[2]);
  if (s.removed().particles > 0)
    fmt::print("  left the grid: {} particles, {:.6g} kg, {:.6g} J\n", s.removed().particles,
               s.removed().mass, e.removed);
  if (options_.ranks) {
    const auto& r = s.sharing();
    fmt::print(
        "  ranks: {}; the partition cut {} times; rank 0 sent or received {} migrating points, "
        "shared {:.0f} blocks of nodes a step and sent {:.3g} MB a step\n",
        options_.ranks->size(), r.cuts, r.migrated,
        static_cast<double>(r.shared_blocks) /
            std::max<std::int64_t>(1, s.step_count() - first_step_),
        1e-6 * static_cast<double>(r.bytes_sent) /
            std::max<std::int64_t>(1, s.step_count() - first_step_));
  }
}

// The far field's plastic strain and the zone a growing one reached.
void SceneRun::print_far_field() const {
  if (!hybrid_) return;
  const fem::FarField& far = hybrid_->far_field();
  if (far.plastic()) {
    const double alpha = far.max_equivalent_plastic_strain();
    fmt::print(
        "  far field: largest plastic strain {:.4g}{}{}, plastic work {:.6g} J\n", alpha,
        scene_.far_field->failing_faces
            ? fmt::format(" (facesheets: {:.4g} mm^3 torn)", 1e9 * far.facesheet_failed_volume())
            : std::string(),
        scene_.far_field->yielding_core
            ? fmt::format(" (core: {:.4g}{})", far.max_core_plastic_strain(),
                          scene_.far_field->failing_core
                              ? fmt::format(", {:.4g} mm^3 torn", 1e9 * far.core_failed_volume())
                              : std::string())
            : std::string(),
        far.plastic_work());
    // Beyond a few percent the damage has reached the zone's edge, which the far field cannot tear
    // (and small-strain J2 stops meaning much).
    if (alpha > 0.05)
      fmt::print(
          "  warning: the far field's facesheets yield to a plastic strain of {:.3g}{}; the damage "
          "reaches "
          "the MPM zone's edge: {} would hold it\n",
          alpha, far.finite_strain() ? "" : " (small-strain theory)",
          hybrid_->growing() ? "a larger limit of [far_field.zone.grow]"
                             : "a larger [far_field] zone, or one that grows,");
  }
  if (!hybrid_->growing()) return;
  const auto& z = hybrid_->zone();
  const Hybrid::LimitRecord& held = hybrid_->held_at_limit();
  fmt::print(
      "  MPM zone: [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] mm, {} far-field elements taken over; {}\n",
      1e3 * z[0], 1e3 * z[2], 1e3 * z[1], 1e3 * z[3], far.removed_cell_count(),
      held.steps == 0
          ? std::string("the damage never reached a side at its limit")
          : fmt::format(
                "the damage held it at its limit ({}) at {} steps, from t = {:.4g} to {:.4g} s",
                side_names(held.sides, z), held.steps, held.first_time, held.last_time));
}

toml::table SceneRun::summary(const char* status, double rate, std::size_t peak_memory,
                              double balance) const {
  const mpm::Solver& s = *solver_;
  toml::table summary{{"time", s.time()},
                      {"steps", s.step_count()},
                      {"particles", static_cast<std::int64_t>(s.point_count())},
                      {"wall_seconds", wall_},
                      {"particle_steps_per_second", rate},
                      {"threads", threads_},
                      {"ranks", options_.ranks ? options_.ranks->size() : 1},
                      {"peak_memory_bytes", static_cast<std::int64_t>(peak_memory)},
                      {"initial_energy", initial_energy_},
                      {"energy_balance", balance},
                      {"removed_particles", s.removed().particles},
                      {"removed_mass", s.removed().mass},
                      {"status", status}};
  if (!std::isnan(earlier_wall_)) summary.insert("wall_seconds_total", earlier_wall_ + wall_);
  if (settled_) summary.insert("settled", *settled_);  // why it stopped before the end time
  if (std::any_of(scene_.materials.begin(), scene_.materials.end(),
                  [](const auto& m) { return m.erosion != "none"; })) {
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
  add_far_field_summary(summary);
  return summary;
}

void SceneRun::add_far_field_summary(toml::table& summary) const {
  if (!hybrid_) return;
  const fem::FarField& far = hybrid_->far_field();
  summary.insert("far_field_nodes", static_cast<std::int64_t>(far.node_count()));
  summary.insert("far_field_elements", static_cast<std::int64_t>(far.cell_count()));
  if (hybrid_->growing()) {  // only when the scene asks for a zone that grows
    const auto& z = hybrid_->zone();
    summary.insert("mpm_zone", toml::array{z[0], z[1], z[2], z[3]});
    summary.insert("far_field_elements_taken_over",
                   static_cast<std::int64_t>(far.removed_cell_count()));
    summary.insert("energy_not_carried_over", hybrid_->coupling().converted_energy());
    // Whether the limit, not the damage, stopped the zone: the steps at which the panel's
    // damage reached a side at its limit, and the first and last time it did.
    const Hybrid::LimitRecord& held = hybrid_->held_at_limit();
    summary.insert("mpm_zone_limit_reached_steps", held.steps);
    if (held.steps > 0) {
      summary.insert("mpm_zone_limit_reached_first_time", held.first_time);
      summary.insert("mpm_zone_limit_reached_last_time", held.last_time);
    }
  }
  if (far.plastic()) {  // only when the scene asks for J2 facesheets or a yielding core
    summary.insert("far_field_max_plastic_strain", far.max_equivalent_plastic_strain());
    if (scene_.far_field->yielding_core)
      summary.insert("far_field_max_core_plastic_strain", far.max_core_plastic_strain());
    if (scene_.far_field->failing_core)
      summary.insert("far_field_core_failed_volume", far.core_failed_volume());
    if (scene_.far_field->failing_faces)
      summary.insert("far_field_facesheet_failed_volume", far.facesheet_failed_volume());
    summary.insert("far_field_plastic_work", far.plastic_work());
  }
}

// The panel's holes, from the final snapshot (as hvi measure RUN_DIR does). The solver and the
// far field go first, their memory back to the system: the measure reads the snapshots and on a
// large model needs memory of its own, which then does not come on top of the run's.
void SceneRun::measure_final_holes(toml::table& summary, std::map<std::string, double>& measured,
                                   std::size_t peak_memory) {
  // The history has measured the final snapshot already.
  const Measurements* final_holes = history_ ? history_->at_step(solver_->step_count()) : nullptr;
  probes_.reset();
  hybrid_.reset();
  solver_.reset();
  malloc_trim(0);
  try {
    MeasureOptions mo;
    mo.run = dir_;
    mo.front = holes_->body;  // empty: the panel's front facesheet
    const Measurements m = final_holes ? *final_holes : measure_run(mo);
    fmt::print("\n");
    print_measurements(m);
    write_measurements(m, dir_);
    for (const auto& [name, value] : headline_quantities(m)) measured[name] = value;
  } catch (const std::exception& e) {
    fmt::print(stderr, "hvi: the holes could not be measured: {}\n", e.what());
  }
  // The command's peak: the run's, or the measurement's where that is larger (the kernel's
  // counters can read a fraction of a MB lower after memory was returned).
  summary.insert("peak_memory_with_measure_bytes",
                 static_cast<std::int64_t>(std::max(peak_memory, peak_memory_bytes())));
}

}  // namespace

namespace {

// A rank but the first of a run spread over ranks: builds the same solver with its share of the
// points, and steps with rank 0 until it says stop. Signals are rank 0's to act on (it checkpoints
// and stops the others). A step that fails on every rank alike (SolverError::every_rank: a bad
// point on any rank, a collapsed time step) is rank 0's to report, and every rank ends with the
// run's failure code; any other error here ends the job.
int follow_scene(const scene::Scene& scene, const RunOptions& options) {
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGTERM, SIG_IGN);
  if (options.threads > 0) omp_set_num_threads(options.threads);
  std::unique_ptr<mpm::Solver> solver;
  // Every rank steps the far field's nodes and a share of its element work; rank 0 writes it.
  std::unique_ptr<Hybrid> hybrid;
  try {
    solver = make_solver(scene);
    solver->distribute(options.ranks);
    hybrid = make_hybrid(scene, *solver);
    // Its share of the points (rank 0 samples its own alike); a resumed run reads its share of
    // the checkpoint instead, when rank 0 restores it.
    if (!options.resume) {
      add_bodies(scene, *solver, options.max_memory, nullptr,
                 {options.ranks->rank(), options.ranks->size()});
      if (hybrid) hybrid->record_reference_positions(*solver);
    }
  } catch (const std::exception&) {  // rank 0 refuses the same scene and says why
    solver.reset();
  }
  if (!solver) {
    std::vector<double> message;
    do options.ranks->broadcast(message);  // until rank 0 says stop
    while (message.at(0) != 0.0);
    return input_error;
  }
  // Rank 0 says which file to write a part of: a snapshot's index, or the checkpoint.
  const auto write = [&](double what) {
    const fs::path checkpoint = options.out / "checkpoint.h5";
    if (what == mpm::io::checkpoint_file)
      mpm::io::write_checkpoint(checkpoint, *solver, {}, options.shared_files);
    else
      mpm::io::write_snapshot_file(
          mpm::io::SnapshotWriter::temporary(
              options.out / mpm::io::SnapshotWriter::file_name(static_cast<std::size_t>(what))),
          *solver, options.shared_files);
  };
  try {
    const auto measure = [&] {
      (void)solver->max_pairs_over_ranks(point_extrema(scene.measures, *solver));
    };
    const auto restore = [&] {
      mpm::io::read_checkpoint(options.out / "checkpoint.h5", *solver);
      if (hybrid) hybrid->restore_zone();
    };
    const auto grow = [&] { (void)hybrid->grow(*solver); };
    if (solver->follow({restore, write, measure, grow})) return run_failed;  // rank 0 said why
  } catch (const std::exception& e) {
    fmt::print(stderr, "hvi: rank {}: the run failed: {}\n", options.ranks->rank(), e.what());
    std::fflush(nullptr);
    options.ranks->abort(run_failed);
  }
  return success;
}

// Ends the other ranks' follow_scene() when rank 0's driver returns, however it returns.
class FollowersStop {
 public:
  explicit FollowersStop(mpm::Communicator& ranks) : ranks_(ranks) {}
  ~FollowersStop() { mpm::Solver::stop_followers(ranks_); }
  FollowersStop(const FollowersStop&) = delete;
  FollowersStop& operator=(const FollowersStop&) = delete;

 private:
  mpm::Communicator& ranks_;
};

// The phases of a run, in order; each returns at the first error with its exit code.
int lead_scene(const scene::Scene& scene, const RunOptions& options) {
  SceneRun run(scene, options);
  if (const int code = run.check_directory(); code != success) return code;
  if (const int code = run.build(); code != success) return code;  // nothing written yet
  run.prepare_directory();
  run.open_logs();
  if (const int code = run.start(); code != success) return code;
  const int code = run.time_loop();
  if (code == run_failed) return code;
  return run.finish(code);
}

}  // namespace

int run_scene(const scene::Scene& scene, const RunOptions& options) {
  if (!options.ranks) return lead_scene(scene, options);
  if (options.ranks->rank() != 0) return follow_scene(scene, options);
  const FollowersStop stop(*options.ranks);
  try {
    return lead_scene(scene, options);
  } catch (const std::exception& e) {
    // The other ranks may be waiting inside a collective call (a shared file's write): the job
    // ends here.
    fmt::print(stderr, "hvi: the run failed: {}\n", e.what());
    std::fflush(nullptr);
    options.ranks->abort(run_failed);
  }
  return run_failed;  // not reached: abort() ends the job
}

}  // namespace hvi::driver
