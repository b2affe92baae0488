#include "cases/run/probe_history.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include <fmt/format.h>

#include "cases/run/hybrid.hpp"
#include "cases/scene/scene.hpp"
#include "mpm/io/hdf5_file.hpp"
#include "mpm/io/snapshot_writer.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;
using mpm::io::Hdf5File;

namespace {

using Point = std::array<double, 3>;

double distance2(const double* x, const Point& p) {
  return (x[0] - p[0]) * (x[0] - p[0]) + (x[1] - p[1]) * (x[1] - p[1]) +
         (x[2] - p[2]) * (x[2] - p[2]);
}

// The index of the position (3 per entry) nearest `p`.
std::size_t nearest(const std::vector<double>& x, const Point& p) {
  std::size_t best = 0;
  for (std::size_t k = 1; 3 * k < x.size(); ++k)
    if (distance2(&x[3 * k], p) < distance2(&x[3 * best], p)) best = k;
  return best;
}

// A particle snapshot's positions, ids, bodies and (if written) undeformed positions.
struct Points {
  double time = 0;
  std::vector<double> x, X;
  std::vector<std::int64_t> id, body;

  Points(const fs::path& file, bool reference) {
    const Hdf5File f(file.string(), Hdf5File::Mode::read);
    time = f.read_double_attribute("time");
    x = f.read_doubles("position");
    id = f.read_integers("id");
    body = f.read_integers("body");
    if (!reference) return;
    if (!f.has_dataset("reference_position"))
      throw std::invalid_argument(fmt::format(
          "{} holds no reference_position (a run made before hvi wrote it): read the run's "
          "probes.csv",
          file.string()));
    X = f.read_doubles("reference_position");
  }

  // The points of the body of the point nearest `p` (by `at`, 3 per point) within one cell of
  // it, or that nearest one alone when none is so near.
  std::vector<std::size_t> near(const std::vector<double>& at, const Point& p, double cell) const {
    if (id.empty()) throw std::invalid_argument("the snapshot holds no particles");
    const std::size_t n = nearest(at, p);
    const double r2 = std::max(cell * cell, distance2(&at[3 * n], p));
    std::vector<std::size_t> chosen;
    for (std::size_t k = 0; k < id.size(); ++k)
      if (body[k] == body[n] && distance2(&at[3 * k], p) <= r2) chosen.push_back(k);
    return chosen;
  }
};

std::vector<fs::path> particle_snapshots(const fs::path& run) {
  std::vector<fs::path> files;
  for (const auto& [index, file] : mpm::io::SnapshotWriter::files(run)) files.push_back(file);
  if (files.empty())
    throw std::invalid_argument(
        fmt::format("{}: no particle snapshots", (run / "snapshots").string()));
  return files;
}

// The far field's node files (Hybrid::write_snapshot) in step order.
std::vector<fs::path> node_files(const fs::path& run) {
  std::map<std::int64_t, fs::path> files;
  if (fs::is_directory(run / "far_field"))
    for (const auto& entry : fs::directory_iterator(run / "far_field")) {
      const std::string name = entry.path().filename().string();
      const std::string step = name.size() > 9 ? name.substr(6, name.size() - 9) : "";
      if (name.starts_with("nodes_") && name.ends_with(".h5") && !step.empty() &&
          step.find_first_not_of("0123456789") == std::string::npos)
        files[std::stoll(step)] = entry.path();
    }
  if (files.empty())
    throw std::invalid_argument(
        fmt::format("{}: no far-field node files nodes_<step>.h5 (a run made before hvi wrote "
                    "them): read the run's probes.csv",
                    (run / "far_field").string()));
  std::vector<fs::path> ordered;
  for (const auto& [step, file] : files) ordered.push_back(file);
  return ordered;
}

ProbeReading particle_history(const fs::path& run, const Point& p, int axis, double cell) {
  const std::vector<fs::path> files = particle_snapshots(run);
  const Points first(files.front(), false);
  const std::vector<std::size_t> chosen = first.near(first.x, p, cell);
  std::unordered_map<std::int64_t, double> start;  // id -> its coordinate at the first snapshot
  for (const std::size_t k : chosen) start[first.id[k]] = first.x[3 * k + axis];
  ProbeReading r;
  for (const fs::path& file : files) {
    const Points now(file, false);
    double sum = 0;
    std::size_t n = 0;
    for (std::size_t k = 0; k < now.id.size(); ++k)
      if (const auto it = start.find(now.id[k]); it != start.end()) {
        sum += now.x[3 * k + axis] - it->second;
        ++n;
      }
    r.rows.push_back({now.time, n ? sum / static_cast<double>(n) : std::nan("")});
  }
  r.source = fmt::format("{} particles of body {} within {:g} m", chosen.size(),
                         first.body[chosen.front()], cell);
  return r;
}

ProbeReading far_field_history(const fs::path& run, const Point& p, int axis, double cell,
                               bool grows) {
  std::vector<std::pair<double, fs::path>> snapshots;  // (time, file), for a take-over
  std::size_t node = 0;
  ProbeReading r;
  std::string taken;
  for (const fs::path& file : node_files(run)) {
    const Hdf5File f(file.string(), Hdf5File::Mode::read);
    const double time = f.read_double_attribute("time");
    if (r.rows.empty()) {
      const std::vector<double> X = f.read_doubles("reference_position");
      node = nearest(X, p);
      r.source = fmt::format("the far-field node at {:.6g}, {:.6g}, {:.6g} m", X[3 * node],
                             X[3 * node + 1], X[3 * node + 2]);
    }
    if (!grows || f.read_doubles("lumped_mass")[node] > 0.0) {
      r.rows.push_back({time, f.read_doubles("displacement")[3 * node + axis]});
      continue;
    }
    // The zone grew over the node: the points that took its place, by their undeformed positions.
    if (snapshots.empty())
      for (const fs::path& s : particle_snapshots(run))
        snapshots.emplace_back(
            Hdf5File(s.string(), Hdf5File::Mode::read).read_double_attribute("time"), s);
    const auto closest = std::min_element(
        snapshots.begin(), snapshots.end(),
        [&](auto& a, auto& b) { return std::abs(a.first - time) < std::abs(b.first - time); });
    const Points points(closest->second, true);
    const std::vector<std::size_t> chosen = points.near(points.X, p, cell);
    double sum = 0;
    for (const std::size_t k : chosen) sum += points.x[3 * k + axis] - points.X[3 * k + axis];
    r.rows.push_back({time, sum / static_cast<double>(chosen.size())});
    if (taken.empty())
      taken = fmt::format(
          ", then (from t = {:g} s, the zone grown over it) {} points of body {} "
          "within {:g} m by their undeformed positions",
          time, chosen.size(), points.body[chosen.front()], cell);
  }
  r.source += taken;
  return r;
}

}  // namespace

ProbeReading read_probe(const fs::path& run, const Point& point, int axis) {
  const scene::Scene s = scene::load_scene((run / "scene.resolved.toml").string(), {},
                                           scene::MeshFiles::may_be_missing);
  const double cell = s.grid.cell_size;
  if (s.far_field) {
    const auto& z = s.far_field->zone;
    const bool in_zone =
        z[0] <= point[0] && point[0] <= z[2] && z[1] <= point[1] && point[1] <= z[3];
    if (!in_zone) return far_field_history(run, point, axis, cell, s.far_field->grow.has_value());
  }
  return particle_history(run, point, axis, cell);
}

}  // namespace hvi::driver
