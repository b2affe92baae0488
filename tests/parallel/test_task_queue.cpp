// Tasks handed out among ranks (cases/parallel/task_queue.hpp): every task runs once, on whichever
// rank, and rank 0 hears of each with the result that rank gave it; when rank 0's callback says
// stop, no further task is handed out and those under way still report. Run plainly (one rank) and
// under mpirun on 3 ranks, where every rank takes a share. The tests' own main joins the job.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "cases/parallel/task_queue.hpp"

namespace hvi::parallel {
namespace {

const Ranks* ranks = nullptr;

// Task k takes 20-60 ms, so that on several ranks every rank is handed some, and gives 7 k and
// the rank that ran it.
TaskResult task(std::size_t k) {
  std::this_thread::sleep_for(std::chrono::milliseconds(20 * (1 + k % 3)));
  return {static_cast<int>(7 * k), std::to_string(ranks->rank())};
}

TEST(TaskQueue, EveryTaskRunsOnceAndRankZeroHearsOfIt) {
  const std::size_t n = 11;
  std::map<std::size_t, int> heard;
  std::set<std::string> runners;
  share_tasks(*ranks, n, task, [&](std::size_t k, const TaskResult& r) {
    ++heard[k];
    EXPECT_EQ(r.code, static_cast<int>(7 * k));
    runners.insert(r.status);
    return true;
  });
  if (!ranks->root()) return;  // rank 0 hears of every task
  ASSERT_EQ(heard.size(), n);
  for (const auto& [k, times] : heard) EXPECT_EQ(times, 1) << "task " << k;
  EXPECT_EQ(runners.size(), static_cast<std::size_t>(ranks->size()));  // every rank had a share
}

TEST(TaskQueue, AStopHandsOutNothingMore) {
  const std::size_t n = 40, stop_at = 3;
  std::set<std::size_t> heard;
  share_tasks(*ranks, n, task, [&](std::size_t k, const TaskResult&) {
    heard.insert(k);
    return k != stop_at;
  });
  if (!ranks->root()) return;
  EXPECT_TRUE(heard.contains(stop_at));
  // Handed out before the stop: the tasks up to stop_at, and at most one more per rank.
  EXPECT_LE(heard.size(), stop_at + 1 + static_cast<std::size_t>(ranks->size()));
  if (ranks->size() == 1) {
    EXPECT_EQ(heard.size(), stop_at + 1);  // in order, on one rank
  }
}

// Calls one after another keep apart: a rank that has left one call and asks for work in the next
// is not answered by rank 0 still in the first (it was, once, and two ranks left early).
TEST(TaskQueue, ConsecutiveCallsKeepApart) {
  for (int call = 0; call < 20; ++call) {
    std::map<std::size_t, int> heard;
    share_tasks(
        *ranks, 2,
        [](std::size_t k) {
          return TaskResult{static_cast<int>(k), ""};
        },
        [&](std::size_t k, const TaskResult&) {
          ++heard[k];
          return true;
        });
    if (ranks->root()) {
      ASSERT_EQ(heard.size(), 2u) << "call " << call;
      EXPECT_EQ(heard[0] + heard[1], 2) << "call " << call;
    }
  }
}

// Every rank returns only when every task has ended, on whichever rank: each task leaves a file
// as it ends (the last after 300 ms), and on return every rank finds all of them. Without the
// wait, a rank told there is nothing more returned while others still ran.
TEST(TaskQueue, EveryRankReturnsWhenEveryTaskHasEnded) {
  const std::size_t n = 5;
  const auto dir = std::filesystem::path(testing::TempDir()) /
                   ("hvi_task_queue_" + std::to_string(ranks->size()));
  if (ranks->root()) {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
  }
  share_tasks(
      *ranks, 1, [&](std::size_t) { return TaskResult{}; },
      [](std::size_t, const TaskResult&) { return true; });  // rank 0 made dir before this
  share_tasks(
      *ranks, n,
      [&](std::size_t k) {
        std::this_thread::sleep_for(std::chrono::milliseconds(k + 1 == n ? 300 : 10));
        std::ofstream(dir / std::to_string(k)) << k;
        return TaskResult{};
      },
      [](std::size_t, const TaskResult&) { return true; });
  for (std::size_t k = 0; k < n; ++k)
    EXPECT_TRUE(std::filesystem::exists(dir / std::to_string(k)))
        << "task " << k << ", rank " << ranks->rank();
}

}  // namespace
}  // namespace hvi::parallel

int main(int argc, char** argv) {
  const hvi::parallel::Ranks ranks(argc, argv);
  hvi::parallel::ranks = &ranks;
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
