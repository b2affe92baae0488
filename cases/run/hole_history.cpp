#include "cases/run/hole_history.hpp"

#include <utility>

#include <fmt/format.h>

namespace hvi::driver {

namespace fs = std::filesystem;

HoleHistory::HoleHistory(fs::path run, std::string front, std::int64_t resume_step) {
  options_.run = std::move(run);
  options_.front = std::move(front);  // as the end-of-run measure: empty, the panel's facesheets
  options_.snapshot = "last";         // the one just written
  const fs::path file = options_.run / hole_history_file;
  if (resume_step < 0)
    fs::remove(file);
  else
    keep_history_rows(file, resume_step);
}

const Measurements& HoleHistory::add() {
  last_ = measure_run(options_);
  append_history_row(*last_, options_.run / hole_history_file);
  return *last_;
}

const Measurements* HoleHistory::at_step(std::int64_t step) const {
  return last_ && last_->step == step ? &*last_ : nullptr;
}

std::string hole_summary(const Measurements& m) {
  constexpr double mm = 1e-3;
  auto sheet = [](const std::optional<SheetMeasurement>& s, const char* name, const char* symbol) {
    if (!s) return std::string();
    if (!s->hole.perforated) return fmt::format("{} NP", name);
    if (s->hole.resolution == 0) return fmt::format("{} gone (nothing attached left)", name);
    return fmt::format("{} {} = {:.3f} mm", name, symbol, s->hole.D / mm);
  };
  std::string line = sheet(m.front, "front", "D_f");
  const std::string rear = sheet(m.rear, "rear", "D_r");
  if (!rear.empty()) line += (line.empty() ? "" : ", ") + rear;
  if (m.bulge) line += fmt::format(" (bulge {:.3f} mm)", m.bulge->displacement / mm);
  if (!m.debris_behind.empty()) line += fmt::format(", debris {:.4g} mg", m.debris.mass * 1e6);
  return line;
}

}  // namespace hvi::driver
