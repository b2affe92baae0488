#include "cases/driver/probes.hpp"

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

Probes::Probes(const scene::Scene& scene, const mpm::Solver& solver, const Hybrid* hybrid) : hybrid_(hybrid) {
  const auto& P = solver.particles();
  for (const auto& m : scene.measures) {
    if (m.kind != "displacement") continue;
    const std::array<double, 3> x = *m.point;
    Probe probe;
    probe.name = m.name;
    probe.axis = m.axis;
    if (hybrid && !in_zone(x, scene)) {
      const auto X = hybrid->far_field().reference_positions();
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t a = 0; a < hybrid->far_field().node_count(); ++a)
        if (const double r2 = distance2(&X[3 * a], x); r2 < best) {
          best = r2;
          probe.node = a;
        }
      probe.far_field = true;
    } else {
      const auto& names = solver.body_names();
      std::int64_t body = m.body.empty() ? -1 : std::find(names.begin(), names.end(), m.body) - names.begin();
      double best = std::numeric_limits<double>::infinity();
      std::size_t nearest = P.size();
      for (std::size_t p = 0; p < P.size(); ++p)
        if (body < 0 || P.body[p] == body)
          if (const double r2 = distance2(&P.position[3 * p], x); r2 < best) {
            best = r2;
            nearest = p;
          }
      if (nearest == P.size())
        throw std::invalid_argument(fmt::format("measure '{}': no particle to probe{}", m.name,
                                                m.body.empty() ? "" : " in body '" + m.body + "'"));
      body = P.body[nearest];
      const double h = scene.grid.cell_size;
      for (std::size_t p = 0; p < P.size(); ++p)
        if (P.body[p] == body && distance2(&P.position[3 * p], x) <= std::max(h * h, best)) {
          probe.slot[P.id[p]] = probe.ids.size();
          probe.ids.push_back(P.id[p]);
          probe.reference.insert(probe.reference.end(), &P.position[3 * p], &P.position[3 * p] + 3);
        }
    }
    probes_.push_back(std::move(probe));
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
      for (int d = 0; d < 3; ++d) extras[fmt::format("{}.{}.x{}", key, k, d)] = p.reference[3 * k + d];
    }
  }
}

void Probes::load(const mpm::io::CheckpointExtras& extras) {
  for (auto& p : probes_) {
    const std::string key = "probe." + p.name;
    p.peak = extras.at(key + ".peak");
    if (p.far_field) continue;
    const auto n = static_cast<std::size_t>(extras.at(key + ".n"));
    p.ids.resize(n);
    p.reference.resize(3 * n);
    p.slot.clear();
    for (std::size_t k = 0; k < n; ++k) {
      p.ids[k] = static_cast<std::int64_t>(extras.at(fmt::format("{}.{}.id", key, k)));
      p.slot[p.ids[k]] = k;
      for (int d = 0; d < 3; ++d) p.reference[3 * k + d] = extras.at(fmt::format("{}.{}.x{}", key, k, d));
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
    while (std::getline(in, line) && std::stoll(line.substr(0, line.find(','))) <= resume_step) kept.push_back(line);
  }
  log_.open(dir / "probes.csv", std::ios::trunc);
  log_ << "step,time";
  for (const auto& p : probes_) log_ << ',' << p.name;
  log_ << '\n';
  for (const auto& l : kept) log_ << l << '\n';
  log_.flush();
}

void Probes::record(const mpm::Solver& solver) {
  if (probes_.empty()) return;
  log_ << fmt::format("{},{:.17g}", solver.step_count(), solver.time());
  for (auto& p : probes_) {
    const double u = value(p, solver);
    if (std::abs(u) > std::abs(p.peak)) p.peak = u;
    log_ << fmt::format(",{:.17g}", u);
  }
  log_ << '\n';
  log_.flush();
}

std::map<std::string, double> Probes::values(const mpm::Solver& solver) const {
  std::map<std::string, double> out;
  for (const auto& p : probes_) {
    out[p.name] = value(p, solver);
    out[p.name + "_peak"] = p.peak;
  }
  return out;
}

double Probes::value(const Probe& p, const mpm::Solver& solver) const {
  if (p.far_field) return hybrid_->far_field().displacement()[3 * p.node + p.axis];
  const auto& P = solver.particles();
  double sum = 0;
  std::size_t found = 0;
  for (std::size_t q = 0; q < P.size(); ++q)
    if (const auto it = p.slot.find(P.id[q]); it != p.slot.end()) {
      sum += P.position[3 * q + p.axis] - p.reference[3 * it->second + p.axis];
      ++found;
    }
  // Particles that left the grid no longer count; none left: not a number.
  return found ? sum / found : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace hvi::driver
