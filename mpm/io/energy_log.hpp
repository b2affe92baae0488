#pragma once
// energy.csv: the energy and momentum balance of a run, one row every N steps.
// Columns: step, time (s), dt (s), kinetic, internal (strain), dissipated, removed, total (J),
// momentum_x/y/z (kg m/s, particles in the domain plus those removed plus coupled models),
// mass_removed (kg), particles_removed; and with coupled models (the far field) only,
// coupled_kinetic and coupled_strain (J, included in total); and with contact (grid.contact) only,
// contact (J, the kinetic energy contact took out of the grid nodes, included in total).
#include <filesystem>
#include <fstream>

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

}  // namespace hvi::mpm::io
