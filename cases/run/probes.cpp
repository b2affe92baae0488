#include "cases/run/probes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

namespace hvi::driver {

namespace {

double distance2(const double* a, const std::array<double, 3>& b) {
  double r2 = 0;
  for (int d = 0; d < 3; ++d) r2 += (a[d] - b[d]) * (a[d] - b[d]);
  return r2;
}

bool in_zone(const std::array<double, 3>& x, const scene::Scene& s) {
  const auto& z = s.far_field->zone;
  return x[0] >= z[0] && x[0] <= z[2] && x[1] >= z[1] && x[1] <= z[3];
}

}  // namespace

bool has_probes(const scene::Scene& scene) {
  return std::any_of(scene.measures.begin(), scene.measures.end(),
                     [](const auto& m) { return m.kind == "displacement"; });
}

Probes::Probes(const scene::Scene& scene, const mpm::Solver& solver, const Hybrid* hybrid)
    : hybrid_(hybrid), cell_(scene.grid.cell_size) {
  for (const auto& m : scene.measures) {
    if (m.kind != "displacement") continue;
    Probe probe;
    probe.name = m.name;
    probe.point = *m.point;
    probe.body = m.body;
    probe.axis = m.axis;
    if (hybrid && !in_zone(probe.point, scene)) {
      const auto X = hybrid->far_field().reference_positions();
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t a = 0; a < hybrid->far_field().node_count(); ++a)
        if (const double r2 = distance2(&X[3 * a], probe.point); r2 < best) {
          best = r2;
          probe.node = a;
        }
      probe.far_field = true;
    } else {
      choose_particles(probe, solver, cell_, 0, {});
      if (probe.ids.empty())
        throw std::invalid_argument(fmt::format("measure '{}': no particle to probe{}", m.name,
                                                m.body.empty() ? "" : " in body '" + m.body + "'"));
    }
    probes_.push_back(std::move(probe));
  }
}

void Probes::choose_particles(Probe& probe, const mpm::Solver& solver, double h,
                              std::int64_t first_id, const std::vector<double>& reference) {
  const auto& P = solver.particles();
  auto X = [&](std::size_t p) {
    return reference.empty() ? &P.position[3 * p]
                             : &reference[3 * static_cast<std::size_t>(P.id[p] - first_id)];
  };
  const auto& names = solver.body_names();
  std::int64_t body =
      probe.body.empty() ? -1 : std::find(names.begin(), names.end(), probe.body) - names.begin();
  double best = std::numeric_limits<double>::infinity();
  std::size_t nearest = P.size();
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.id[p] >= first_id && (body < 0 || P.body[p] == body))
      if (const double r2 = distance2(X(p), probe.point); r2 < best) {
        best = r2;
        nearest = p;
      }
  probe.ids.clear();
  probe.reference.clear();
  probe.slot.clear();
  if (nearest == P.size()) return;
  body = P.body[nearest];
  std::vector<std::size_t> chosen;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.id[p] >= first_id && P.body[p] == body &&
        distance2(X(p), probe.point) <= std::max(h * h, best))
      chosen.push_back(p);
  // In the order of their ids: the probe sums them so, whatever the order of the arrays.
  std::sort(chosen.begin(), chosen.end(), [&](auto a, auto b) { return P.id[a] < P.id[b]; });
  for (const std::size_t p : chosen) {
    probe.slot[P.id[p]] = probe.ids.size();
    probe.ids.push_back(P.id[p]);
    probe.reference.insert(probe.reference.end(), X(p), X(p) + 3);
  }
}

void Probes::zone_grew(const mpm::Solver& solver, std::int64_t first_id) {
  const auto& P = solver.particles();
  for (auto& p : probes_) {
    if (!p.far_field || hybrid_->far_field().lumped_mass()[p.node] > 0.0) continue;
    // The points near the node (by their undeformed positions) go on from its reading: each
    // takes as reference its position now less the node's displacement, so the probe reads the
    // node's displacement at the take-over plus the points' mean displacement since.
    choose_particles(p, solver, cell_, first_id, hybrid_->last_points());
    if (p.ids.empty()) continue;  // no point of the body near the node: it keeps reading the node
    const auto u = hybrid_->far_field().displacement();
    for (std::size_t q = 0; q < P.size(); ++q)
      if (const auto it = p.slot.find(P.id[q]); it != p.slot.end())
        for (int d = 0; d < 3; ++d)
          p.reference[3 * it->second + d] = P.position[3 * q + d] - u[3 * p.node + d];
    p.far_field = false;
  }
}

void Probes::save(mpm::io::CheckpointExtras& extras) const {
  for (const auto& p : probes_) {
    const std::string key = "probe." + p.name;
    extras[key + ".peak"] = p.peak;
    if (p.far_field) continue;  // the node is chosen the same way again
    extras[key + ".n"] = static_cast<double>(p.ids.size());
    for (std::size_t k = 0; k < p.ids.size(); ++k) {
      extras[fmt::format("{}.{}.id", key, k)] = static_cast<double>(p.ids[k]);
      for (int d = 0; d < 3; ++d)
        extras[fmt::format("{}.{}.x{}", key, k, d)] = p.reference[3 * k + d];
    }
  }
}

void Probes::load(const mpm::io::CheckpointExtras& extras) {
  for (auto& p : probes_) {
    const std::string key = "probe." + p.name;
    p.peak = extras.at(key + ".peak");
    // A probe in the far field that a grown zone moved to its points saved them.
    if (!extras.contains(key + ".n")) continue;
    p.far_field = false;
    const auto n = static_cast<std::size_t>(extras.at(key + ".n"));
    p.ids.resize(n);
    p.reference.resize(3 * n);
    p.slot.clear();
    for (std::size_t k = 0; k < n; ++k) {
      p.ids[k] = static_cast<std::int64_t>(extras.at(fmt::format("{}.{}.id", key, k)));
      p.slot[p.ids[k]] = k;
      for (int d = 0; d < 3; ++d)
        p.reference[3 * k + d] = extras.at(fmt::format("{}.{}.x{}", key, k, d));
    }
  }
}

void Probes::open(const std::filesystem::path& dir, std::int64_t resume_step) {
  if (probes_.empty()) return;
  std::vector<std::string> kept;
  if (resume_step >= 0) {
    std::ifstream in(dir / "probes.csv");
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line) && std::stoll(line.substr(0, line.find(','))) <= resume_step)
      kept.push_back(line);
  }
  log_.open(dir / "probes.csv", std::ios::trunc);
  log_ << "step,time";
  for (const auto& p : probes_) log_ << ',' << p.name;
  log_ << '\n';
  for (const auto& l : kept) log_ << l << '\n';
  log_.flush();
}

Probes::Positions Probes::positions(const mpm::Solver& solver) const {
  std::vector<std::int64_t> ids;
  for (const auto& p : probes_)
    if (!p.far_field) ids.insert(ids.end(), p.ids.begin(), p.ids.end());
  Positions at;
  if (ids.empty()) return at;
  for (const auto& q : solver.positions_of(std::move(ids))) at.emplace(q.id, q.x);
  return at;
}

void Probes::record(const mpm::Solver& solver) {
  if (probes_.empty()) return;
  log_ << fmt::format("{},{:.17g}", solver.step_count(), solver.time());
  const Positions at = positions(solver);
  for (auto& p : probes_) {
    const double u = value(p, at);
    if (std::abs(u) > std::abs(p.peak)) p.peak = u;
    log_ << fmt::format(",{:.17g}", u);
  }
  log_ << '\n';
  log_.flush();
}

std::map<std::string, double> Probes::values(const mpm::Solver& solver) const {
  std::map<std::string, double> out;
  const Positions at = positions(solver);
  for (const auto& p : probes_) {
    out[p.name] = value(p, at);
    out[p.name + "_peak"] = p.peak;
  }
  return out;
}

// The mean over the probe's points, in the order of its ids (so the same bits wherever the
// points are).
double Probes::value(const Probe& p, const Positions& at) const {
  if (p.far_field) return hybrid_->far_field().displacement()[3 * p.node + p.axis];
  double sum = 0;
  std::size_t found = 0;
  for (std::size_t k = 0; k < p.ids.size(); ++k)
    if (const auto it = at.find(p.ids[k]); it != at.end()) {
      sum += it->second[static_cast<std::size_t>(p.axis)] - p.reference[3 * k + p.axis];
      ++found;
    }
  // Particles that left the grid no longer count; none left: not a number.
  return found ? sum / found : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace hvi::driver
