#include "mpm/io/energy_log.hpp"

#include <string>
#include <vector>

#include <fmt/format.h>

namespace hvi::mpm::io {

std::string EnergyLog::header() {
  return "step,time,dt,kinetic,internal,dissipated,removed,total,momentum_x,momentum_y,momentum_z,"
         "mass_removed,particles_removed";
}

EnergyLog::EnergyLog(const std::filesystem::path& path, std::int64_t resume_step) {
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
  out_ << header() << '\n';
  for (const auto& l : kept) out_ << l << '\n';
  out_.flush();
}

void EnergyLog::write(const Solver& solver, const EnergyReport& e) {
  const auto& r = solver.removed();
  out_ << fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{}\n",
                      solver.step_count(), solver.time(), solver.next_time_step(), e.kinetic,
                      e.internal, e.dissipated, e.removed, e.total(),
                      e.momentum[0] + e.removed_momentum[0], e.momentum[1] + e.removed_momentum[1],
                      e.momentum[2] + e.removed_momentum[2], e.removed_mass, r.particles);
  out_.flush();
}

}  // namespace hvi::mpm::io
