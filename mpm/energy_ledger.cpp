#include "mpm/energy_ledger.hpp"

#include <cstdint>

#include <omp.h>

#include "mpm/point_exchange.hpp"
#include "mpm/types.hpp"

namespace hvi::mpm {

const char* ledger::name(int column) {
  static const char* names[columns] = {"transfer_kinetic", "force_work",  "stress_internal",
                                       "failed_internal",  "failed_work", "removed"};
  return names[column];
}

EnergyLedger::EnergyLedger(std::size_t bodies)
    : bodies_(bodies), pending_(bodies * ledger::columns) {}

// Each thread adds its points' terms to sums of its own, which are then added to pending_: the
// sums are exact, so neither the split among threads nor the order of the merge changes a bit.
template <class F>
void EnergyLedger::add_by_body(const Particles& P, F&& f) {
  const auto n = static_cast<std::int64_t>(P.size());
#pragma omp parallel
  {
    std::vector<ExactSum> mine(pending_.size());
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) f(p, &mine[at(static_cast<std::size_t>(P.body[p]), 0)]);
#pragma omp critical(energy_ledger)
    for (std::size_t k = 0; k < mine.size(); ++k) pending_[k] += mine[k];
  }
}

namespace {

double kinetic(const Particles& P, std::int64_t p) {
  const double* v = &P.velocity[3 * p];
  return 0.5 * P.mass[p] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

bool is_failed(const double* failed, std::int64_t p) {
  return failed && failed[p] > 0.0;
}

}  // namespace

void EnergyLedger::start_transfer(const Particles& P) {
  before_.resize(P.size());
  const auto n = static_cast<std::int64_t>(P.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) before_[p] = kinetic(P, p);
}

void EnergyLedger::end_transfer(const Particles& P) {
  add_by_body(P, [&](std::int64_t p, ExactSum* row) {
    row[ledger::transfer_kinetic] += kinetic(P, p);
    row[ledger::transfer_kinetic] += -before_[p];
  });
}

// W_p = -V_p sigma_p : Dbar_p dt, Dbar the symmetric part of Lbar (sigma is symmetric).
void EnergyLedger::add_force_work(const Particles& P, const std::vector<double>& Lbar, double dt,
                                  const double* failed) {
  add_by_body(P, [&](std::int64_t p, ExactSum* row) {
    double D[6], W[9];
    split_velocity_gradient(&Lbar[9 * p], D, W);
    const double work = -P.volume[p] * contract_sym(&P.stress[6 * p], D) * dt;
    row[ledger::force_work] += work;
    if (is_failed(failed, p)) row[ledger::failed_work] += work;
  });
}

void EnergyLedger::start_stress(const Particles& P) {
  before_.resize(P.size());
  const auto n = static_cast<std::int64_t>(P.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) before_[p] = P.mass[p] * P.internal_energy[p];
}

void EnergyLedger::end_stress(const Particles& P, const double* failed) {
  add_by_body(P, [&](std::int64_t p, ExactSum* row) {
    const double now = P.mass[p] * P.internal_energy[p];
    row[ledger::stress_internal] += now;
    row[ledger::stress_internal] += -before_[p];
    if (is_failed(failed, p)) {
      row[ledger::failed_internal] += now;
      row[ledger::failed_internal] += -before_[p];
    }
  });
}

void EnergyLedger::close_step(Communicator* comm, std::vector<double>& totals) {
  if (comm && comm->size() > 1) add_over_ranks(*comm, pending_);
  totals.resize(pending_.size(), 0.0);
  for (std::size_t k = 0; k < pending_.size(); ++k) {
    totals[k] += pending_[k].value();
    pending_[k] = ExactSum{};
  }
}

}  // namespace hvi::mpm
