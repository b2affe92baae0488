#pragma once
// The solver's view of an MPI job's ranks (mpm/communicator.hpp) over MPI_COMM_WORLD. Only
// built with MPI; make one with Ranks::communicator().
#include <memory>

#include "mpm/communicator.hpp"

namespace hvi::parallel {

class Ranks;

// The job's ranks as a communicator, or nullptr when this process is the one rank of no job.
std::unique_ptr<mpm::Communicator> make_communicator(const Ranks& ranks);

}  // namespace hvi::parallel
