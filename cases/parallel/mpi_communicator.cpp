#include "cases/parallel/mpi_communicator.hpp"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "cases/parallel/ranks.hpp"

#ifdef HVI_WITH_MPI
#include <mpi.h>
#endif

namespace hvi::parallel {

#ifdef HVI_WITH_MPI
namespace {

// Messages are cut in pieces of at most this many doubles (MPI counts are int).
constexpr std::size_t piece = std::size_t{1} << 28;

class MpiCommunicator final : public mpm::Communicator {
 public:
  MpiCommunicator(int rank, int size) : rank_(rank), size_(size) {}
  int rank() const override { return rank_; }
  int size() const override { return size_; }

  // The sizes all-to-all, then the buffers rank to rank (non-blocking, in pieces).
  std::vector<std::vector<double>> exchange(std::vector<std::vector<double>> to) override {
    const auto n = static_cast<std::size_t>(size_);
    std::vector<std::uint64_t> send_size(n), receive_size(n);
    for (std::size_t r = 0; r < n; ++r) send_size[r] = to[r].size();
    MPI_Alltoall(send_size.data(), 1, MPI_UINT64_T, receive_size.data(), 1, MPI_UINT64_T,
                 MPI_COMM_WORLD);
    std::vector<std::vector<double>> from(n);
    std::vector<MPI_Request> requests;
    for (std::size_t r = 0; r < n; ++r) {
      if (static_cast<int>(r) == rank_) continue;
      from[r].resize(receive_size[r]);
      post(from[r].data(), from[r].size(), static_cast<int>(r), requests, true);
      post(to[r].data(), to[r].size(), static_cast<int>(r), requests, false);
    }
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    from[static_cast<std::size_t>(rank_)] = std::move(to[static_cast<std::size_t>(rank_)]);
    return from;
  }

  std::vector<std::vector<double>> all_gather(const std::vector<double>& mine) override {
    if (mine.size() > static_cast<std::size_t>(INT_MAX))
      throw std::length_error("all_gather: more than 2^31 values from one rank");
    const int count = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(counts.size(), 0);
    MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
    std::size_t total = 0;
    for (std::size_t r = 0; r < counts.size(); ++r) {
      if (total > static_cast<std::size_t>(INT_MAX))
        throw std::length_error("all_gather: more than 2^31 values in all");
      offsets[r] = static_cast<int>(total);
      total += static_cast<std::size_t>(counts[r]);
    }
    std::vector<double> all(total);
    MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                   MPI_DOUBLE, MPI_COMM_WORLD);
    std::vector<std::vector<double>> out(counts.size());
    for (std::size_t r = 0; r < counts.size(); ++r)
      out[r].assign(all.begin() + offsets[r], all.begin() + offsets[r] + counts[r]);
    return out;
  }

  double max(double x) override {
    double m = x;
    MPI_Allreduce(&x, &m, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return m;
  }

  void broadcast(std::vector<double>& data) override {
    std::uint64_t size = data.size();
    MPI_Bcast(&size, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    data.resize(size);
    for (std::size_t first = 0; first < size; first += piece)
      MPI_Bcast(data.data() + first, static_cast<int>(std::min(piece, size - first)), MPI_DOUBLE, 0,
                MPI_COMM_WORLD);
  }

  [[noreturn]] void abort(int code) override {
    MPI_Abort(MPI_COMM_WORLD, code);
    std::abort();  // MPI_Abort does not return
  }

 private:
  // Posts the messages of one buffer, piece by piece (tag = the piece's number).
  static void post(double* data, std::size_t size, int peer, std::vector<MPI_Request>& requests,
                   bool receive) {
    for (std::size_t first = 0, tag = 0; first < size; first += piece, ++tag) {
      const int count = static_cast<int>(std::min(piece, size - first));
      MPI_Request r;
      if (receive)
        MPI_Irecv(data + first, count, MPI_DOUBLE, peer, static_cast<int>(tag), MPI_COMM_WORLD, &r);
      else
        MPI_Isend(data + first, count, MPI_DOUBLE, peer, static_cast<int>(tag), MPI_COMM_WORLD, &r);
      requests.push_back(r);
    }
  }
  int rank_, size_;
};

}  // namespace

std::unique_ptr<mpm::Communicator> make_communicator(const Ranks& ranks) {
  if (!ranks.joined()) return nullptr;
  return std::make_unique<MpiCommunicator>(ranks.rank(), ranks.size());
}
#else
std::unique_ptr<mpm::Communicator> make_communicator(const Ranks&) {
  return nullptr;
}
#endif

}  // namespace hvi::parallel
