#include "cases/parallel/mpi_file_access.hpp"

#include <hdf5.h>

#include "cases/parallel/ranks.hpp"

namespace hvi::parallel {

#if defined(H5_HAVE_PARALLEL) && defined(HVI_WITH_MPI)
namespace {

class MpiFileAccess final : public mpm::io::SharedFileAccess {
 public:
  void set_file_access(std::int64_t fapl) const override {
    H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL);
  }
  // Collective: the ranks' rows reach the file in one MPI-IO call, not one each.
  void set_transfer(std::int64_t dxpl) const override {
    H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE);
  }
};

}  // namespace

std::unique_ptr<mpm::io::SharedFileAccess> make_file_access(const Ranks& ranks) {
  if (!ranks.joined() || ranks.size() < 2) return nullptr;
  return std::make_unique<MpiFileAccess>();
}
#else
std::unique_ptr<mpm::io::SharedFileAccess> make_file_access(const Ranks&) {
  return nullptr;
}
#endif

}  // namespace hvi::parallel
