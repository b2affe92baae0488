#include "analysis/snapshot.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "mpm/io/hdf5_file.hpp"

namespace hvi::analysis {

namespace fs = std::filesystem;

Snapshot read_snapshot(const fs::path& file) {
  const mpm::io::Hdf5File h5(file.string(), mpm::io::Hdf5File::Mode::read);
  Snapshot s;
  s.file = file;
  s.time = h5.read_double_attribute("time");
  s.step = h5.read_integer_attribute("step");
  for (const char* name : {"position", "id", "body", "mass", "volume"})
    if (!h5.has_dataset(name))
      throw std::runtime_error(fmt::format("{}: no dataset '{}'", file.string(), name));
  ParticleData& p = s.particles;
  p.position = h5.read_doubles("position");
  p.id = h5.read_integers("id");
  p.body = h5.read_integers("body");
  p.mass = h5.read_doubles("mass");
  p.volume = h5.read_doubles("volume");
  if (h5.has_dataset("failed")) p.failed = h5.read_doubles("failed");
  if (h5.has_dataset("velocity")) p.velocity = h5.read_doubles("velocity");
  s.volume0 = p.volume;
  if (h5.has_dataset("volume_ratio")) {
    const std::vector<double> ratio = h5.read_doubles("volume_ratio");
    for (std::size_t k = 0; k < ratio.size(); ++k) s.volume0[k] /= ratio[k];
  }
  const std::size_t n = p.id.size();
  if (p.position.size() != 3 * n || p.body.size() != n || p.mass.size() != n ||
      p.volume.size() != n || (!p.failed.empty() && p.failed.size() != n))
    throw std::runtime_error(fmt::format("{}: datasets of different lengths", file.string()));
  return s;
}

}  // namespace hvi::analysis
