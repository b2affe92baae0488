#pragma once
// One HDF5 file written by every rank of an MPI job at once (mpm/io/hdf5_file.hpp): MPI-IO over
// MPI_COMM_WORLD, collective transfers. Needs an HDF5 built for MPI (Debian's
// libhdf5-openmpi-dev, which CMake prefers when hvi is built with MPI).
#include <memory>

#include "mpm/io/hdf5_file.hpp"

namespace hvi::parallel {

class Ranks;

// The job's shared file access; nullptr when this process is the one rank of no job, or when
// the HDF5 hvi is built with cannot share a file (the driver then gathers the points on rank 0
// to write).
std::unique_ptr<mpm::io::SharedFileAccess> make_file_access(const Ranks& ranks);

}  // namespace hvi::parallel
