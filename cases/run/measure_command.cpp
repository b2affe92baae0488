#include "cases/run/measure_command.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "analysis/snapshot.hpp"
#include "cases/scene/run_info.hpp"
#include "mpm/io/snapshot_writer.hpp"

namespace hvi::driver {

namespace fs = std::filesystem;
using analysis::ParticleData;
using analysis::ParticleSet;

namespace {

// The impact direction: every panel is struck along -z ([[panel]], paper Fig. 1), and the top
// view looks along z.
constexpr analysis::Vec3 impact_direction{0, 0, -1};

std::string body_list(const RunInfo& info) {
  std::string s;
  for (const auto& b : info.bodies) s += (s.empty() ? "'" : ", '") + b.name + "'";
  return s;
}

int facesheet_body(const RunInfo& info, const std::string& name, const char* option) {
  const int b = info.body(name);
  if (b < 0)
    throw std::invalid_argument(
        fmt::format("{}: no body named '{}'; bodies: {}", option, name, body_list(info)));
  return b;
}

// Per-particle point spacing from the scene (RunInfo::spacing).
void attach_spacing(ParticleData& p, const std::vector<double>& volume0, const RunInfo& info,
                    const fs::path& file) {
  p.spacing.resize(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.body[k] < 0 || p.body[k] >= static_cast<std::int64_t>(info.bodies.size()))
      throw std::invalid_argument(fmt::format("{}: body index {} but the scene has {} bodies",
                                              file.string(), p.body[k], info.bodies.size()));
    p.spacing[k] = info.spacing(static_cast<int>(p.body[k]), volume0[k]);
  }
}

std::string index_list(const std::map<std::size_t, fs::path>& snapshots) {
  std::string s;
  for (const auto& entry : snapshots) s += (s.empty() ? "" : ", ") + std::to_string(entry.first);
  return s;
}

std::size_t snapshot_index(const std::string& which,
                           const std::map<std::size_t, fs::path>& snapshots, const fs::path& run) {
  if (which == "last") return snapshots.rbegin()->first;
  std::size_t pos = 0;
  long n = -1;
  try {
    n = std::stol(which, &pos);
  } catch (const std::exception&) {
  }
  if (pos != which.size() || n < 0)
    throw std::invalid_argument(
        fmt::format("--snapshot: expected an index, 'last' or 'all', got '{}'", which));
  if (!snapshots.contains(static_cast<std::size_t>(n)))
    throw std::invalid_argument(
        fmt::format("--snapshot {}: {} has snapshots {}", n, run.string(), index_list(snapshots)));
  return static_cast<std::size_t>(n);
}

// The moving body at t = 0 with the largest speed of its mean velocity: the projectile.
struct Projectile {
  int body = -1;
  double speed = 0;
};
Projectile find_projectile(const analysis::Snapshot& s) {
  std::map<std::int64_t, std::array<double, 4>> momentum;  // body -> (m v, m)
  const auto& p = s.particles;
  if (p.velocity.size() != 3 * p.size()) return {};
  for (std::size_t k = 0; k < p.size(); ++k) {
    auto& m = momentum[p.body[k]];
    for (int d = 0; d < 3; ++d) m[d] += p.mass[k] * p.velocity[3 * k + d];
    m[3] += p.mass[k];
  }
  Projectile best;
  for (const auto& [body, m] : momentum) {
    const double speed = std::hypot(m[0], m[1], m[2]) / m[3];
    if (speed > best.speed) best = {static_cast<int>(body), speed};
  }
  return best;
}

// A run opened for measuring: its scene, its snapshots, and what every snapshot's measure takes
// from the state at t = 0 (read once, for one snapshot or all of them). Only the particles a
// measure reads are mirrored: a half or quarter model's full copy would hold 2-4 times the
// run's points.
struct OpenRun {
  RunInfo info;
  std::map<std::size_t, fs::path> snapshots;
  analysis::Snapshot first;
  analysis::MirrorPlanes mirror;
  std::int64_t stride =
      1;  // id offset of mirror images: above every id at t = 0 (a growing zone adds more)
  Projectile projectile;
  ParticleData projectile_initial;  // the projectile's points at t = 0, mirrored
  // z at t = 0 by id (NaN: no point of that id at t = 0). Mirroring keeps z, so an image's is its
  // original's, id modulo the stride.
  std::vector<double> initial_z;
  std::vector<double> body_mean_z;  // per body, at t = 0: the z of a point a growing zone adds
};

OpenRun open_run(const MeasureOptions& o) {
  const fs::path& run = o.run;
  const fs::path scene_file = run / "scene.resolved.toml";
  if (!fs::exists(scene_file))
    throw std::invalid_argument(
        fmt::format("{}: not a run directory (no scene.resolved.toml)", run.string()));
  OpenRun r;
  r.info = read_run_info(scene_file);
  r.snapshots = mpm::io::SnapshotWriter::files(run);
  if (r.snapshots.empty())
    throw std::invalid_argument(fmt::format("{}: no snapshots", run.string()));
  if (!r.snapshots.contains(0))
    throw std::invalid_argument(fmt::format(
        "{}: no snapshots/particles_000000.h5 (the state at step 0, which the measure needs for "
        "the initial positions); the run has snapshots {}",
        run.string(), index_list(r.snapshots)));
  r.first = analysis::read_snapshot(r.snapshots.at(0));
  if (r.first.step != 0)
    throw std::invalid_argument(fmt::format("{}: written at step {}, expected the state at step 0",
                                            r.snapshots.at(0).string(), r.first.step));
  const ParticleData& p = r.first.particles;
  attach_spacing(r.first.particles, r.first.volume0, r.info, r.first.file);
  for (const std::int64_t id : p.id) {
    if (id < 0)
      throw std::invalid_argument(
          fmt::format("{}: particle id {} (ids are not negative)", r.first.file.string(), id));
    r.stride = std::max(r.stride, id + 1);
  }
  r.mirror = o.mirror ? r.info.mirror : analysis::MirrorPlanes{};
  r.projectile = find_projectile(r.first);
  if (r.projectile.body >= 0)
    r.projectile_initial = analysis::mirrored(
        p.view(), r.mirror, r.stride, analysis::particles_of(p.view(), r.projectile.body, false));
  r.initial_z.assign(static_cast<std::size_t>(r.stride), std::numeric_limits<double>::quiet_NaN());
  std::vector<std::pair<double, double>> body_z(r.info.bodies.size());  // (sum z, count)
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double z = p.position[3 * k + 2];
    r.initial_z[static_cast<std::size_t>(p.id[k])] = z;
    body_z[static_cast<std::size_t>(p.body[k])].first += z;
    body_z[static_cast<std::size_t>(p.body[k])].second += 1;
  }
  for (const auto& [sum, count] : body_z)
    r.body_mean_z.push_back(count > 0 ? sum / count : std::nan(""));
  return r;
}

// The facesheets the measure reads: named, or the run's one panel's; -1 for one not measured.
struct Facesheets {
  int front = -1, rear = -1;
};

Facesheets facesheets(const MeasureOptions& o, const RunInfo& info) {
  std::string front = o.front, rear = o.rear;
  if (front.empty() && rear.empty()) {
    if (info.panels.size() != 1)
      throw std::invalid_argument(
          fmt::format("{}: name the facesheets with --front BODY and/or --rear BODY (the scene has "
                      "{} [[panel]]s; bodies: {})",
                      o.run.string(), info.panels.size(), body_list(info)));
    front = info.panels[0].name + ".front";
    rear = info.panels[0].name + ".rear";
  }
  return {front.empty() ? -1 : facesheet_body(info, front, "--front"),
          rear.empty() ? -1 : facesheet_body(info, rear, "--rear")};
}

// The back face the debris is counted behind: body `behind`'s (particle centres sit half a
// spacing inside it), and one spacing behind it the debris threshold. Mirroring keeps z, so the
// first snapshot's own points give it.
struct BackFace {
  double z = INFINITY, threshold = 0;
};

BackFace back_face(const RunInfo& info, const analysis::Snapshot& first, int behind) {
  BackFace f;
  if (behind < 0) return f;
  const ParticleData& p = first.particles;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.body[k] == behind) f.z = std::min(f.z, p.position[3 * k + 2] - p.spacing[k] / 2);
  if (!std::isfinite(f.z))
    throw std::invalid_argument(
        fmt::format("body '{}' has no particles", info.bodies[behind].name));
  f.threshold = info.bodies[behind].spacing;
  return f;
}

// What the measures read, mirrored: the facesheets, and whatever lies behind the back face
// (debris candidates; the debris test itself is one spacing further back).
ParticleData points_read(const analysis::Snapshot& now, const Facesheets& sheets,
                         const BackFace& back, const analysis::MirrorPlanes& mirror,
                         std::int64_t stride) {
  std::vector<std::size_t> read;
  const ParticleData& p = now.particles;
  const double z_debris = back.z - back.threshold / 2;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (p.body[k] == sheets.front || p.body[k] == sheets.rear || p.position[3 * k + 2] < z_debris)
      read.push_back(k);
  return analysis::mirrored(p.view(), mirror, stride, read);
}

// The impact axis: given, or through the projectile's centroid at t = 0.
std::array<double, 2> impact_axis(const MeasureOptions& o, const OpenRun& run) {
  if (o.axis) return *o.axis;
  if (run.projectile.body < 0)
    throw std::invalid_argument(
        "no body moves at t = 0 to take the impact axis from: give --axis x0,y0");
  const ParticleData& initial = run.projectile_initial;
  double m = 0, x = 0, y = 0;
  for (std::size_t k = 0; k < initial.size(); ++k) {
    m += initial.mass[k];
    x += initial.mass[k] * initial.position[3 * k];
    y += initial.mass[k] * initial.position[3 * k + 1];
  }
  // To a picometre: the centroid of a mirrored set is on the plane only to round-off (1e-21 m).
  // (+ 0.0 turns -0 into 0.)
  return {std::round(x / m * 1e12) / 1e12 + 0.0, std::round(y / m * 1e12) / 1e12 + 0.0};
}

// One facesheet in top view: its hole and the points still attached to it.
std::pair<SheetMeasurement, analysis::FacesheetResult> measure_sheet(
    const MeasureOptions& o, const RunInfo& info, const ParticleData& current, int body,
    std::array<double, 2> axis, analysis::DiameterRule rule) {
  analysis::FacesheetOptions f;
  f.axis = axis;
  f.rule = rule;
  f.rotation = o.rotation;
  f.view.resolution = o.resolution;
  f.view.gap_closing = o.gap_closing;
  f.link_factor = o.link_factor;
  analysis::FacesheetResult r = analysis::measure_facesheet(current.view(), body, f);
  SheetMeasurement s{info.bodies[body].name,  r.hole,   r.raster.spacing,
                     r.raster.closing_radius, r.intact, r.detached};
  return {s, std::move(r)};
}

// Debris behind the last sheet's back face. Not debris: `excluded` (the sheet's own attached
// material: a bulge, petals), and material that was behind the face from the start (the rest of
// a panel when only --front is named).
void measure_debris(Measurements& out, const OpenRun& run, const ParticleData& current,
                    const BackFace& back, std::int64_t stride, std::vector<std::size_t> excluded) {
  analysis::DebrisOptions d;
  d.axis_point = {out.axis[0], out.axis[1], 0};
  d.direction = impact_direction;
  d.back_face = -back.z;  // (x - a) . d with d = -z
  d.threshold = back.threshold;
  // z at t = 0; a point added later by a growing zone (a panel layer's) takes its body's mean z
  // at t = 0, which is its layer's.
  for (std::size_t k = 0; k < current.size(); ++k) {
    const auto original = static_cast<std::size_t>(current.id[k] % stride);
    double z0 = original < run.initial_z.size() ? run.initial_z[original] : std::nan("");
    if (std::isnan(z0)) z0 = run.body_mean_z[static_cast<std::size_t>(current.body[k])];
    if (std::isnan(z0)) z0 = current.position[3 * k + 2];
    if (z0 < back.z - d.threshold) excluded.push_back(k);
  }
  out.debris = analysis::debris_cloud(current.view(), d, excluded);
  out.debris_back_face = back.z;
  out.debris_threshold = d.threshold;
}

// The rear sheet's detached spall: its intact points outside the attached clusters that lie more
// than one spacing behind its back face at t = 0 (the debris test, restricted to the sheet).
analysis::Debris detached_spall(const Measurements& out, const ParticleData& current,
                                const BackFace& back, int rear,
                                const std::vector<std::size_t>& attached) {
  std::vector<std::uint8_t> keep(current.size(), 0);
  for (const std::size_t k : analysis::particles_of(current.view(), rear, true)) keep[k] = 1;
  for (const std::size_t k : attached) keep[k] = 0;
  std::vector<std::size_t> excluded;
  for (std::size_t k = 0; k < current.size(); ++k)
    if (!keep[k]) excluded.push_back(k);
  analysis::DebrisOptions d;
  d.axis_point = {out.axis[0], out.axis[1], 0};
  d.direction = impact_direction;
  d.back_face = -back.z;
  d.threshold = back.threshold;
  return analysis::debris_cloud(current.view(), d, excluded);
}

// The dimensional-analysis variables (paper Section 6).
void add_variables(Measurements& out, const OpenRun& run, const Facesheets& sheets) {
  const RunInfo& info = run.info;
  const Projectile& projectile = run.projectile;
  auto add = [&](const char* name, std::optional<double> v) {
    if (v) out.variables.emplace_back(name, *v);
  };
  auto speed_of = [&](int body) -> std::optional<double> {
    if (body < 0) return std::nullopt;
    const auto it = info.sound_speed.find(info.bodies[body].material);
    return it == info.sound_speed.end() ? std::nullopt : std::optional<double>(it->second);
  };
  if (projectile.body >= 0) {
    add("v_p", projectile.speed);
    std::optional<double> d = info.bodies[projectile.body].sphere_radius;
    if (d) {
      *d *= 2;
    } else {  // the diameter of the sphere of the same volume
      double v = 0;
      for (const double volume : run.projectile_initial.volume)
        v += volume;  // at t = 0, the initial volume
      d = std::cbrt(6 * v / std::numbers::pi);
    }
    add("d_p", d);
  }
  add("t_f", sheets.front >= 0 ? info.bodies[sheets.front].thickness : std::nullopt);
  add("t_r", sheets.rear >= 0 ? info.bodies[sheets.rear].thickness : std::nullopt);
  add("c_f", speed_of(sheets.front));
  add("c_r", speed_of(sheets.rear));
  if (info.panels.size() == 1) {
    add("c_hc", speed_of(info.body(info.panels[0].name + ".core")));
    add("t_hc", info.panels[0].wall_thickness);
    add("D_hc", info.panels[0].cell_diameter);
  }
  add("S", out.core_height);
}

// The measurements of one snapshot (`index` a key of run.snapshots).
Measurements measure_snapshot(const MeasureOptions& o, const OpenRun& run, std::size_t index) {
  Measurements out;
  out.run = o.run;
  const RunInfo& info = run.info;
  const analysis::Snapshot& first = run.first;
  const Facesheets sheets = facesheets(o, info);
  const int behind = sheets.rear >= 0 ? sheets.rear : sheets.front;
  const BackFace back = back_face(info, first, behind);

  // The chosen snapshot.
  std::optional<analysis::Snapshot> read;
  if (index != 0) {
    read = analysis::read_snapshot(run.snapshots.at(index));
    attach_spacing(read->particles, read->volume0, info, read->file);
  }
  const analysis::Snapshot& now = index == 0 ? first : *read;
  out.snapshot_file = now.file;
  out.time = now.time;
  out.step = now.step;
  if (now.particles.failed.empty())
    out.notes.push_back(
        "no 'failed' field in the snapshot (no failure model): every particle counts as intact");
  // A hybrid's zone that grows adds points after t = 0, with ids beyond those of the first
  // snapshot: mirror images then need a larger id offset, and the points have no initial state.
  std::int64_t stride = run.stride;
  for (const std::int64_t id : now.particles.id) stride = std::max(stride, id + 1);
  out.mirror = run.mirror;
  const ParticleData current = points_read(now, sheets, back, out.mirror, stride);
  out.axis = impact_axis(o, run);

  // The facesheets in top view.
  std::vector<std::size_t> front_attached, rear_attached;
  if (sheets.front >= 0) {
    auto [s, view] = measure_sheet(o, info, current, sheets.front, out.axis, o.front_rule);
    out.front = s;
    front_attached = view.attached;
    if (o.images) out.front_view = std::move(view);
  }
  if (sheets.rear >= 0) {
    auto [s, view] = measure_sheet(o, info, current, sheets.rear, out.axis, o.rear_rule);
    out.rear = s;
    rear_attached = view.attached;
    if (!s.hole.perforated && !view.attached.empty()) {
      const ParticleSet p = first.particles.view();
      const ParticleData initial =
          analysis::mirrored(p, out.mirror, stride, analysis::particles_of(p, sheets.rear, false));
      out.bulge =
          analysis::rear_bulge(initial.view(), current.view(), view.attached, impact_direction);
    }
    if (o.images) out.rear_view = std::move(view);
  }

  // Taper, eq. (12).
  out.core_height = o.core_height;
  if (!out.core_height && info.panels.size() == 1) out.core_height = info.panels[0].core_height;
  // (Not when a sheet has nothing attached left to measure: its hole has no size.)
  if (out.front && out.rear && out.front->hole.perforated && out.rear->hole.perforated &&
      out.front->hole.resolution > 0 && out.rear->hole.resolution > 0 && out.core_height)
    out.taper = analysis::channel_taper(out.rear->hole.D, out.front->hole.D, *out.core_height);

  if (sheets.rear >= 0) out.spall = detached_spall(out, current, back, sheets.rear, rear_attached);
  if (behind >= 0) {
    measure_debris(out, run, current, back, stride,
                   sheets.rear >= 0 ? rear_attached : front_attached);
    out.debris_behind = info.bodies[behind].name;
  }
  add_variables(out, run, sheets);
  return out;
}

}  // namespace

Measurements measure_run(const MeasureOptions& o) {
  const OpenRun run = open_run(o);
  if (o.snapshot == "all")
    throw std::invalid_argument("--snapshot all: measure_history measures every snapshot");
  return measure_snapshot(o, run, snapshot_index(o.snapshot, run.snapshots, o.run));
}

std::vector<Measurements> measure_history(const MeasureOptions& o) {
  const OpenRun run = open_run(o);
  std::vector<Measurements> out;
  for (const auto& entry : run.snapshots) out.push_back(measure_snapshot(o, run, entry.first));
  return out;
}

}  // namespace hvi::driver
