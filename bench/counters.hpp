#pragma once
// The counters every MPM benchmark reports: particle_steps_per_s (particles x steps / wall
// time), bytes_per_particle (all particle arrays, grid and bins over the particle count), the
// threads, and the seconds of each phase of the step (mpm/phase_timer.hpp) of one iteration's
// solver, as s_<phase> ("move particles" becomes s_move_particles).
#include <benchmark/benchmark.h>

#include <string>

#include "mpm/phase_timer.hpp"
#include "mpm/solver.hpp"

namespace hvi::bench {

// How a whole-run benchmark is timed: once on 1 and once on 2 threads (its argument), wall time.
inline void on_one_and_two_threads(benchmark::internal::Benchmark* b) {
  b->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
}

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

// What an iteration's solver leaves for the counters, taken after its timed steps.
struct Measured {
  double particles = 0.0, bytes = 0.0;
  mpm::PhaseTimer phases;
  void take(mpm::Solver& solver) {
    particles = static_cast<double>(solver.particles().size());
    bytes = static_cast<double>(solver.bytes());
    phases = solver.timer();
  }
};

inline void report(benchmark::State& state, const Measured& m, int steps) {
  state.counters["particles"] = m.particles;
  state.counters["threads"] = static_cast<double>(state.range(0));
  state.counters["particle_steps_per_s"] = benchmark::Counter(
      m.particles * steps * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["bytes_per_particle"] = m.bytes / m.particles;
  for (const auto& e : m.phases.entries()) state.counters[counter_name(e.name)] = e.seconds;
}

// Times `steps` steps of a solver that `make()` builds, untimed (with any warm-up), in every
// iteration, and reports the counters of the last.
template <class Make>
void time_steps(benchmark::State& state, int steps, Make make) {
  Measured measured;
  for (auto _ : state) {
    state.PauseTiming();
    auto solver = make();
    state.ResumeTiming();
    for (int s = 0; s < steps; ++s) solver->step();
    state.PauseTiming();
    measured.take(*solver);
    state.ResumeTiming();
  }
  report(state, measured, steps);
}

}  // namespace hvi::bench
