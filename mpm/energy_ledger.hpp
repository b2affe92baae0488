#pragma once
// The energy ledger (output.energy_ledger): where a run's energy balance is made or lost, body by
// body and phase by phase. An explicit MPM step changes its points' energy in two phases only:
// the grid-to-particle update changes their kinetic energy, the stress update their internal
// energy. Between the two stands the work the points' stresses do on the grid nodes over the step,
//   W_b = sum_{p in b} -V_p sigma_p : Lbar_p dt,   Lbar_p = sum_I vbar_I (x) grad N_I(x_p),
// with vbar_I = v_I + dv_I / 2 the nodal velocity at mid-step, so that sum_b W_b = sum_I f_I .
// vbar_I dt: the kinetic energy the internal force gives the nodes in the grid update. A step that
// conserves energy has
//   dK (transfer) = sum_b W_b    the kinetic energy the nodes gained reaches the points, and
//   dU_b (stress) = -W_b         what body b's stresses did is what its internal energy lost.
// Per body, cumulative from the start of the run (J):
//   transfer_kinetic  dK of the body's points in the grid-to-particle update
//   force_work        W_b
//   stress_internal   d(sum m e) of the body's points in the stress update
//   failed_internal   the part of stress_internal of points failed or eroded after their update
//   failed_work       the part of force_work of points failed or eroded at the step's start
//   removed           kinetic + internal energy of the body's points that left the grid
// The run's two errors follow: the transfer error, sum_b (transfer_kinetic - force_work) (FLIP's
// update, boundary conditions, contact's corrections), and each body's stress error,
// stress_internal + force_work (the strain rate of the MUSL remap instead of vbar, failure's
// tension cut, the update's own integration). Far-field coupling forces are not in it.
//
// Each phase's terms are exact sums (exact_sum.hpp), added over the ranks at the end of the step
// and only then rounded, so the ledger is bitwise the same for any thread and rank count; its
// totals live in SolverState, so also on resume.
#include <cstddef>
#include <vector>

#include "mpm/communicator.hpp"
#include "mpm/exact_sum.hpp"
#include "mpm/particles.hpp"

namespace hvi::mpm {

namespace ledger {
enum Column : int {
  transfer_kinetic,
  force_work,
  stress_internal,
  failed_internal,
  failed_work,
  removed,
  columns
};
const char* name(int column);
}  // namespace ledger

class EnergyLedger {
 public:
  explicit EnergyLedger(std::size_t bodies);
  std::size_t bodies() const { return bodies_; }

  // Around the grid-to-particle update.
  void start_transfer(const Particles& particles);
  void end_transfer(const Particles& particles);
  // W_b from Lbar_p (9 per point, row-major) with the start-of-step stress and volume;
  // `failed` is the points' failure state (nullptr where no material can fail).
  void add_force_work(const Particles& particles, const std::vector<double>& mid_gradient,
                      double dt, const double* failed);
  // Around the stress update.
  void start_stress(const Particles& particles);
  void end_stress(const Particles& particles, const double* failed);
  // A point of `body` leaving the grid with this kinetic plus internal energy.
  void add_removed(std::size_t body, double energy) {
    pending_[at(body, ledger::removed)] += energy;
  }
  // Ends the step: the step's sums (over the ranks, with `comm`) rounded and added to `totals`
  // (bodies x columns, row by body).
  void close_step(Communicator* comm, std::vector<double>& totals);

 private:
  std::size_t at(std::size_t body, int column) const {
    return body * ledger::columns + static_cast<std::size_t>(column);
  }
  // f(p, row) for every point, row the thread's sums of the point's body; merged into pending_.
  template <class F>
  void add_by_body(const Particles& particles, F&& f);

  std::size_t bodies_;
  std::vector<ExactSum> pending_;  // this step's terms, bodies x columns
  std::vector<double> before_;     // per point: its kinetic or internal energy before a phase
};

}  // namespace hvi::mpm
