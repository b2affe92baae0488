#include "coupling/zone_growth.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mpm/types.hpp"

namespace hvi::coupling {

std::array<bool, 4> sides_reached(const mpm::Particles& P, std::span<const std::int64_t> bodies,
                                  const std::array<double, 4>& zone, const ZoneGrowth& growth) {
  std::array<bool, 4> reached{};
  const std::vector<double>* damage = P.has_field("damage") ? &P.field("damage") : nullptr;
  const std::vector<double>* failed = P.has_field("failed") ? &P.field("failed") : nullptr;
  if (!damage && !failed) return reached;
  // Where the material started, when the points carry it (a growing zone's do): a fragment
  // torn off near the axis that flies out along the panel is not damage at the side it reaches.
  const std::vector<double>& start =
      P.has_field(reference_position_field) ? P.field(reference_position_field) : P.position;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const bool damaged =
        (damage && (*damage)[p] >= growth.damage) || (failed && (*failed)[p] > 0.0);
    if (!damaged || std::find(bodies.begin(), bodies.end(), P.body[p]) == bodies.end()) continue;
    const double x = start[3 * p], y = start[3 * p + 1], z = P.position[3 * p + 2];
    // Within the margin of a side, in plane, and not beyond the zone across it; in the panel
    // (debris flying out of it is not the panel's damage).
    if (x < zone[0] - growth.margin || x > zone[2] + growth.margin || y < zone[1] - growth.margin ||
        y > zone[3] + growth.margin || z < growth.z_lower - growth.margin ||
        z > growth.z_upper + growth.margin)
      continue;
    reached[0] = reached[0] || x < zone[0] + growth.margin;
    reached[1] = reached[1] || y < zone[1] + growth.margin;
    reached[2] = reached[2] || x > zone[2] - growth.margin;
    reached[3] = reached[3] || y > zone[3] - growth.margin;
  }
  return reached;
}

std::array<bool, 4> sides_reached_from_outside(std::span<const double> centres,
                                               const std::array<double, 4>& zone,
                                               const ZoneGrowth& growth) {
  std::array<bool, 4> reached{};
  const double m = growth.margin;
  for (std::size_t k = 0; k + 1 < centres.size(); k += 2) {
    const double x = centres[k], y = centres[k + 1];
    const bool across_x = y >= zone[1] - m && y <= zone[3] + m,
               across_y = x >= zone[0] - m && x <= zone[2] + m;
    reached[0] = reached[0] || (across_x && x < zone[0] && x >= zone[0] - m);
    reached[1] = reached[1] || (across_y && y < zone[1] && y >= zone[1] - m);
    reached[2] = reached[2] || (across_x && x > zone[2] && x <= zone[2] + m);
    reached[3] = reached[3] || (across_y && y > zone[3] && y <= zone[3] + m);
  }
  return reached;
}

std::array<double, 4> grown_zone(const std::array<bool, 4>& reached,
                                 const std::array<double, 4>& zone, const ZoneGrowth& growth) {
  std::array<double, 4> grown = zone;
  for (int side = 0; side < 4; ++side) {
    if (!reached[side] || !growth.movable[side]) continue;
    // Sides 0, 1 move down to the limit, sides 2, 3 up to it.
    grown[side] = side < 2 ? std::max(zone[side] - growth.step, growth.limit[side])
                           : std::min(zone[side] + growth.step, growth.limit[side]);
  }
  return grown;
}

std::array<double, 4> grown_zone(const mpm::Particles& P, std::span<const std::int64_t> bodies,
                                 const std::array<double, 4>& zone, const ZoneGrowth& growth) {
  return grown_zone(sides_reached(P, bodies, zone, growth), zone, growth);
}

std::array<bool, 4> sides_held_at_limit(const std::array<bool, 4>& reached,
                                        const std::array<double, 4>& zone,
                                        const ZoneGrowth& growth) {
  std::array<bool, 4> held{};
  // A side that reached its limit holds it exactly (grown_zone's max and min return the limit).
  for (int side = 0; side < 4; ++side)
    held[side] = reached[side] && growth.movable[side] && zone[side] == growth.limit[side];
  return held;
}

std::vector<std::array<double, 4>> ring(const std::array<double, 4>& zone,
                                        const std::array<double, 4>& grown) {
  std::vector<std::array<double, 4>> boxes;
  auto add = [&](double x0, double y0, double x1, double y1) {
    if (x1 > x0 && y1 > y0) boxes.push_back({x0, y0, x1, y1});
  };
  add(grown[0], grown[1], grown[2], zone[1]);
  add(grown[0], zone[3], grown[2], grown[3]);
  add(grown[0], zone[1], zone[0], zone[3]);
  add(zone[2], zone[1], grown[2], zone[3]);
  return boxes;
}

namespace {

// fem's Voigt order (xx, yy, zz, yz, xz, xy) into the particles' Tensor6 slots.
constexpr int to_particle[6] = {mpm::sym::xx, mpm::sym::yy, mpm::sym::zz,
                                mpm::sym::yz, mpm::sym::xz, mpm::sym::xy};

// A wall point's stress (coupling/zone_growth.hpp) from the core's elastic strain e (fem's Voigt
// order, tensor shears) and the wall's direction t; returns its elastic energy per volume,
// 1/2 (sigma_zz e_zz + tau gamma_tz).
double take_wall_stress(const LayerTakeover& walls, const fem::Sym& e, const double* t,
                        double* stress) {
  const double E = walls.wall_youngs_modulus, G = E / (2.0 * (1.0 + walls.wall_poisson_ratio));
  const double e_zz = e[2], shear = 2.0 * (e[4] * t[0] + e[3] * t[1]);  // gamma_tz
  const double sigma_zz = E * e_zz, tau = G * shear;
  for (int c = 0; c < 6; ++c) stress[c] = 0.0;
  stress[mpm::sym::zz] = sigma_zz;
  stress[mpm::sym::xz] = tau * t[0];
  stress[mpm::sym::yz] = tau * t[1];
  return 0.5 * (sigma_zz * e_zz + tau * shear);
}

}  // namespace

TakeoverReport take_over(FarFieldCoupling& coupling, fem::FarField& far_field, mpm::Solver& solver,
                         const NewPoints& points, const InterfaceBand& band,
                         const std::vector<LayerTakeover>& layers) {
  TakeoverReport report;
  const std::size_t n = points.size();
  report.points = n;
  const bool directions = points.wall_direction.size() == 2 * n;
  if (!directions && !points.wall_direction.empty())
    throw std::invalid_argument("take_over: wall directions for " +
                                std::to_string(points.wall_direction.size() / 2) + " of " +
                                std::to_string(n) + " points");
  const auto samples = far_field.sample(points.position);
  for (std::size_t k = 0; k < n; ++k) {
    const int l = samples[k].layer;
    if (l < 0 || layers.at(static_cast<std::size_t>(l)).kind != LayerTakeover::Kind::walls)
      continue;
    if (!directions ||
        (points.wall_direction[2 * k] == 0.0 && points.wall_direction[2 * k + 1] == 0.0))
      throw std::invalid_argument("take_over: point " + std::to_string(k) +
                                  " of the honeycomb core's layer has no wall direction");
  }

  // 2. The far field gives up the zone's cells; its losses of energy and momentum.
  const double kinetic_before = far_field.kinetic_energy(),
               strain_before = far_field.strain_energy();
  const auto momentum_before = far_field.momentum();
  report.cells = far_field.remove_cells(band.zone);
  coupling.retie(band);
  report.far_field_kinetic = kinetic_before - far_field.kinetic_energy();
  report.far_field_energy = report.far_field_kinetic + strain_before - far_field.strain_energy();
  const auto momentum_after = far_field.momentum();

  // 1. The new points, from the samples.
  mpm::Particles& P = solver.particles();
  const std::size_t first = P.size();
  const std::int64_t next_id = solver.next_point_id();  // over every rank
  report.first_id = next_id;
  P.resize(first + n);
  std::vector<double>* half_width = P.has_field(mpm::Solver::half_width_field)
                                        ? &P.field(mpm::Solver::half_width_field)
                                        : nullptr;
  std::vector<double>* pressure = P.has_field("eos_pressure") ? &P.field("eos_pressure") : nullptr;
  std::vector<double>* alpha = P.has_field("plastic_strain") ? &P.field("plastic_strain") : nullptr;
  std::vector<double>* damage = P.has_field("damage") ? &P.field("damage") : nullptr;
  std::vector<double>* failed = P.has_field("failed") ? &P.field("failed") : nullptr;
  std::vector<double>* reference =
      P.has_field(reference_position_field) ? &P.field(reference_position_field) : nullptr;
  mpm::Vec3 lost{}, taken{};
  double new_mass = 0.0;
  for (int d = 0; d < 3; ++d) lost[d] = momentum_before[d] - momentum_after[d];
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t p = first + k;
    const fem::FarField::PointSample& s = samples[k];
    if (s.layer < 0) {
      for (int d = 0; d < 3; ++d) P.position[3 * p + d] = points.position[3 * k + d];
      P.id[p] = next_id + static_cast<std::int64_t>(k);
      P.body[p] = points.body[k];
      P.material[p] = points.material[k];
      solver.fail(p, "a point taking over far-field cells lies outside the far field");
    }
    const LayerTakeover& layer = layers.at(static_cast<std::size_t>(s.layer));
    const bool stressed = layer.kind == LayerTakeover::Kind::solid;
    const bool torn = s.damage >= 1.0;
    double trace = 0.0;
    if (reference)
      for (int d = 0; d < 3; ++d) (*reference)[3 * p + d] = points.position[3 * k + d];
    for (int d = 0; d < 3; ++d) {
      P.position[3 * p + d] = points.position[3 * k + d] + s.displacement[d];
      P.velocity[3 * p + d] = s.velocity[d];
      trace += s.strain[d];
    }
    P.volume0[p] = points.volume[k];
    P.volume[p] = stressed ? points.volume[k] * (1.0 + trace) : points.volume[k];
    P.mass[p] = points.density[k] * points.volume[k];
    P.id[p] = next_id + static_cast<std::int64_t>(k);
    P.body[p] = points.body[k];
    P.material[p] = points.material[k];
    double energy = 0.0;  // elastic, J/kg
    if (stressed) {
      // A torn point keeps only a compressive pressure, as failed material does.
      const double mean = (s.stress[0] + s.stress[1] + s.stress[2]) / 3.0;
      for (int k6 = 0; k6 < 6; ++k6) {
        const double sigma = torn ? (k6 < 3 ? std::min(mean, 0.0) : 0.0) : s.stress[k6];
        P.stress[6 * p + to_particle[k6]] = sigma;
      }
      if (!torn)
        for (int k6 = 0; k6 < 6; ++k6)
          energy += 0.5 * (k6 < 3 ? 1.0 : 2.0) * s.stress[k6] * s.elastic_strain[k6];
      if (pressure) (*pressure)[p] = torn ? std::max(-mean, 0.0) : -mean;
    } else if (!torn) {
      energy = take_wall_stress(layer, s.elastic_strain, &points.wall_direction[2 * k],
                                &P.stress[6 * p]);
      const double e_zz = s.elastic_strain[2];
      P.volume[p] = points.volume[k] * (1.0 + (1.0 - 2.0 * layer.wall_poisson_ratio) * e_zz);
      if (pressure) (*pressure)[p] = -P.stress[6 * p + mpm::sym::zz] / 3.0;
    }
    // 1/2 sigma : (eps - eps_p) per mass: the plastic work stays booked in the far field's.
    P.internal_energy[p] = std::max(energy, 0.0) * P.volume0[p] / P.mass[p];
    if (alpha) (*alpha)[p] = s.plastic_strain;
    if (damage) (*damage)[p] = std::min(s.damage, 1.0);
    if (failed && torn) (*failed)[p] = 1.0;
    if (half_width && points.half_width.size() == 3 * n)
      for (int d = 0; d < 3; ++d) (*half_width)[3 * p + d] = points.half_width[3 * k + d];
    new_mass += P.mass[p];
    for (int d = 0; d < 3; ++d) taken[d] += P.mass[p] * P.velocity[3 * p + d];
  }

  // 3. Momentum: one velocity correction over the new points.
  mpm::Vec3 dv{};
  if (new_mass > 0.0)
    for (int d = 0; d < 3; ++d) dv[d] = (lost[d] - taken[d]) / new_mass;
  report.momentum_correction = mpm::norm(dv);
  for (std::size_t p = first; p < first + n; ++p) {
    double v2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      P.velocity[3 * p + d] += dv[d];
      v2 += P.velocity[3 * p + d] * P.velocity[3 * p + d];
    }
    report.point_kinetic += 0.5 * P.mass[p] * v2;
    report.point_energy += P.mass[p] * (0.5 * v2 + P.internal_energy[p]);
  }

  // Spread over ranks, the new points are one rank's (rank 0's): every rank books what it holds.
  if (mpm::Communicator* comm = solver.communicator()) {
    std::vector<double> held{report.point_energy, report.point_kinetic, report.momentum_correction};
    comm->broadcast(held);
    report.point_energy = held.at(0);
    report.point_kinetic = held.at(1);
    report.momentum_correction = held.at(2);
  }

  // 4. Energy: the mismatch is booked as converted, in the far field's internal energy.
  coupling.book_conversion(report.far_field_energy - report.point_energy);
  solver.adopt_particles(first);
  return report;
}

}  // namespace hvi::coupling
