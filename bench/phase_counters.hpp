#pragma once
// The seconds of each phase of the step (mpm/phase_timer.hpp) of one iteration's solver as
// benchmark counters: "move particles" becomes s_move_particles.
#include <benchmark/benchmark.h>

#include <string>

#include "mpm/phase_timer.hpp"

namespace hvi::bench {

inline std::string counter_name(const std::string& phase) {
  std::string s = "s_";
  for (const char c : phase)
    if (c == ' ' || c == ':' || c == '+') {
      if (s.back() != '_') s += '_';
    } else {
      s += c;
    }
  return s;
}

inline void add_phase_counters(benchmark::State& state, const mpm::PhaseTimer& phases) {
  for (const auto& e : phases.entries()) state.counters[counter_name(e.name)] = e.seconds;
}

}  // namespace hvi::bench
