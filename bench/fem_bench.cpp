// Benchmark of the finite-element far field. Run: build/hvi_bench --benchmark_filter=FarField
// The quarter of a 300 x 300 mm study panel (t_f = t_r = 0.5 mm, S = 14.2 mm, D_hc = 3 mm,
// t_hc = 0.05 mm; Table 4's Al6061 facesheets and Al5052 core walls from the material library)
// around a 24 x 24 mm MPM zone: elements of 0.4 mm (the grid's cell) at the interface growing by
// 1.25 per element up to 3 mm (6 t_f, the Q1 locking rule), the faces one element and the core
// four elements through the thickness. Arguments, each the cost of one far_field key:
//   degree        1 or 2
//   facesheets    0 elastic, 1 J2 (plasticity = "j2": the return at every facesheet quadrature
//                 point, elastic or not), 2 failing (plasticity = "failing": J2 and the damage)
//   finite        1 for kinematics = "finite" (F S instead of K u at every quadrature point, and
//                 the stretch bound of the step)
//   core          0 elastic, 1 yielding (core = "yielding": the caps' return at every core
//                 quadrature point), 2 failing (core = "failing": the caps and the walls' damage)
// Run with OMP_NUM_THREADS=1 and 2 (the cell loops run on OpenMP threads). Reports
// node_steps_per_s (nodes x steps / wall time) and bytes_per_node. FarFieldPanelTakenOver: the
// cost of the cells a growing zone has taken (below).
#include <benchmark/benchmark.h>

#include "fem/far_field.hpp"
#include "mpm/materials/library.hpp"

namespace {

const hvi::mpm::HydroModels& library(const char* name) {
  return hvi::mpm::find_library_material(name)->parameters;
}

hvi::fem::LayeredMesh study_panel_quarter(int degree, int facesheets, bool finite_strain,
                                          int core_kind) {
  using namespace hvi::fem;
  const double h = 0.4e-3, zone = 12e-3, half = 150e-3;
  const auto &face_metal = library("Al6061"), &wall_metal = library("Al5052");
  LayeredMesh m;
  m.lower = {0, 0};
  // Fine elements (h for Q1, 2h for Q2 so that every node sits on a grid node) over the zone and
  // two elements beyond it, then graded.
  const double fine = degree == 1 ? h : 2 * h;
  m.x_steps = m.y_steps = graded_steps(0, half, 0, zone + 2 * fine, fine, 1.25, 3e-3, 0);
  m.hole = std::array<double, 4>{-1, -1, zone, zone};
  const Orthotropic face = isotropic(face_metal.youngs_modulus, face_metal.poisson_ratio);
  const Orthotropic core =
      honeycomb_core(wall_metal.youngs_modulus, wall_metal.poisson_ratio, 3e-3, 0.05e-3);
  const double rho_core = wall_metal.density * honeycomb_core_solidity(3e-3, 0.05e-3);
  std::optional<hvi::materials::JohnsonCookStrength> j2;
  std::optional<hvi::materials::JohnsonCookDamage> tear;
  if (facesheets >= 1) j2 = face_metal.johnson_cook;
  if (facesheets == 2) tear = face_metal.damage;
  std::optional<CoreYield> caps;
  if (core_kind >= 1)
    caps = honeycomb_core_yield(core, wall_metal.youngs_modulus, wall_metal.poisson_ratio,
                                wall_metal.johnson_cook->A);
  if (core_kind == 2) caps->failure = honeycomb_core_failure(*wall_metal.damage);
  m.layers = {{"rear", -15.2e-3, -14.7e-3, 1, face, face_metal.density, j2, {}, tear},
              {"core", -14.7e-3, -0.5e-3, 4, core, rho_core, {}, caps, {}},
              {"front", -0.5e-3, 0, 1, face, face_metal.density, j2, {}, tear}};
  m.degree = degree;
  m.finite_strain = finite_strain;
  return m;
}

void FarFieldPanel(benchmark::State& state) {
  hvi::fem::FarField f(study_panel_quarter(static_cast<int>(state.range(0)),
                                           static_cast<int>(state.range(1)), state.range(2) != 0,
                                           static_cast<int>(state.range(3))));
  const double dt = 0.9 * f.stable_time_step();
  auto v = f.velocity();
  for (std::size_t a = 0; a < f.node_count(); ++a) v[3 * a + 2] = 1.0;  // something to move
  const int steps = 100;
  for (auto _ : state)
    for (int s = 0; s < steps; ++s) f.step(dt);
  const double nodes = static_cast<double>(f.node_count());
  state.counters["nodes"] = nodes;
  state.counters["cells"] = static_cast<double>(f.cell_count());
  state.counters["dt_ns"] = dt * 1e9;
  state.counters["node_steps_per_s"] =
      benchmark::Counter(nodes * steps * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["bytes_per_node"] = static_cast<double>(f.bytes()) / nodes;
}

// The same far field (Q1, failing J2 facesheets, failing core: the growing-zone runs' settings)
// after a zone grew over it out to `taken` mm from the axis (remove_cells; 0: none). Its step
// should cost in proportion to the cells kept: reports kept_cell_steps_per_s beside the nodes'.
void FarFieldPanelTakenOver(benchmark::State& state) {
  hvi::fem::FarField f(study_panel_quarter(1, 2, false, 2));
  const double taken = 1e-3 * static_cast<double>(state.range(0));
  if (taken > 0) f.remove_cells({-1.0, -1.0, taken, taken});
  const double dt = 0.9 * f.stable_time_step();
  auto v = f.velocity();
  for (std::size_t a = 0; a < f.node_count(); ++a) v[3 * a + 2] = 1.0;
  const int steps = 100;
  for (auto _ : state)
    for (int s = 0; s < steps; ++s) f.step(dt);
  const double nodes = static_cast<double>(f.node_count()),
               kept = static_cast<double>(f.cell_count() - f.removed_cell_count());
  state.counters["cells_kept"] = kept;
  state.counters["batches_visited"] = static_cast<double>(f.evaluated_batch_count());
  state.counters["node_steps_per_s"] =
      benchmark::Counter(nodes * steps * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["kept_cell_steps_per_s"] =
      benchmark::Counter(kept * steps * state.iterations(), benchmark::Counter::kIsRate);
}

BENCHMARK(FarFieldPanelTakenOver)
    ->ArgName("taken_mm")
    ->Arg(0)
    ->Arg(40)
    ->Arg(80)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

BENCHMARK(FarFieldPanel)
    ->ArgNames({"degree", "facesheets", "finite", "core"})
    ->Args({1, 0, 0, 0})
    ->Args({1, 1, 0, 0})
    ->Args({1, 2, 0, 0})
    ->Args({1, 0, 1, 0})
    ->Args({1, 1, 1, 0})
    ->Args({1, 1, 0, 1})
    ->Args({1, 1, 0, 2})
    ->Args({1, 2, 0, 2})
    ->Args({2, 0, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
