// The machine's memory bandwidth, for the roofline of the particle benchmarks: the STREAM triad
// a_i = b_i + s c_i over three arrays of 2^25 doubles (768 MiB in all, far beyond any cache),
// static schedule so each thread streams its own part. Reports bytes_per_s counted the STREAM way,
// 24 bytes per element (two loads, one store; the store's write-allocate read is not counted).
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cstdint>
#include <vector>

namespace {

void Triad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  omp_set_num_threads(threads);
  const std::int64_t n = std::int64_t{1} << 25;
  std::vector<double> a(n), b(n), c(n);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {  // first touch by the thread that streams it
    a[i] = 0.0;
    b[i] = 1.0;
    c[i] = 2.0;
  }
  const double s = 3.0;
  for (auto _ : state) {
    double* pa = a.data();
    const double* pb = b.data();
    const double* pc = c.data();
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::DoNotOptimize(pa);
    benchmark::ClobberMemory();
  }
  state.counters["threads"] = threads;
  state.counters["bytes_per_s"] =
      benchmark::Counter(24.0 * static_cast<double>(n) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}

BENCHMARK(Triad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

}  // namespace
