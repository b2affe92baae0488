// What each physical model costs: the Taylor-bar scene (cases/verification/taylor_bar.toml, 32,886
// particles, quarter model) run for 100 steps with the models added one at a time, in Al6061 (the
// library entry with data for every model; the fracture energy and scatter follow the spall
// criterion, and the last rung swaps that criterion). Reports
// particle_steps_per_s and bytes_per_particle.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "bench/counters.hpp"

#include "cases/run/build_solver.hpp"
#include "cases/scene/scene.hpp"

namespace {

struct Rung {
  const char* name;
  std::vector<std::string> settings;  // cumulative
};

const std::vector<Rung>& ladder() {
  static const std::vector<Rung> rungs = [] {
    std::vector<Rung> r;
    std::vector<std::string> s = {"library=Al6061", "heating=none", "strength=elastic"};
    r.push_back({"elastic", s});
    s.back() = "strength=johnson-cook";
    r.push_back({"+johnson-cook", s});
    s.push_back("eos=mie-gruneisen");
    r.push_back({"+mie-gruneisen", s});
    s.push_back("viscosity=bulk");
    r.push_back({"+viscosity", s});
    s.push_back("damage=johnson-cook");
    r.push_back({"+damage", s});
    s.push_back("heating=adiabatic");
    r.push_back({"+heating", s});
    s.push_back("failure=max-principal-stress");
    s.push_back("max_principal_stress.limit=1.5e9");
    r.push_back({"+max-principal-stress", s});
    // Failure that softens over a fracture energy (2024-T351's), then failure thresholds with
    // Weibull scatter.
    s.push_back("damage_evolution=fracture-energy");
    s.push_back("fracture_energy.energy=14.3e3");
    r.push_back({"+fracture-energy", s});
    s.push_back("scatter=weibull");
    s.push_back("weibull.modulus=8");
    r.push_back({"+weibull", s});
    // The time-dependent spall criterion in place of the instantaneous one (and of the two above).
    s.resize(s.size() - 6);
    s.push_back("failure=tuler-butcher");
    s.push_back("tuler_butcher.threshold=1.5e9");
    s.push_back("tuler_butcher.time=1e-7");
    r.push_back({"+tuler-butcher(instead)", s});
    return r;
  }();
  return rungs;
}

void TaylorBar(benchmark::State& state, const Rung& rung) {
  omp_set_num_threads(static_cast<int>(state.range(0)));
  std::vector<std::string> overrides;
  for (const auto& s : rung.settings) overrides.push_back("material.42CrMo4." + s);
  const auto scene = hvi::scene::load_scene(
      std::string(HVI_SOURCE_DIR) + "/cases/verification/taylor_bar.toml", overrides);
  const int steps = 100;
  hvi::bench::time_steps(state, steps, [&] {
    auto solver = hvi::driver::make_solver(scene);
    hvi::driver::add_bodies(scene, *solver);
    solver->initialise();
    return solver;
  });
}

const bool registered = [] {
  for (const auto& rung : ladder())
    benchmark::RegisterBenchmark((std::string("TaylorBar/") + rung.name).c_str(), TaylorBar, rung)
        ->Arg(2)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(3);
  return true;
}();

}  // namespace
