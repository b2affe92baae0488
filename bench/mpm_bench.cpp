// Benchmarks of the MPM core. Run: build/hvi_bench --benchmark_filter=ElasticBlock
// Reports particle_steps_per_s (particles x steps / wall time) and bytes_per_particle (all
// particle arrays, grid and bins divided by the particle count).
#include <benchmark/benchmark.h>
#include <omp.h>

#include "bench/counters.hpp"

#include "bench/block_setup.hpp"

namespace {

// 1,000,000 particles (50^3 cells x 8 particles per cell), MUSL, 100 steps; range(0) threads.
void run_block(benchmark::State& state, hvi::mpm::ShapeFunction shape,
               hvi::mpm::Dilatation dilatation = hvi::mpm::Dilatation::particle,
               bool contact = false) {
  const int threads = static_cast<int>(state.range(0));
  omp_set_num_threads(threads);
  hvi::mpm::SolverSettings settings;
  settings.shape = shape;
  settings.dilatation = dilatation;
  if (contact) settings.contact = hvi::mpm::ContactSettings{};
  const int steps = 100;
  hvi::bench::time_steps(state, steps, [&] { return hvi::bench::elastic_block(50, 2, settings); });
}

// The reference workload: linear shape functions.
void ElasticBlock(benchmark::State& state) {
  run_block(state, hvi::mpm::ShapeFunction::linear);
}
// The scene default: cpGIMP (27-node stencils).
void ElasticBlockCpGimp(benchmark::State& state) {
  run_block(state, hvi::mpm::ShapeFunction::cpgimp);
}
// cpGIMP with grid.dilatation = "node-average": two more passes over the points per step.
void ElasticBlockCpGimpNodeAverage(benchmark::State& state) {
  run_block(state, hvi::mpm::ShapeFunction::cpgimp, hvi::mpm::Dilatation::node_average);
}

// cpGIMP with [contact] between the block's two halves: a second grid, a normal pass over the
// blocks where they meet and the corrections at the nodes they share.
void ElasticBlockCpGimpContact(benchmark::State& state) {
  run_block(state, hvi::mpm::ShapeFunction::cpgimp, hvi::mpm::Dilatation::particle, true);
}

BENCHMARK(ElasticBlock)->Apply(hvi::bench::on_one_and_two_threads);
BENCHMARK(ElasticBlockCpGimp)->Apply(hvi::bench::on_one_and_two_threads);
BENCHMARK(ElasticBlockCpGimpNodeAverage)->Apply(hvi::bench::on_one_and_two_threads);
BENCHMARK(ElasticBlockCpGimpContact)->Apply(hvi::bench::on_one_and_two_threads);

}  // namespace

BENCHMARK_MAIN();
