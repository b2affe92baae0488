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

namespace {

// Opens a log for writing under `header`: a new one, or for a resumed run the rows of the old one
// up to `resume_step` (the first column is the step).
void open_log(std::ofstream& out, const std::filesystem::path& path, const std::string& header,
              std::int64_t resume_step) {
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
  out.open(path, std::ios::trunc);
  out << header << '\n';
  for (const auto& l : kept) out << l << '\n';
  out.flush();
}

}  // namespace

EnergyLog::EnergyLog(const std::filesystem::path& path, std::int64_t resume_step, bool coupled,
                     bool contact)
    : coupled_(coupled), contact_(contact) {
  open_log(out_, path, header(coupled_, contact_), resume_step);
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

LedgerLog::LedgerLog(const std::filesystem::path& path, std::vector<std::string> bodies,
                     std::int64_t resume_step)
    : bodies_(std::move(bodies)) {
  std::string header = "step,time,body";
  for (int c = 0; c < ledger::columns; ++c) header += std::string(",") + ledger::name(c);
  open_log(out_, path, header + ",stress_error,transfer_minus_work", resume_step);
}

void LedgerLog::write(const Solver& solver, const EnergyReport& e) {
  std::array<double, ledger::columns> all{};
  const auto row = [&](const std::string& body, const std::array<double, ledger::columns>& r) {
    out_ << fmt::format("{},{:.17g},{}", solver.step_count(), solver.time(), body);
    for (const double x : r) out_ << fmt::format(",{:.17g}", x);
    out_ << fmt::format(",{:.17g},{:.17g}\n", r[ledger::stress_internal] + r[ledger::force_work],
                        r[ledger::transfer_kinetic] - r[ledger::force_work]);
  };
  for (std::size_t b = 0; b < e.ledger.size(); ++b) {
    row(bodies_.at(b), e.ledger[b]);
    for (int c = 0; c < ledger::columns; ++c) all[c] += e.ledger[b][c];
  }
  row("all", all);
  out_.flush();
}

}  // namespace hvi::mpm::io
