#pragma once
// The points of a run in id order, the order of every snapshot and checkpoint, cut into slabs of
// consecutive rows, one per rank: rank r writes the rows of the ids in [r M / R, (r + 1) M / R),
// M = 1 + the largest id, R ranks. A point's values travel to the rank of its slab (one exchange
// per field), so no rank ever holds every point, and the file holds the same rows in the same
// order for any rank count. On one rank the slab is every point, sorted by id.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "mpm/communicator.hpp"
#include "mpm/io/hdf5_file.hpp"
#include "mpm/particles.hpp"

namespace hvi::mpm::io {

// The non-scratch fields of P that `keep` keeps, by name: the order in which every rank creates
// the datasets of a shared file (ranks may have declared their fields in different orders).
template <class Keep>
std::vector<const RealField*> by_name(const Particles& P, Keep keep) {
  std::vector<const RealField*> out;
  for (const auto& f : P.real_fields())
    if (!f.scratch && keep(f)) out.push_back(&f);
  std::sort(out.begin(), out.end(), [](auto a, auto b) { return a->name < b->name; });
  return out;
}

class IdSlabs {
 public:
  // Collective over `comm` (null: one rank).
  IdSlabs(const Particles& P, Communicator* comm);

  // This rank's rows of the file.
  Hdf5File::Rows rows() const { return rows_; }

  // This rank's rows of a field of `columns` values a point, `field[p * columns + c]` for its
  // points p (collective).
  std::vector<double> gather(const std::vector<double>& field, int columns) const;
  std::vector<std::int64_t> gather(const std::vector<std::int64_t>& field) const;

 private:
  std::vector<double> route(const std::vector<double>& field, int columns) const;
  Communicator* comm_;
  std::vector<std::vector<std::uint32_t>> sent_;  // per rank, the points sent there, in order
  std::vector<std::uint32_t> order_;              // the received points, in id order
  Hdf5File::Rows rows_{0, 0, 0};
};

}  // namespace hvi::mpm::io
