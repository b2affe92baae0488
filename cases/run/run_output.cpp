#include "cases/run/run_output.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "hvi_git_revision.hpp"
#include "mpm/io/checkpoint.hpp"
#include "mpm/io/snapshot_writer.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;

namespace {
std::string format_duration(double seconds) {
  const auto s = static_cast<long>(seconds);
  return fmt::format("{}:{:02d}:{:02d}", s / 3600, (s / 60) % 60, s % 60);
}
}  // namespace

Progress::Progress(double end_time) : end_time_(end_time), tty_(isatty(STDERR_FILENO)) {}

void Progress::update(const mpm::Solver& s, bool force) {
  if (!tty_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_ < std::chrono::milliseconds(500)) return;
  fmt::print(stderr, "\r{}   ", line(s, now));
  std::fflush(stderr);
  last_ = now;
  active_ = true;
}

void Progress::snapshot_written(const mpm::Solver& s) {
  if (tty_) return;
  const auto now = std::chrono::steady_clock::now();
  fmt::print("{}  (wall {})\n", line(s, now),
             format_duration(std::chrono::duration<double>(now - start_).count()));
  std::fflush(stdout);
}

void Progress::start(const mpm::Solver& s) {
  first_step_ = s.step_count();
  first_time_ = s.time();
}

void Progress::finish() {
  if (active_) fmt::print(stderr, "\n");
  active_ = false;
}

std::string Progress::line(const mpm::Solver& s, std::chrono::steady_clock::time_point now) const {
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double steps_per_s = (s.step_count() - first_step_) / std::max(wall, 1e-9);
  const double sim_rate = (s.time() - first_time_) / std::max(wall, 1e-9);
  const double eta = sim_rate > 0 ? (end_time_ - s.time()) / sim_rate : 0.0;
  const std::string rate =
      steps_per_s >= 100 ? fmt::format("{:.0f}", steps_per_s) : fmt::format("{:.3g}", steps_per_s);
  return fmt::format("  t = {:.4g} / {:.4g} s  step {}  dt {:.3g} s  {} steps/s  ETA {}", s.time(),
                     end_time_, s.step_count(), s.next_time_step(), rate, format_duration(eta));
}

void report_disk(const fs::path& dir, const mpm::Solver& s, const scene::Scene& scene,
                 double next_output, bool fresh) {
  const OutputSize o = output_size(s, scene, next_output, fresh);
  std::error_code error;
  const auto space = fs::space(dir, error);
  fmt::print(
      "  output: {:.0f} snapshot{} of about {} and a checkpoint of {} to come, {} in all{}\n",
      o.snapshots, o.snapshots == 1.0 ? "" : "s", format_bytes(o.snapshot),
      format_bytes(o.checkpoint), format_bytes(o.total),
      error ? std::string()
            : fmt::format("; {} free on the disk",
                          format_bytes(static_cast<double>(space.available))));
  if (!error && o.total > static_cast<double>(space.available))
    fmt::print(
        "  warning: the output needs about {} and {}'s disk has {} free: the run will stop when "
        "the disk is "
        "full (its last checkpoint kept, to resume from); free space, keep only the newest "
        "snapshots "
        "(output.keep_snapshots), or raise output.interval\n",
        format_bytes(o.total), dir.string(), format_bytes(static_cast<double>(space.available)));
}

void report_removals(const mpm::Solver& solver, std::vector<mpm::RemovalEvent> events,
                     std::int64_t& reported) {
  constexpr std::int64_t detailed = 5;
  for (const auto& e : events) {
    if (reported < detailed)
      fmt::print(
          "  step {}, t = {:.6g} s: particle {} (body '{}', material '{}') left the grid at "
          "({:.4g}, {:.4g}, {:.4g}) m; removed with mass {:.4g} kg, kinetic energy {:.4g} J\n",
          e.step, e.time, e.id, solver.body_names().at(e.body),
          solver.materials().at(e.material)->name(), e.position[0], e.position[1], e.position[2],
          e.mass,
          0.5 * e.mass *
              (e.velocity[0] * e.velocity[0] + e.velocity[1] * e.velocity[1] +
               e.velocity[2] * e.velocity[2]));
    else if (reported == detailed)
      fmt::print("  (further removals are counted in energy.csv and the summary)\n");
    ++reported;
  }
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

void write_run_info(const fs::path& dir, const RunOptions& options, int threads,
                    const scene::Scene& scene, const std::vector<std::string>& body_names) {
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

void append_resume_record(const fs::path& dir, const RunOptions& options, int threads,
                          std::int64_t step, double time) {
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

std::string side_names(const std::array<bool, 4>& sides, const std::array<double, 4>& zone) {
  std::string names;
  for (int side = 0; side < 4; ++side)
    if (sides[side])
      names += fmt::format("{}{} = {:.4g} mm", names.empty() ? "" : ", ", side % 2 ? 'y' : 'x',
                           1e3 * zone[side]);
  return names;
}

void write_timing(const fs::path& dir, const mpm::PhaseTimer& timer) {
  std::ofstream out(dir / "timing.csv");
  out << "phase,seconds,calls\n";
  for (const auto& e : timer.entries())
    out << fmt::format("\"{}\",{:.6f},{}\n", e.name, e.seconds, e.calls);
}

std::string format_bytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.3g} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.3g} MB", bytes / 1e6);
  return fmt::format("{:.3g} kB", bytes / 1e3);
}

OutputSize output_size(const mpm::Solver& s, const scene::Scene& scene, double next_output,
                       bool fresh) {
  OutputSize o;
  const double end = scene.end_time;
  o.snapshots = 1.0;  // the last step's
  if (next_output < end * (1 - 1e-12))
    o.snapshots += std::ceil((end - next_output) / scene.output_interval - 1e-9);
  // Keeping only the newest N, at most N + 1 besides the first are on the disk at once (the newest
  // is written before the oldest goes); the count from t = 0 (next_output 0) includes the first.
  if (scene.keep_snapshots > 0)
    o.snapshots = std::min(o.snapshots,
                           static_cast<double>(scene.keep_snapshots) + (next_output > 0 ? 1 : 2));
  o.snapshot =
      static_cast<double>(mpm::io::snapshot_bytes_per_particle(s.particles()) * s.point_count());
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

}  // namespace hvi::driver
