#pragma once
// A cube of elastic material sampled on a regular lattice, the workload of the core benchmarks.
#include <memory>

#include "mpm/elastic.hpp"
#include "mpm/solver.hpp"

namespace hvi::bench {

// A cube of `cells_per_edge` cells of 1 mm, `ppc` particles per cell per direction, moving at
// 10 m/s along x with a small shear so that stresses are not zero; grid padded by 8 cells. With
// settings.contact, its upper half (z above the middle) is a second body on the contact's field:
// the fields meet over a whole cross-section, contact's worst case.
inline std::unique_ptr<mpm::Solver> elastic_block(int cells_per_edge, int ppc,
                                                  mpm::SolverSettings settings) {
  const double h = 1e-3;
  mpm::GridGeometry g;
  g.cell_size = h;
  const int pad = 8;
  g.origin = {-pad * h, -pad * h, -pad * h};
  g.cells = {cells_per_edge + 2 * pad, cells_per_edge + 2 * pad, cells_per_edge + 2 * pad};
  std::vector<std::unique_ptr<mpm::Material>> materials;
  materials.push_back(std::make_unique<mpm::LinearElastic>("aluminium", 2700.0, 70e9, 0.33));
  const bool halves = settings.contact.has_value();
  if (halves) settings.contact->impactor = {0, 1};
  auto solver = std::make_unique<mpm::Solver>(
      g, settings, std::move(materials),
      halves ? std::vector<std::string>{"block", "top"} : std::vector<std::string>{"block"},
      std::vector<mpm::GridBoundary>{});
  auto& P = solver->particles();
  const int n = cells_per_edge * ppc;
  const double dx = h / ppc;
  P.resize(static_cast<std::size_t>(n) * n * n);
  std::size_t p = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++p) {
        const double x[3] = {(i + 0.5) * dx, (j + 0.5) * dx, (k + 0.5) * dx};
        for (int d = 0; d < 3; ++d) P.position[3 * p + d] = x[d];
        P.velocity[3 * p + 0] = 10.0 + 100.0 * (x[1] - 0.5 * n * dx);
        P.volume0[p] = P.volume[p] = dx * dx * dx;
        P.mass[p] = 2700.0 * dx * dx * dx;
        P.id[p] = static_cast<std::int64_t>(p);
        if (halves && 2 * k >= n) P.body[p] = 1;
      }
  solver->initialise();
  return solver;
}

}  // namespace hvi::bench
