#pragma once
// The coupled bar of the coupling tests: 1 mm cells, x in [0, 120 h], material points left of
// x = 60 h and finite elements right of it, rollers on the four long sides (uniaxial strain, so
// the closed forms are 1D); and the uniform-strain patch test across its interface.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "fem/far_field.hpp"
#include "geometry/primitives.hpp"
#include "tests/mpm/mpm_test_helpers.hpp"

namespace hvi::coupling::test {

constexpr double h = 1e-3;                    // grid cell and far-field element, m
constexpr int mpm_cells = 60, fe_cells = 60;  // bar x in [0, 120 h]: MPM left, FE right
constexpr double rho = 2700, E = 70e9, nu = 0.33;
inline const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
inline const double M = lambda + 2 * mu,
                    c = std::sqrt(M / rho);  // constrained modulus, bar wave speed

inline mpm::GridGeometry bar_grid() {
  return mpm::test::grid({-4 * h, 0, 0}, h, {130, 2, 2});
}

// Rollers on y = 0, 2h and z = 0, 2h.
inline std::vector<mpm::GridBoundary> rollers() {
  using mpm::BoundaryType;
  return {{1, 0, true, BoundaryType::symmetry},
          {1, 2, false, BoundaryType::symmetry},
          {2, 0, true, BoundaryType::symmetry},
          {2, 2, false, BoundaryType::symmetry}};
}

// Material points over [0, length_cells h].
inline std::unique_ptr<mpm::Solver> bar_solver(double length_cells) {
  mpm::SolverSettings s;
  s.shape = mpm::ShapeFunction::cpgimp;
  s.scheme = mpm::UpdateScheme::musl;
  auto solver = std::make_unique<mpm::Solver>(
      bar_grid(), s,
      mpm::test::one_material(std::make_unique<mpm::LinearElastic>("al", rho, E, nu)),
      std::vector<std::string>{"bar"}, rollers());
  mpm::test::add_body(*solver, geometry::Box({0, 0, 0}, {length_cells * h, 2 * h, 2 * h}), 2, 0, 0,
                      mpm::test::uniform({0, 0, 0}));
  return solver;
}

// Trilinear bricks one cell wide over [60 h, 120 h], rollers on the long sides.
inline std::unique_ptr<fem::FarField> bar_far_field() {
  fem::LayeredMesh m;
  m.lower = {mpm_cells * h, 0};
  m.x_steps.assign(fe_cells, h);
  m.y_steps.assign(2, h);
  m.layers = {{"bar", 0, 2 * h, 2, fem::isotropic(E, nu), rho, {}, {}, {}}};
  m.degree = 1;
  auto f = std::make_unique<fem::FarField>(m);
  const auto x = f->reference_positions();
  for (std::size_t a = 0; a < f->node_count(); ++a) {
    if (x[3 * a + 1] < 1e-12 || x[3 * a + 1] > 2 * h - 1e-12) f->fix(a, 0b010);
    if (x[3 * a + 2] < 1e-12 || x[3 * a + 2] > 2 * h - 1e-12) f->fix(a, 0b100);
  }
  return f;
}

// Uniform uniaxial strain eps on both sides: the particles' stress and strain energy, the far
// field's displacement u_x = eps x.
inline void strain_uniformly(mpm::Particles& P, fem::FarField& far, double eps) {
  for (std::size_t p = 0; p < P.size(); ++p) {
    P.stress[6 * p + mpm::sym::xx] = M * eps;
    P.stress[6 * p + mpm::sym::yy] = P.stress[6 * p + mpm::sym::zz] = lambda * eps;
    P.internal_energy[p] = 0.5 * M * eps * eps / rho;
  }
  const auto x = far.reference_positions();
  for (std::size_t a = 0; a < far.node_count(); ++a) far.displacement()[3 * a] = eps * x[3 * a];
}

// After a step of the uniformly strained bar: the largest speed at its free far end, and near the
// interface at `interface_x` (far-field nodes up to 4 cells right of it, particles beyond 4 cells
// left of the first interface at 60 h).
struct PatchSpeeds {
  double far_end = 0, interface = 0;
};
inline PatchSpeeds patch_speeds(const mpm::Particles& P, const fem::FarField& far,
                                double interface_x) {
  PatchSpeeds s;
  const auto x = far.reference_positions();
  const auto v = far.velocity();
  for (std::size_t a = 0; a < far.node_count(); ++a) {
    if (x[3 * a] > (mpm_cells + fe_cells) * h - 1e-9)
      s.far_end = std::max(s.far_end, std::abs(v[3 * a]));
    if (x[3 * a] < interface_x + 4 * h) s.interface = std::max(s.interface, std::abs(v[3 * a]));
  }
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.position[3 * p] > (mpm_cells - 4) * h)
      s.interface = std::max(s.interface, std::abs(P.velocity[3 * p]));
  return s;
}

}  // namespace hvi::coupling::test
