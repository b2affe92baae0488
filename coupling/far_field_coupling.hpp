#pragma once
// The hybrid: the finite-element far field (fem/) and the MPM impact zone (mpm/) share the
// background-grid nodes of an interface band, and advance with one time step.
//
// Every far-field node within `band` of the MPM zone is tied to the grid node it sits on (in plane
// it lies exactly on one; through the thickness a panel's layer surfaces need not fall on grid
// planes, so a node between two planes is tied to both with linear weights w, which are 0 and 1
// when it does lie on a plane). For a tied node a, at each step (MUSL, USL or USF alike, through
// the hooks of mpm/grid_coupling.hpp):
//   m_I += w m_a                      lumped far-field mass      (stage mass_momentum)
//   p_I += w m_a v_a^(n-1/2)          far-field momentum
//   f_I += w f_a,  f = -K u^n         far-field internal force   (stage force; with finite
//                                      strain -int F S . grad N; J2 stresses in plastic
//                                      facesheets, their state committed here)
// the grid solves v_I, dv_I = dt f_I / m_I once for both sides, and the tied node takes
//   v_a <- flip (v_a + sum_I w dv_I) + (1 - flip) sum_I w (v_I + dv_I)
// with the solver's FLIP fraction, and moves as a particle does, with the nodal velocity:
//   u_a += dt sum_I w (v_I + dv_I)
// (its own v_a would let the far field deform with a velocity field other than the particles' at
// the interface, doing spurious work: +4.5% of the impact energy in tests/driver's small hybrid,
// -0.13% with the nodal velocity). Every other far-field node takes its own central-difference
// step, v += dt f / m, u += dt v. The particles see the same nodal increments, so the
// total momentum of particles plus far field changes by dt sum_I f_I = 0: it is conserved
// exactly, for any FLIP fraction (flip = 1 adds every node's increment to its own velocity; PIC
// gives every tied node and particle the nodal velocity). With MUSL the tied nodes add their new
// momentum w m_a v_a to the remap (stage remapped).
//
// The far field's stable step (its element bound, times `safety`; with finite strain reduced by
// the current stretch) enters the solver's choice of time step at every step, so both sides take
// the smaller of the two limits.
//
// Spread over ranks, every rank holds the whole far field and steps it alike (it is small beside
// the zone: that is what it is for), while its element work is split over the ranks and merged
// back bitwise (fem::FarField::spread). Each rank adds the tied nodes to the copies of the grid
// blocks it holds and requests the blocks it owns; after the grid update, each tie's (v_I, dv_I)
// is read on the rank owning its block and gathered to every rank, which sums them per node in
// tie order, as one rank does: every rank's far field keeps the one-rank bits.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "fem/far_field.hpp"
#include "mpm/grid_coupling.hpp"

namespace hvi::coupling {

struct InterfaceBand {
  std::array<double, 4> zone{};  // in-plane box of the MPM zone: x0, y0, x1, y1 (m)
  double width = 0.0;            // far-field nodes up to this far outside the zone are tied (m)
};

class FarFieldCoupling : public mpm::GridCoupling {
 public:
  // Throws std::invalid_argument when a tied node lies outside the grid or the band ties none.
  FarFieldCoupling(fem::FarField& far_field, const mpm::GridGeometry& grid,
                   const InterfaceBand& band, double flip = 1.0, double safety = 0.9);

  void spread(const mpm::GridRanks& ranks) override;
  void gather_to_root() override { far_field_.gather_state_to_root(); }
  void request_blocks(std::vector<std::uint64_t>& keys) const override;
  void add_to_grid(mpm::SparseGrid& grid, mpm::GridStage stage, double time, double dt) override;
  void take_from_grid(const mpm::SparseGrid& grid, double time, double dt) override;
  double stable_time_step() const override;
  // The far field's kinetic energy 1/2 sum m v^2 (half-step velocities), its internal energy
  // (elastic strain energy, 1/2 u.K u when elastic, plus the plastic work of J2 facesheets, plus
  // the energy take-overs did not carry over to points) and momentum; the solver adds them to its
  // energy balance.
  mpm::CoupledEnergy energy() const override;
  // far_field_displacement and far_field_velocity, 3 per node, and with plastic facesheets their
  // plastic state and work, for checkpoints.
  std::vector<std::pair<std::string, std::span<double>>> state() override;

  // A zone that grows (coupling/zone_growth.hpp): the band tied now and the energy booked as
  // converted are then part of the state (checkpoints), and the converted energy part of the
  // internal energy.
  void enable_growth() { growing_ = true; }
  bool growing() const { return growing_; }
  const InterfaceBand& band() const { return band_; }
  void book_conversion(double energy) { converted_ += energy; }
  double converted_energy() const { return converted_; }

  // Ties the nodes of a new band (the MPM zone grown over far-field cells that
  // fem::FarField::remove_cells took out), as the constructor does: a node detached by the
  // removal (no mass) is not tied and takes no step. Throws as the constructor does.
  void retie(const InterfaceBand& band);

  std::size_t tied_node_count() const { return tied_nodes_; }
  // Tied nodes that lie exactly on a grid node (weight 1).
  std::size_t exact_node_count() const { return exact_nodes_; }
  const fem::FarField& far_field() const { return far_field_; }
  // The far-field internal force of the last step (N, 3 per node).
  const std::vector<double>& internal_force() const { return force_; }

 private:
  struct Tie {
    std::uint32_t node;       // far-field node
    std::array<int, 3> grid;  // global grid node (i, j, k)
    double weight;
  };
  fem::FarField& far_field_;
  mpm::GridGeometry grid_;
  InterfaceBand band_;
  bool growing_ = false;
  double converted_ = 0.0;  // J
  double flip_, safety_;
  // Per tie: the nodal velocity at the start of the step and its increment (6 values), read
  // from the rank owning the tie's block when spread.
  void read_ties(const mpm::SparseGrid& grid);
  std::uint64_t block_of(const Tie& t) const {
    return mpm::SparseGrid::key_of_node(t.grid[0], t.grid[1], t.grid[2]);
  }

  std::optional<mpm::GridRanks> ranks_;
  std::vector<Tie> ties_;                           // grouped by far-field node
  std::vector<double> tie_values_;                  // 6 per tie: v_I, dv_I
  std::vector<int> tie_owner_;                      // spread: the rank owning each tie's block
  std::vector<std::uint8_t> tied_;                  // per far-field node
  std::vector<double> force_;                       // -K u^n, 3 per node
  std::vector<double> increment_, nodal_velocity_;  // per node: sum w dv_I, sum w (v_I + dv_I)
  std::size_t tied_nodes_ = 0, exact_nodes_ = 0;
};

}  // namespace hvi::coupling
