#pragma once
// Runs of this executable as child processes (hvi convergence, hvi sweep): each run is an ordinary
// `hvi run` in its own directory with its own log, so it can be inspected, resumed or re-run
// alone, and its peak memory is its own.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace hvi::driver {

// Runs `hvi ARGS...` with stdout and stderr to `log` (appended to with `append`); returns the exit
// code (-1 if it did not exit normally). `launcher`, if not empty, goes before it as the shell
// splits it (an MPI launcher: `mpiexec -n 4`).
int run_child(const std::string& hvi, const std::vector<std::string>& args,
              const std::filesystem::path& log, bool append = false,
              const std::string& launcher = "");

// What a child run said in its log from byte `from` on (one invocation of a log that resumed runs
// append to): the lines that tell how it ended ("hvi: ..." other than the banner naming the scene
// `scene_file` or the run it resumes) and its warnings, without their indentation, so that the
// parent's console can show why a run failed or stopped without the log being opened.
struct ChildLog {
  std::vector<std::string> outcome;
  std::vector<std::string> warnings;
};
ChildLog read_child_log(const std::filesystem::path& log, std::uintmax_t from,
                        const std::string& scene_file);

// `s` in single quotes for the shell (a quote inside becomes '\'').
std::string shell_quote(const std::string& s);

// What a finished run's summary.toml says.
struct RunSummary {
  std::string status;  // finished, settled, stopped, interrupted; empty: no summary
  double wall_seconds = 0, peak_memory = 0, particles = 0, steps = 0, energy_balance = 0;
  // The command's peak with its hole measurement (NaN: no such measure, or an older run).
  double peak_memory_with_measure = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, double> measures;
  // Ended as the scene asks: at its end time, or once its rear sheet settled (settle.hpp).
  bool finished() const { return status == "finished" || status == "settled"; }
};
RunSummary read_run_summary(const std::filesystem::path& run_dir);

}  // namespace hvi::driver
