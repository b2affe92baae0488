#include "cases/parallel/task_queue.hpp"

#include <chrono>
#include <cstdint>
#include <cstring>
#include <future>
#include <optional>
#include <thread>

#ifdef HVI_WITH_MPI
#include <mpi.h>
#endif

namespace hvi::parallel {

namespace {

void run_in_order(std::size_t n, const RunTask& run, const TaskFinished& finished) {
  for (std::size_t k = 0; k < n; ++k)
    if (!finished(k, run(k))) return;
}

#ifdef HVI_WITH_MPI

constexpr int report_tag = 7101, task_tag = 7102;
constexpr std::int64_t no_task = -1;
constexpr auto poll = std::chrono::milliseconds(10);

// What a rank sends rank 0 when it is free: the task it ended (no_task at first) and its result.
struct Report {
  std::int64_t task = no_task;
  std::int32_t code = 0;
  char status[24] = {};
};

Report report(std::int64_t task, const TaskResult& r) {
  Report rep;
  rep.task = task;
  rep.code = r.code;
  std::strncpy(rep.status, r.status.c_str(), sizeof rep.status - 1);
  return rep;
}

// MPI_Wait without spinning: Open MPI's blocking wait keeps a core busy.
void wait_idly(MPI_Request& request) {
  int done = 0;
  for (MPI_Test(&request, &done, MPI_STATUS_IGNORE); !done;
       MPI_Test(&request, &done, MPI_STATUS_IGNORE))
    std::this_thread::sleep_for(poll);
}

void work(const RunTask& run, MPI_Comm comm) {
  Report rep;
  for (;;) {
    MPI_Send(&rep, sizeof rep, MPI_BYTE, 0, report_tag, comm);
    std::int64_t task = no_task;
    MPI_Request request;
    MPI_Irecv(&task, 1, MPI_INT64_T, 0, task_tag, comm, &request);
    wait_idly(request);
    if (task == no_task) return;
    rep = report(task, run(static_cast<std::size_t>(task)));
  }
}

// Rank 0: hands out the tasks and runs its own share on a second thread.
class Dispatcher {
 public:
  Dispatcher(const Ranks& ranks, MPI_Comm comm, std::size_t n, const RunTask& run,
             const TaskFinished& finished)
      : workers_(ranks.size() - 1), comm_(comm), n_(n), run_(run), finished_(finished) {}

  void dispatch() {
    start_own();
    while (own_ || stopped_ < workers_) {
      const bool own_done = collect_own();
      const bool answered = answer_a_rank();
      if (!own_done && !answered) std::this_thread::sleep_for(poll);
    }
  }

 private:
  std::optional<std::size_t> next_task() {
    if (!handing_ || next_ >= n_) return std::nullopt;
    return next_++;
  }
  void ended(std::size_t k, const TaskResult& r) {
    const bool go_on = finished_(k, r);
    handing_ = handing_ && go_on;
  }
  void start_own() {
    own_ = next_task();
    if (own_) own_result_ = std::async(std::launch::async, run_, *own_);
  }
  bool collect_own() {
    if (!own_ || own_result_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
      return false;
    const std::size_t k = *own_;
    ended(k, own_result_.get());
    start_own();
    return true;
  }
  bool answer_a_rank() {
    int waiting = 0;
    MPI_Status probe;
    MPI_Iprobe(MPI_ANY_SOURCE, report_tag, comm_, &waiting, &probe);
    if (!waiting) return false;
    Report rep;
    MPI_Recv(&rep, sizeof rep, MPI_BYTE, probe.MPI_SOURCE, report_tag, comm_, MPI_STATUS_IGNORE);
    if (rep.task != no_task)
      ended(static_cast<std::size_t>(rep.task), TaskResult{rep.code, rep.status});
    const std::optional<std::size_t> k = next_task();
    const std::int64_t task = k ? static_cast<std::int64_t>(*k) : no_task;
    if (!k) ++stopped_;
    MPI_Send(&task, 1, MPI_INT64_T, probe.MPI_SOURCE, task_tag, comm_);
    return true;
  }

  const int workers_;
  const MPI_Comm comm_;
  const std::size_t n_;
  const RunTask& run_;
  const TaskFinished& finished_;
  std::size_t next_ = 0;
  bool handing_ = true;
  int stopped_ = 0;  // ranks told there is nothing more
  std::optional<std::size_t> own_;
  std::future<TaskResult> own_result_;
};

#endif

}  // namespace

void share_tasks([[maybe_unused]] const Ranks& ranks, std::size_t n, const RunTask& run,
                 const TaskFinished& finished) {
#ifdef HVI_WITH_MPI
  if (ranks.size() > 1) {
    // A communicator of this call's own: a rank that has left one call and asks for work in the
    // next is not heard by rank 0 still in the first.
    MPI_Comm comm;
    MPI_Comm_dup(MPI_COMM_WORLD, &comm);
    if (ranks.root())
      Dispatcher(ranks, comm, n, run, finished).dispatch();
    else
      work(run, comm);
    // A rank told there is nothing more may be the first done: every rank waits for the last
    // task to end, so that each then reads every task's output (hvi ballistic-limit's rounds).
    MPI_Request all_done;
    MPI_Ibarrier(comm, &all_done);
    wait_idly(all_done);
    MPI_Comm_free(&comm);
    return;
  }
#endif
  run_in_order(n, run, finished);
}

}  // namespace hvi::parallel
