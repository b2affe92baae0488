#pragma once
// Complete restart files: every non-scratch particle field in its current array order (so a
// resumed run adds floating-point numbers in exactly the same order as an uninterrupted one), the
// solver's state and any values the caller wants back (output schedule, ...). Written to a
// temporary file and renamed, so a crash while writing leaves the previous checkpoint intact.
// Every dataset carries a Fletcher-32 checksum: a damaged checkpoint fails to read.
#include <filesystem>
#include <map>
#include <string>

#include "mpm/solver.hpp"

namespace hvi::mpm::io {

using CheckpointExtras = std::map<std::string, double>;

void write_checkpoint(const std::filesystem::path& path, const Solver& solver,
                      const CheckpointExtras& extras);

// The bytes of the datasets write_checkpoint writes for `solver` now (8 a value: the particles'
// non-scratch fields and the couplings' state); a file adds a few kB of HDF5 metadata.
std::size_t checkpoint_bytes(const Solver& solver);

// Loads particles and state into a solver constructed from the same scene (same materials,
// bodies, grid) and calls Solver::restore. Returns the caller's extras.
CheckpointExtras read_checkpoint(const std::filesystem::path& path, Solver& solver);

}  // namespace hvi::mpm::io
