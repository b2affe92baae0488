#pragma once
// energy.csv: the energy and momentum balance of a run, one row every N steps.
// Columns: step, time (s), dt (s), kinetic, internal (strain), dissipated, removed, total (J),
// momentum_x/y/z (kg m/s, particles in the domain plus those removed plus coupled models),
// mass_removed (kg), particles_removed; and with coupled models (the far field) only,
// coupled_kinetic and coupled_strain (J, included in total); and with contact (grid.contact) only,
// contact (J, the kinetic energy contact took out of the grid nodes, included in total).
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "mpm/solver.hpp"

namespace hvi::mpm::io {

class EnergyLog {
 public:
  // Starts a new log (truncating), or for a resumed run keeps the rows up to `resume_step`.
  EnergyLog(const std::filesystem::path& path, std::int64_t resume_step = -1, bool coupled = false,
            bool contact = false);
  void write(const Solver& solver, const EnergyReport& energy);
  static std::string header(bool coupled = false, bool contact = false);

 private:
  std::ofstream out_;
  bool coupled_, contact_;
};

// energy_ledger.csv (output.energy_ledger; mpm/energy_ledger.hpp): at every energy.csv row, one
// row per body and one for all bodies: step, time (s), body, the ledger's columns (J, cumulative),
// then stress_error = stress_internal + force_work (the internal energy its stress update booked
// beyond the work its stresses did on the grid) and transfer_minus_work = transfer_kinetic -
// force_work (for a body, the kinetic energy it took from the others' stresses as well; for all,
// the transfer error).
class LedgerLog {
 public:
  LedgerLog(const std::filesystem::path& path, std::vector<std::string> bodies,
            std::int64_t resume_step = -1);
  void write(const Solver& solver, const EnergyReport& energy);

 private:
  std::ofstream out_;
  std::vector<std::string> bodies_;
};

}  // namespace hvi::mpm::io
