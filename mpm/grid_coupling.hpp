#pragma once
// Hook points where another model shares the grid's nodes (the finite-element far field of the
// hybrid, external nodal loads). The solver calls them at fixed places of the step, so no model
// has to edit the MPM loop:
//   1. request_blocks       while the grid is built: blocks the model needs active
//   2. add_to_grid          after particles scattered mass and momentum (stage `mass_momentum`),
//                           after they scattered force (stage `force`), and after the MUSL
//                           momentum remap (stage `remapped`)
//   3. take_from_grid       after the nodal velocities at the end of the step are known
//   4. stable_time_step     when the next time step is chosen
// and two for the run around the step: energy() enters the solver's energy balance, state()
// names the arrays a checkpoint saves and a resumed run fills back.
//
// In a run spread over ranks (solver_ranks.cpp) every rank holds the whole coupled model, alike,
// and the solver hands it the ranks (spread()): each grid block has one owner rank, which holds
// the block at every stage, and every rank holding a copy of a block holds the same node values
// (the one-rank bits). So a model adds to every copy it finds, requests only the blocks its rank
// owns, and reads a node from its owner.
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mpm/communicator.hpp"
#include "mpm/grid.hpp"
#include "mpm/types.hpp"

namespace hvi::mpm {

enum class GridStage {
  mass_momentum,  // node mass and p = momentum are scattered
  force,          // f = force is scattered
  remapped,       // MUSL: p = momentum remapped from the updated particle velocities
};

// What a coupled model holds of the balance: its own kinetic and strain energy and momentum.
struct CoupledEnergy {
  double kinetic = 0.0, strain = 0.0;  // J
  Vec3 momentum{};                     // kg m/s
};

// The ranks of a spread run, as a coupled model sees them.
struct GridRanks {
  Communicator* comm = nullptr;
  // The rank owning the grid block with this key (SparseGrid::block_key), under the partition
  // of the step under way: the same answer on every rank.
  std::function<int(std::uint64_t block_key)> owner;
};

class GridCoupling {
 public:
  virtual ~GridCoupling() = default;
  // Called once by a solver spread over ranks, before its first step. A model that does not
  // say how it is spread refuses.
  virtual void spread(const GridRanks& /*ranks*/) {
    throw std::invalid_argument("this coupled model cannot be spread over ranks");
  }
  virtual void request_blocks(std::vector<std::uint64_t>& /*keys*/) const {}
  virtual void add_to_grid(SparseGrid& /*grid*/, GridStage /*stage*/, double /*time*/,
                           double /*dt*/) {}
  virtual void take_from_grid(const SparseGrid& /*grid*/, double /*time*/, double /*dt*/) {}
  virtual double stable_time_step() const { return std::numeric_limits<double>::infinity(); }
  virtual CoupledEnergy energy() const { return {}; }
  // Spread: brings state the model splits over ranks to rank 0, which writes and reports it
  // (Solver::gather_coupled_state, collective). Nothing for a model every rank holds alike.
  virtual void gather_to_root() {}
  // Restartable state: named arrays (names unique across a solver's couplings) a checkpoint
  // writes and a resumed run fills back in place, same sizes.
  virtual std::vector<std::pair<std::string, std::span<double>>> state() { return {}; }
};

}  // namespace hvi::mpm
