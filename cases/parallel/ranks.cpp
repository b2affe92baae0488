#include "cases/parallel/ranks.hpp"

#include <cstdlib>

#ifdef HVI_WITH_MPI
#include <mpi.h>
#endif

namespace hvi::parallel {

namespace {

// Set by a rank for the processes it starts: they are plain processes, whatever the environment
// they inherit says of the job.
constexpr const char* plain_process = "HVI_PLAIN_PROCESS";

}  // namespace

bool Ranks::built_with_mpi() {
#ifdef HVI_WITH_MPI
  return true;
#else
  return false;
#endif
}

bool Ranks::launched_by_mpi() {
  if (std::getenv(plain_process)) return false;
  // Open MPI's mpirun, MPICH's and Intel MPI's Hydra (PMI), PMIx launchers and Slurm's srun.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(name)) return true;
  return false;
}

Ranks::Ranks([[maybe_unused]] int& argc, [[maybe_unused]] char**& argv) {
#ifdef HVI_WITH_MPI
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  joined_ = true;
  setenv(plain_process, "1", 1);
#endif
}

Ranks::~Ranks() {
#ifdef HVI_WITH_MPI
  if (joined_) MPI_Finalize();
#endif
}

}  // namespace hvi::parallel
