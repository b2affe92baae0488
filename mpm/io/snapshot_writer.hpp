#pragma once
// Particle snapshots for ParaView and Python: one HDF5 file per snapshot
// (DIR/snapshots/particles_NNNNNN.h5, one dataset per field, particles in id order) and an XDMF
// index DIR/particles.xmf that ParaView opens as a time series. Only fields that exist in the run
// are written, plus a few derived ones (density, pressure, von Mises stress, volume ratio).
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mpm/io/hdf5_file.hpp"
#include "mpm/solver.hpp"

namespace hvi::mpm::io {

// Writes one snapshot file (the datasets of a SnapshotWriter snapshot, no index). With `shared`,
// every rank of a run spread over ranks calls it at once and writes the rows of its slab of ids
// (id_slabs.hpp); without, the solver's points are all on this rank.
void write_snapshot_file(const std::filesystem::path& path, const Solver& solver,
                         const SharedFileAccess* shared = nullptr);

// The bytes per particle of the datasets a snapshot holds (position, the output fields, the
// derived ones and the integer fields, 8 bytes a value); a file adds a few kB of HDF5 metadata.
std::size_t snapshot_bytes_per_particle(const Particles& particles);

class SnapshotWriter {
 public:
  // With `shared`, on rank 0 of a run spread over ranks: each write tells the others to write
  // their rows (Solver::announce_write with the snapshot's index; they call
  // write_snapshot_file(temporary(directory / file_name(index)), solver, shared)).
  explicit SnapshotWriter(std::filesystem::path run_directory,
                          const SharedFileAccess* shared = nullptr);

  // Writes the solver's current state as the next snapshot and updates the index.
  void write(const Solver& solver);
  // Where a snapshot file is written until it is complete.
  static std::filesystem::path temporary(const std::filesystem::path& file);
  std::size_t count() const { return entries_.size(); }
  // Keep the first snapshot (the state at t = 0, which hvi measure reads) and the newest `newest`
  // others: each write then deletes the oldest of the rest (0, the default: keep all).
  void keep_newest(std::size_t newest) { keep_newest_ = newest; }

  // For a resumed run: re-reads the snapshots written up to `last_step` and deletes later ones;
  // numbering continues after the last one kept (files deleted by hand leave gaps, and new
  // snapshots never take their numbers).
  void resume(std::int64_t last_step);

  static std::string file_name(std::size_t index);
  // The snapshot files of a run directory by their index NNNNNN (a directory pruned by hand has
  // gaps); other files are left out.
  static std::map<std::size_t, std::filesystem::path> files(
      const std::filesystem::path& run_directory);

 private:
  struct Attribute {
    std::string name;
    int components;  // 1, 3, 6 or 9
    bool integer;
  };
  struct Entry {
    std::string file;  // relative to the run directory
    double time;
    std::int64_t step;
    std::size_t particles;
    std::vector<Attribute> attributes;
  };
  void write_index() const;
  std::filesystem::path directory_;
  std::vector<Entry> entries_;
  std::size_t next_index_ = 0;  // of the next snapshot file
  std::size_t keep_newest_ = 0;
  const SharedFileAccess* shared_;
};

}  // namespace hvi::mpm::io
