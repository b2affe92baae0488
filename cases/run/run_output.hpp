#pragma once
// What a run says and writes besides its snapshots: the progress line, the disk estimate, the
// removals, run.json and resumes.jsonl, timing.csv. Internal to run.cpp.
#include <array>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "cases/run/run.hpp"
#include "mpm/phase_timer.hpp"
#include "mpm/solver.hpp"

namespace hvi::driver {

// Progress: on a terminal one line rewritten in place; otherwise (a batch job's log) one line per
// snapshot written.
class Progress {
 public:
  explicit Progress(double end_time);
  void start(const mpm::Solver& s);
  void update(const mpm::Solver& s, bool force = false);
  void snapshot_written(const mpm::Solver& s);
  void finish();

 private:
  std::string line(const mpm::Solver& s, std::chrono::steady_clock::time_point now) const;
  double end_time_;
  bool tty_, active_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
  std::int64_t first_step_ = 0;
  double first_time_ = 0.0;
};

// What the rest of a run writes (output_size), against the space left on its output's disk. A
// warning, not an error: snapshots may be deleted as the run goes.
void report_disk(const std::filesystem::path& dir, const mpm::Solver& s, const scene::Scene& scene,
                 double next_output, bool fresh);

// The first removals in detail, then a count; `reported` carries the count between calls.
void report_removals(const mpm::Solver& solver, std::vector<mpm::RemovalEvent> events,
                     std::int64_t& reported);

void write_text(const std::filesystem::path& path, const std::string& text);

// run.json: what made the run, and the names behind the snapshots' integer `body` and `material`
// fields (index k is bodies[k], materials[k]).
void write_run_info(const std::filesystem::path& dir, const RunOptions& options, int threads,
                    const scene::Scene& scene, const std::vector<std::string>& body_names);

// resumes.jsonl: one line per resume, appended, so a run resumed or run on several times (perhaps
// by other builds) keeps what made each part: revision, command, threads, and the step and time
// it continued from.
void append_resume_record(const std::filesystem::path& dir, const RunOptions& options, int threads,
                          std::int64_t step, double time);

// The zone's sides (x0, y0, x1, y1) that `sides` names, as "x = 28 mm, y = 28 mm".
std::string side_names(const std::array<bool, 4>& sides, const std::array<double, 4>& zone);

void write_timing(const std::filesystem::path& dir, const mpm::PhaseTimer& timer);

}  // namespace hvi::driver
