#include "coupling/far_field_coupling.hpp"

#include "mpm/communicator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace hvi::coupling {

namespace {

// Weights of the grid nodes around coordinate s (in cells from the origin) along one axis: a
// single node when s is a node (to 1e-9 of a cell), else the two neighbours, linearly.
int axis_weights(double s, int n_cells, std::array<int, 2>& node, std::array<double, 2>& w) {
  const double r = std::round(s);
  if (std::abs(s - r) < 1e-9) {
    node[0] = static_cast<int>(r);
    w[0] = 1.0;
    return node[0] >= 0 && node[0] <= n_cells ? 1 : -1;
  }
  node[0] = static_cast<int>(std::floor(s));
  node[1] = node[0] + 1;
  w[1] = s - node[0];
  w[0] = 1.0 - w[1];
  return node[0] >= 0 && node[1] <= n_cells ? 2 : -1;
}

}  // namespace

FarFieldCoupling::FarFieldCoupling(fem::FarField& far_field, const mpm::GridGeometry& grid,
                                   const InterfaceBand& band, double flip, double safety)
    : far_field_(far_field), grid_(grid), flip_(flip), safety_(safety) {
  const std::size_t n = far_field.node_count();
  force_.assign(3 * n, 0.0);
  increment_.assign(3 * n, 0.0);
  nodal_velocity_.assign(3 * n, 0.0);
  retie(band);
}

void FarFieldCoupling::retie(const InterfaceBand& band) {
  band_ = band;
  const auto& grid = grid_;
  const auto x = far_field_.reference_positions();
  const auto mass = far_field_.lumped_mass();
  const std::size_t n = far_field_.node_count();
  ties_.clear();
  tied_.assign(n, 0);
  tied_nodes_ = exact_nodes_ = 0;
  const double tol = 1e-9 * grid.cell_size;
  const auto& z = band.zone;
  for (std::size_t a = 0; a < n; ++a) {
    if (mass[a] == 0.0) continue;  // detached by remove_cells
    const double px = x[3 * a], py = x[3 * a + 1];
    const bool in_band = px >= z[0] - band.width - tol && px <= z[2] + band.width + tol &&
                         py >= z[1] - band.width - tol && py <= z[3] + band.width + tol;
    if (!in_band) continue;
    std::array<std::array<int, 2>, 3> node{};
    std::array<std::array<double, 2>, 3> w{};
    std::array<int, 3> count{};
    for (int d = 0; d < 3; ++d) {
      count[d] = axis_weights((x[3 * a + d] - grid.origin[d]) / grid.cell_size, grid.cells[d],
                              node[d], w[d]);
      if (count[d] < 0)
        throw std::invalid_argument("far-field node " + std::to_string(a) +
                                    " of the interface band lies outside the MPM grid");
    }
    for (int i = 0; i < count[0]; ++i)
      for (int j = 0; j < count[1]; ++j)
        for (int k = 0; k < count[2]; ++k) {
          const double weight = w[0][i] * w[1][j] * w[2][k];
          if (weight > 0.0)
            ties_.push_back(
                {static_cast<std::uint32_t>(a), {node[0][i], node[1][j], node[2][k]}, weight});
        }
    tied_[a] = 1;
    ++tied_nodes_;
    exact_nodes_ += count[0] * count[1] * count[2] == 1;
  }
  if (tied_nodes_ == 0)
    throw std::invalid_argument("the interface band ties no far-field node to the MPM grid");
}

void FarFieldCoupling::spread(const mpm::GridRanks& ranks) {
  ranks_ = ranks;
  mpm::Communicator* comm = ranks.comm;
  fem::FarFieldRanks split{comm->rank(), comm->size(), {}, {}};
  split.all_gather = [comm](const std::vector<double>& mine) { return comm->all_gather(mine); };
  split.gather_to_root = [comm](const std::vector<double>& mine) {
    std::vector<std::vector<double>> to(static_cast<std::size_t>(comm->size()));
    to[0] = mine;
    return comm->exchange(std::move(to));
  };
  far_field_.spread(std::move(split));
}

void FarFieldCoupling::request_blocks(std::vector<std::uint64_t>& keys) const {
  for (const Tie& t : ties_)
    if (!ranks_ || ranks_->owner(block_of(t)) == ranks_->comm->rank()) keys.push_back(block_of(t));
}

void FarFieldCoupling::add_to_grid(mpm::SparseGrid& grid, mpm::GridStage stage, double, double dt) {
  const auto m = far_field_.lumped_mass();
  const auto v = far_field_.velocity();
  // The displacement moved over the last step, of (nearly: the CFL step changes by a small
  // fraction a step) this step's dt: the strain rate of rate-dependent J2 facesheets.
  if (stage == mpm::GridStage::force) far_field_.internal_force(force_, dt);
  for (const Tie& t : ties_) {
    // Requested, so active on one rank; spread, on the owner and wherever points write it.
    const auto node = grid.node(t.grid[0], t.grid[1], t.grid[2]);
    if (!node) continue;
    const double wm = t.weight * m[t.node];
    const std::size_t i = 3 * t.node;
    switch (stage) {
      case mpm::GridStage::mass_momentum:
        node->mass += wm;
        for (int d = 0; d < 3; ++d) node->p[d] += wm * v[i + d];
        break;
      case mpm::GridStage::force:
        for (int d = 0; d < 3; ++d) node->f[d] += t.weight * force_[i + d];
        break;
      case mpm::GridStage::remapped:
        for (int d = 0; d < 3; ++d) node->q[d] += wm * v[i + d];
        break;
    }
  }
}

void FarFieldCoupling::take_from_grid(const mpm::SparseGrid& grid, double, double dt) {
  // After update_grid: p = v_I at the start of the step, f = dv_I over it.
  read_ties(grid);
  std::fill(increment_.begin(), increment_.end(), 0.0);
  std::fill(nodal_velocity_.begin(), nodal_velocity_.end(), 0.0);
  for (std::size_t k = 0; k < ties_.size(); ++k) {
    const Tie& t = ties_[k];
    const double* v = &tie_values_[6 * k];  // v_I, dv_I
    const std::size_t i = 3 * t.node;
    for (int d = 0; d < 3; ++d) {
      increment_[i + d] += t.weight * v[3 + d];
      nodal_velocity_[i + d] += t.weight * (v[d] + v[3 + d]);
    }
  }
  const auto m = far_field_.lumped_mass();
  auto v = far_field_.velocity();
  auto u = far_field_.displacement();
  for (std::size_t a = 0; a < m.size(); ++a) {
    if (m[a] == 0.0) continue;  // detached by remove_cells: at rest
    const unsigned fixed = far_field_.fixed(a);
    for (int d = 0; d < 3; ++d) {
      const std::size_t i = 3 * a + d;
      if (fixed & (1u << d)) {
        v[i] = 0.0;
        continue;
      }
      if (tied_[a]) {
        // Like a particle: its velocity takes the FLIP blend, but it moves with the nodal
        // velocity, so both sides of the interface deform with the same velocity field.
        v[i] = flip_ * (v[i] + increment_[i]) + (1.0 - flip_) * nodal_velocity_[i];
        u[i] += dt * nodal_velocity_[i];
      } else {
        v[i] += dt * force_[i] / m[a];
        u[i] += dt * v[i];
      }
    }
  }
}

void FarFieldCoupling::read_ties(const mpm::SparseGrid& grid) {
  const auto read = [&](const Tie& t, double* to) {
    const auto node = grid.node(t.grid[0], t.grid[1], t.grid[2]);  // requested: active
    for (int d = 0; d < 3; ++d) to[d] = node->p[d], to[3 + d] = node->f[d];
  };
  tie_values_.resize(6 * ties_.size());
  if (!ranks_) {
    for (std::size_t k = 0; k < ties_.size(); ++k) read(ties_[k], &tie_values_[6 * k]);
    return;
  }
  const int me = ranks_->comm->rank();
  tie_owner_.resize(ties_.size());
  std::vector<double> mine;  // this rank's ties' values, in tie order
  for (std::size_t k = 0; k < ties_.size(); ++k) {
    tie_owner_[k] = ranks_->owner(block_of(ties_[k]));
    if (tie_owner_[k] != me) continue;
    mine.resize(mine.size() + 6);
    read(ties_[k], &mine[mine.size() - 6]);
  }
  const auto all = ranks_->comm->all_gather(mine);
  std::vector<std::size_t> at(all.size(), 0);
  for (std::size_t k = 0; k < ties_.size(); ++k) {
    const auto r = static_cast<std::size_t>(tie_owner_[k]);
    std::copy_n(&all.at(r).at(at[r]), 6, &tie_values_[6 * k]);
    at[r] += 6;
  }
}

double FarFieldCoupling::stable_time_step() const {
  return safety_ * far_field_.stable_time_step();
}

mpm::CoupledEnergy FarFieldCoupling::energy() const {
  return {far_field_.kinetic_energy(),
          far_field_.strain_energy() + far_field_.plastic_work() + converted_,
          far_field_.momentum()};
}

std::vector<std::pair<std::string, std::span<double>>> FarFieldCoupling::state() {
  auto s = std::vector<std::pair<std::string, std::span<double>>>{
      {"far_field_displacement", far_field_.displacement()},
      {"far_field_velocity", far_field_.velocity()}};
  for (auto& entry : far_field_.plastic_state()) s.push_back(entry);
  if (growing_) {
    s.emplace_back("far_field_zone", std::span<double>(band_.zone));
    s.emplace_back("far_field_converted_energy", std::span<double>(&converted_, 1));
  }
  return s;
}

}  // namespace hvi::coupling
