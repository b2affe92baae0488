// The production workload: the demo scene (cases/demo.toml: full physics, cpGIMP, MUSL, symmetry
// planes) on 0.2 mm cells, 742,000 points, stepped (after 3 untimed steps) from a checkpoint taken
// 2 us into the impact, when the front sheet is open and failure, damage and debris are active.
// Reports particle_steps_per_s, bytes_per_particle and the seconds of each phase of the step.
//
// The checkpoint is made on first use (about 350 steps from t = 0) and kept in
// HVI_BENCH_CHECKPOINT (default: bench_data/honeycomb_0.2mm.h5 under the working directory), so
// that two builds can be timed from the same state. HVI_BENCH_STEPS sets the number of steps (40).
#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "bench/counters.hpp"
#include "cases/run/build_solver.hpp"
#include "cases/scene/scene.hpp"
#include "mpm/io/checkpoint.hpp"

namespace {

namespace fs = std::filesystem;

constexpr double checkpoint_time = 2e-6;  // s
constexpr int warmup_steps = 3;

// 40 steps, or HVI_BENCH_STEPS.
int steps() {
  const char* env = std::getenv("HVI_BENCH_STEPS");
  return env ? std::atoi(env) : 40;
}

// The demo on 0.2 mm cells; HVI_BENCH_SET adds overrides, separated by ';'.
std::vector<std::string> overrides(bool node_average) {
  std::vector<std::string> o = {"grid.cell_size=0.2mm"};
  if (node_average) o.push_back("grid.dilatation=node-average");
  if (const char* env = std::getenv("HVI_BENCH_SET")) {
    std::string extra = env;
    for (std::size_t start = 0; start < extra.size();) {
      const std::size_t end = std::min(extra.find(';', start), extra.size());
      if (end > start) o.push_back(extra.substr(start, end - start));
      start = end + 1;
    }
  }
  return o;
}

fs::path checkpoint_path() {
  const char* env = std::getenv("HVI_BENCH_CHECKPOINT");
  return env ? fs::path(env) : fs::path("bench_data") / "honeycomb_0.2mm.h5";
}

hvi::scene::Scene demo_scene(bool node_average) {
  return hvi::scene::load_scene(std::string(HVI_SOURCE_DIR) + "/cases/demo.toml",
                                overrides(node_average));
}

// The state 2 us into the impact (always with the particle dilatation: the node average adds no
// particle state, so the same checkpoint serves both workloads).
void make_checkpoint(const fs::path& path) {
  const auto scene = demo_scene(false);
  auto solver = hvi::driver::make_solver(scene);
  hvi::driver::add_bodies(scene, *solver);
  solver->initialise();
  fmt::print(stderr, "honeycomb: making {} ({} points, to t = {} us)\n", path.string(),
             solver->particles().size(), checkpoint_time * 1e6);
  while (solver->time() < checkpoint_time * (1 - 1e-12))
    solver->step(checkpoint_time - solver->time());
  if (path.has_parent_path()) fs::create_directories(path.parent_path());
  hvi::mpm::io::write_checkpoint(path, *solver, {});
}

void Honeycomb(benchmark::State& state, bool node_average) {
  const int threads = static_cast<int>(state.range(0));
  const fs::path path = checkpoint_path();
  if (!fs::exists(path)) make_checkpoint(path);
  omp_set_num_threads(threads);
  const auto scene = demo_scene(node_average);
  const int steps = ::steps();
  hvi::bench::time_steps(state, steps, [&] {
    auto solver = hvi::driver::make_solver(scene);
    hvi::mpm::io::read_checkpoint(path, *solver);
    // Warm-up: the first steps after a restore fault in the pages of the grid and caches.
    for (int s = 0; s < warmup_steps; ++s) solver->step();
    solver->timer().clear();
    return solver;
  });
}

void HoneycombParticle(benchmark::State& state) {
  Honeycomb(state, false);
}
void HoneycombNodeAverage(benchmark::State& state) {
  Honeycomb(state, true);
}

BENCHMARK(HoneycombParticle)->Name("Honeycomb")->Apply(hvi::bench::on_one_and_two_threads);
BENCHMARK(HoneycombNodeAverage)->Apply(hvi::bench::on_one_and_two_threads);

}  // namespace
