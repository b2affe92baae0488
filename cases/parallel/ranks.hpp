#pragma once
// The ranks of an MPI job that this process is one of.
//
// hvi joins an MPI job only when an MPI launcher started it (mpirun, mpiexec, srun: their
// environment says so) and it was built with MPI. Otherwise it is the one rank of a job of one, and
// no MPI function is called: a plain `hvi run` pays nothing for MPI. The child runs a rank starts
// (`hvi sweep` runs each run as a child `hvi run`) are told they are plain processes, so that they
// do not try to join the job of their parent.
namespace hvi::parallel {

class Ranks {
 public:
  // Joins the job (MPI_Init_thread, funneled) if launched by one; one rank otherwise.
  Ranks(int& argc, char**& argv);
  ~Ranks();  // MPI_Finalize, if joined
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool joined() const { return joined_; }

  static bool built_with_mpi();
  // Whether an MPI launcher started this process (its environment names a world size).
  static bool launched_by_mpi();

 private:
  int rank_ = 0, size_ = 1;
  bool joined_ = false;
};

}  // namespace hvi::parallel
