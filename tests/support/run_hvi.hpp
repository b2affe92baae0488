#pragma once
// Running the hvi binary from a test and reading what a run wrote: shared by the tests that drive
// the command line end to end.
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/files.hpp"

namespace hvi::test {

namespace fs = std::filesystem;

// A fresh directory for a run, under the test's temporary directory.
inline fs::path scratch(const std::string& name) {
  const fs::path p = fs::path(testing::TempDir()) / ("hvi_cli_" + name);
  fs::remove_all(p);
  return p;
}

// Runs hvi with `args`; returns its exit code, its stderr in `err` and its stdout in `out` (when
// given).
inline int run(const std::string& args, std::string* err = nullptr, std::string* out = nullptr) {
  // Files of this test alone: ctest runs the tests of a file in parallel.
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  const std::string test = std::string(info->test_suite_name()) + "." + info->name();
  const fs::path e = fs::path(testing::TempDir()) / ("hvi_stderr_" + test + ".txt");
  const fs::path o = fs::path(testing::TempDir()) / ("hvi_stdout_" + test + ".txt");
  const std::string cmd = std::string(HVI_BINARY) + " " + args + " > " +
                          (out ? o.string() : std::string("/dev/null")) + " 2> " + e.string();
  const int status = std::system(cmd.c_str());
  if (err) *err = read(e);
  if (out) *out = read(o);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Runs hvi with `args`, its stdout and stderr both into `log`; returns its exit code.
inline int run_logged(const std::string& args, const fs::path& log) {
  const std::string cmd = std::string(HVI_BINARY) + " " + args + " > " + log.string() + " 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A number of a run's summary.toml, at the top level or in [measures] (NaN when absent).
inline double summary_number(const fs::path& run_dir, const std::string& key) {
  std::string summary = read(run_dir / "summary.toml");
  summary.insert(summary.begin(), '\n');
  std::string line_start = key;
  line_start.insert(line_start.begin(), '\n');
  line_start.append(" = ");
  const auto at = summary.find(line_start);
  return at == std::string::npos ? std::nan("") : std::stod(summary.substr(at + line_start.size()));
}

// The rows of a CSV file of numbers (energy.csv, probes.csv); its header line in `header`.
inline std::vector<std::vector<double>> csv_rows(const fs::path& p, std::string* header = nullptr) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  if (header) *header = line;
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

// Every snapshot file, energy.csv and the XDMF index of two runs are byte-identical; `a` has
// `snapshots` snapshot files (by default the scene's t = 0, 1, 2, 3, 4 us).
inline void expect_same_output(const fs::path& a, const fs::path& b, int snapshots = 5) {
  EXPECT_TRUE(read(a / "energy.csv") == read(b / "energy.csv")) << "energy.csv differs";
  EXPECT_TRUE(read(a / "particles.xmf") == read(b / "particles.xmf")) << "particles.xmf differs";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(a / "snapshots")) {
    const fs::path other = b / "snapshots" / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(read(entry.path()) == read(other)) << entry.path().filename() << " differs";
    ++files;
  }
  EXPECT_EQ(files, snapshots);
}

}  // namespace hvi::test
