#pragma once
// Reading a run's particle snapshots into plain arrays (mpm/io/snapshot_writer.hpp writes them,
// and SnapshotWriter::files lists them: DIR/snapshots/particles_NNNNNN.h5, one dataset per field,
// particles in id order; attributes time and step).
#include <cstdint>
#include <filesystem>
#include <vector>

#include "analysis/particle_set.hpp"

namespace hvi::analysis {

struct Snapshot {
  std::filesystem::path file;
  double time = 0;  // s
  std::int64_t step = 0;
  ParticleData particles;       // position, id, body, mass, volume, failed, velocity (if written)
  std::vector<double> volume0;  // initial volume, m^3 (volume / volume_ratio)
};

// Throws std::runtime_error (or mpm::io::Hdf5Error) for a missing or malformed file.
Snapshot read_snapshot(const std::filesystem::path& file);

}  // namespace hvi::analysis
