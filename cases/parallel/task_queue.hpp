#pragma once
// Independent tasks handed out among the ranks of a job: the runs of a study (hvi sweep). Rank 0
// hands the tasks out in order, one at a time, each to the first rank that is free, so that a
// study of runs of unequal cost keeps every rank busy; it runs tasks itself between hand-outs.
// Waiting ranks sleep between polls instead of spinning, so that a rank waiting for its next task
// leaves its cores to the runs under way.
#include <cstddef>
#include <functional>
#include <string>

#include "cases/parallel/ranks.hpp"

namespace hvi::parallel {

// How a task ended: an exit code and a few words (at most 23 characters travel between ranks).
struct TaskResult {
  int code = 0;
  std::string status;
};

// Runs task k on the calling rank. On rank 0 it runs on a thread of its own and must not call MPI.
using RunTask = std::function<TaskResult(std::size_t k)>;
// Called on rank 0, on the thread that called share_tasks, as each task ends (in the order they
// end, whichever rank ran it). Returning false hands out no further task; those under way finish.
using TaskFinished = std::function<bool(std::size_t k, const TaskResult& result)>;

// Runs the tasks 0 .. n-1 once each over the ranks. Every rank calls it with the same n; it
// returns on every rank when all tasks handed out have ended (on every rank). On one rank: in
// order, here.
void share_tasks(const Ranks& ranks, std::size_t n, const RunTask& run,
                 const TaskFinished& finished);

}  // namespace hvi::parallel
