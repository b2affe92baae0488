// A run killed with SIGKILL (no chance to checkpoint) at any moment loses at most one checkpoint
// interval: resumed with `hvi run --resume`, the demo on 0.8 mm cells, killed twice at different
// moments (during steps, snapshot writes or checkpoint writes, wherever the times fall), ends with
// snapshots and energy.csv byte for byte those of an uninterrupted run, and no half-written file.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/files.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::string hvi = HVI_BINARY;
const std::vector<std::string> demo = {
    "run",       std::string(HVI_SOURCE_DIR) + "/cases/demo.toml",
    "--set",     "grid.cell_size=0.8mm",
    "--set",     "run.end_time=3us",
    "--set",     "output.interval=0.5us",
    "--set",     "output.checkpoint_interval=0.2us",
    "--threads", "1"};

// Starts `hvi args...` with its output to `log`; returns its pid.
pid_t start(std::vector<std::string> args, const fs::path& log) {
  args.insert(args.begin(), hvi);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = -1;
  posix_spawn(&pid, hvi.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::vector<std::string> with_out(std::vector<std::string> args, const fs::path& dir) {
  args.insert(args.end(), {"--out", dir.string()});
  return args;
}

using hvi::test::read;

TEST(KillResume, KilledTwiceTheDemoEndsAsIfNeverKilled) {
  const fs::path root = fs::path(testing::TempDir()) / "hvi_kill_resume";
  fs::remove_all(root);
  fs::create_directories(root);
  const fs::path log = root / "log.txt";
  const auto t0 = Clock::now();
  ASSERT_EQ(wait_for(start(with_out(demo, root / "whole"), log)), 0) << read(log);
  const double whole = std::chrono::duration<double>(Clock::now() - t0).count();

  // Killed at 40% of the uninterrupted wall time, resumed, killed again 30% later, resumed to
  // the end. A kill before the first checkpoint starts the run again.
  const fs::path dir = root / "killed";
  auto kill_after = [&](std::vector<std::string> args, double fraction) {
    const pid_t pid = start(std::move(args), log);
    std::this_thread::sleep_for(std::chrono::duration<double>(fraction * whole));
    kill(pid, SIGKILL);
    wait_for(pid);
  };
  kill_after(with_out(demo, dir), 0.4);
  const auto resume = [&]() -> std::vector<std::string> {
    if (fs::exists(dir / "checkpoint.h5")) return {"run", "--resume", dir.string()};
    auto again = with_out(demo, dir);
    again.push_back("--overwrite");
    return again;
  };
  kill_after(resume(), 0.3);
  ASSERT_EQ(wait_for(start(resume(), log)), 0) << read(log);

  for (const auto& entry : fs::recursive_directory_iterator(dir))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();  // no half-written file
  std::size_t compared = 0;
  for (const auto& entry : fs::directory_iterator(root / "whole" / "snapshots")) {
    const fs::path other = dir / "snapshots" / entry.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_EQ(read(entry.path()), read(other)) << entry.path().filename();
    ++compared;
  }
  EXPECT_EQ(compared, 7u);  // t = 0, 0.5, ..., 3 us
  EXPECT_EQ(read(root / "whole" / "energy.csv"), read(dir / "energy.csv"));
}

}  // namespace
