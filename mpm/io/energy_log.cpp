#include "mpm/io/energy_log.hpp"

#include <string>
#include <vector>

#include <fmt/format.h>

namespace hvi::mpm::io {

std::string EnergyLog::header(bool coupled, bool contact) {
  return std::string(
             "step,time,dt,kinetic,internal,dissipated,removed,total,momentum_x,momentum_y,"
             "momentum_z,"
             "mass_removed,particles_removed") +
         (coupled ? ",coupled_kinetic,coupled_strain" : "") + (contact ? ",contact" : "");
}

EnergyLog::EnergyLog(const std::filesystem::path& path, std::int64_t resume_step, bool coupled,
                     bool contact)
    : coupled_(coupled), contact_(contact) {
  std::vector<std::string> kept;
  if (resume_step >= 0) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
      if (std::stoll(line.substr(0, line.find(','))) > resume_step) break;
      kept.push_back(line);
    }
  }
  out_.open(path, std::ios::trunc);
  out_ << header(coupled_, contact_) << '\n';
  for (const auto& l : kept) out_ << l << '\n';
  out_.flush();
}

void EnergyLog::write(const Solver& solver, const EnergyReport& e) {
  const auto& r = solver.removed();
  out_ << fmt::format(
      "{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{"
      "}",
      solver.step_count(), solver.time(), solver.next_time_step(), e.kinetic, e.internal,
      e.dissipated, e.removed, e.total(), e.momentum[0] + e.removed_momentum[0],
      e.momentum[1] + e.removed_momentum[1], e.momentum[2] + e.removed_momentum[2], e.removed_mass,
      r.particles);
  if (coupled_) out_ << fmt::format(",{:.17g},{:.17g}", e.coupled_kinetic, e.coupled_strain);
  if (contact_) out_ << fmt::format(",{:.17g}", e.contact);
  out_ << '\n';
  out_.flush();
}

}  // namespace hvi::mpm::io
