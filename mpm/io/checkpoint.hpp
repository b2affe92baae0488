#pragma once
// Complete restart files: every non-scratch particle field, points in id order (the order a run
// on any rank count writes, id_slabs.hpp; no sum of the solver depends on the order of its points
// within a material), the solver's state and any values the caller wants back (output schedule,
// ...). Written to a temporary file and renamed, so a crash while writing leaves the previous
// checkpoint intact. Every dataset carries a Fletcher-32 checksum: a damaged checkpoint fails to
// read.
#include <filesystem>
#include <map>
#include <string>

#include "mpm/io/hdf5_file.hpp"
#include "mpm/solver.hpp"

namespace hvi::mpm::io {

using CheckpointExtras = std::map<std::string, double>;

// With `shared`, on every rank of a run spread over ranks: rank 0 (whose driver calls it) tells the
// others to join in (Solver::announce_write(checkpoint_file)); they call it with no extras. Each
// writes the rows of its slab of ids; rank 0 adds the attributes and renames the file.
void write_checkpoint(const std::filesystem::path& path, const Solver& solver,
                      const CheckpointExtras& extras, const SharedFileAccess* shared = nullptr);
// What Solver::announce_write tells the other ranks to write for a checkpoint (a snapshot: its
// index, from 0).
constexpr double checkpoint_file = -1.0;
// Where a checkpoint is written until it is complete.
std::filesystem::path checkpoint_temporary(const std::filesystem::path& path);

// The bytes of the datasets write_checkpoint writes for `solver` now (8 a value: the particles'
// non-scratch fields and the couplings' state); a file adds a few kB of HDF5 metadata.
std::size_t checkpoint_bytes(const Solver& solver);

// Loads particles and state into a solver constructed from the same scene (same materials,
// bodies, grid) and calls Solver::restore. Each rank of a run spread over ranks reads an equal
// share of the points, whatever the rank count that wrote the file. Returns the caller's extras.
CheckpointExtras read_checkpoint(const std::filesystem::path& path, Solver& solver);

}  // namespace hvi::mpm::io
