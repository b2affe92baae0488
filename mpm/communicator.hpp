#pragma once
// The processes (ranks) one run is spread over, as the solver sees them: a few collective
// operations on buffers of doubles. The solver knows no MPI; a driver that joined an MPI job
// hands it an implementation (cases/parallel/mpi_communicator.hpp). Without one, a run is one rank
// and calls none of this.
#include <vector>

namespace hvi::mpm {

class Communicator {
 public:
  virtual ~Communicator() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Collective: to[r] goes to rank r (to[rank()] is handed back as it is); returns from, with
  // from[r] what rank r sent to this one.
  virtual std::vector<std::vector<double>> exchange(std::vector<std::vector<double>> to) = 0;
  // Collective: every rank's `mine`, indexed by rank, on every rank.
  virtual std::vector<std::vector<double>> all_gather(const std::vector<double>& mine) = 0;
  // Collective: the largest of every rank's x (exact, so the same on every rank).
  virtual double max(double x) = 0;
  // Collective: rank 0's `data` (any size) on every rank.
  virtual void broadcast(std::vector<double>& data) = 0;
  // Ends every rank of the job at once with `code` (a rank that cannot go on while the others
  // wait for it).
  [[noreturn]] virtual void abort(int code) = 0;
};

}  // namespace hvi::mpm
