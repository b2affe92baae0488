// The hybrid's shared nodes on a bar, half material points and half finite elements, with
// rollers on its four long sides (uniaxial strain, so the closed forms are 1D): rigid translation
// and uniform strain give no interface force, momentum is conserved exactly, and a smooth
// compressive pulse crosses the interface leaving < 1% of its energy behind and arriving within
// 2% of an all-MPM bar.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "coupling/far_field_coupling.hpp"
#include "tests/coupling/coupled_bar.hpp"

namespace hvi::coupling {
namespace {

using namespace test;

// The MPM zone is the bar left of x = 60 h; far-field nodes up to one cell beyond are tied.
InterfaceBand bar_band() {
  return {{-4 * h, 0, mpm_cells * h, 2 * h}, h};
}

struct Hybrid {
  std::unique_ptr<mpm::Solver> solver = bar_solver(mpm_cells);
  std::unique_ptr<fem::FarField> far = bar_far_field();
  FarFieldCoupling coupling{*far, bar_grid(), bar_band()};
  Hybrid() { solver->add_coupling(&coupling); }
};

double total_momentum_x(const Hybrid& H) {
  return H.solver->energy().momentum[0];  // particles and the far field
}

TEST(FarFieldCoupling, TiesTheInterfaceNodesExactly) {
  Hybrid H;
  // Q1 nodes at x = 60 h and 61 h, 3 x 3 across: all on grid nodes.
  EXPECT_EQ(H.coupling.tied_node_count(), 18u);
  EXPECT_EQ(H.coupling.exact_node_count(), 18u);
  // The far field's stable step (element bound, Q1 cube, lumped) is below the MPM CFL limit.
  EXPECT_LT(H.coupling.stable_time_step(), 0.9 * h / c);
}

// A rigid translation along the bar stays one: no spurious force at the interface.
TEST(FarFieldCoupling, RigidTranslationGivesNoInterfaceForce) {
  mpm::test::Threads one(1);
  Hybrid H;
  const double V = 3.0;
  auto& P = H.solver->particles();
  for (std::size_t p = 0; p < P.size(); ++p) P.velocity[3 * p] = V;
  auto v = H.far->velocity();
  for (std::size_t a = 0; a < H.far->node_count(); ++a) v[3 * a] = V;
  H.solver->initialise();
  for (int s = 0; s < 20; ++s) H.solver->step();
  double worst = 0;
  for (std::size_t p = 0; p < P.size(); ++p)
    worst = std::max(worst, std::abs(P.velocity[3 * p] - V));
  for (std::size_t a = 0; a < H.far->node_count(); ++a)
    worst = std::max(worst, std::abs(v[3 * a] - V));
  EXPECT_LT(worst, 1e-12 * V);
  double stress = 0;
  for (const double s : P.stress) stress = std::max(stress, std::abs(s));
  EXPECT_LT(stress, 1e-9 * rho * c * V);  // rho c V = 50 MPa would be a real wave
  double force = 0;
  for (const double f : H.coupling.internal_force()) force = std::max(force, std::abs(f));
  EXPECT_LT(force, 1e-9 * M * 1e-3 * h * h);
}

// Uniform uniaxial strain eps on both sides: after one step only the bar's two free ends move;
// the nodes at and beside the interface feel no net force (the patch test across it).
TEST(FarFieldCoupling, UniformStrainGivesNoInterfaceForce) {
  mpm::test::Threads one(1);
  Hybrid H;
  const double eps = 1e-4;
  auto& P = H.solver->particles();
  strain_uniformly(P, *H.far, eps);
  H.solver->initialise();
  H.solver->step();
  const auto [far_end, interface] = patch_speeds(P, *H.far, mpm_cells * h);
  EXPECT_GT(far_end, 1e-3);  // the free end starts to move (the traction M eps over one node)
  EXPECT_LT(interface, 1e-10 * far_end);
}

// A smooth right-going compressive pulse, v = V sin^2(pi (x - 20h) / 16h) with the matching stress
// sigma_xx = -rho c v and energy density rho v^2, starts in the MPM half and crosses into the far
// field. After its tail has passed the interface by 16 h:
//  - the energy left in the MPM zone (what the interface reflected, plus the MPM's own wake) is
//    below 1% of the pulse's;
//  - the far field holds the energy and peak velocity an all-MPM bar has beyond x = 60 h, within
//  2%;
//  - the momentum of particles plus far field is conserved to round-off.
TEST(FarFieldCoupling, PulseCrossesTheInterface) {
  mpm::test::Threads one(1);
  const double V = 1.0, x0 = 20 * h, Lp = 16 * h;
  auto pulse = [&](mpm::Solver& s) {
    auto& P = s.particles();
    for (std::size_t p = 0; p < P.size(); ++p) {
      const double xi = (P.position[3 * p] - x0) / Lp;
      const double v = (xi > 0 && xi < 1) ? V * std::pow(std::sin(std::numbers::pi * xi), 2) : 0.0;
      P.velocity[3 * p] = v;
      P.stress[6 * p + mpm::sym::xx] = -rho * c * v;
      P.stress[6 * p + mpm::sym::yy] = P.stress[6 * p + mpm::sym::zz] = -lambda / M * rho * c * v;
      P.internal_energy[p] = 0.5 * v * v;
    }
  };
  auto particle_energy = [](const mpm::Solver& s, double x_min, double x_max) {
    const auto& P = s.particles();
    double e = 0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (P.position[3 * p] < x_min || P.position[3 * p] >= x_max) continue;
      const double* v = &P.velocity[3 * p];
      e += P.mass[p] * (0.5 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) + P.internal_energy[p]);
    }
    return e;
  };
  const double end_time = (mpm_cells * h - x0 + 16 * h) / c;

  Hybrid H;
  pulse(*H.solver);
  H.solver->initialise();
  const double E_pulse = particle_energy(*H.solver, -1, 1);
  const double P0 = total_momentum_x(H);
  double momentum_error = 0;
  while (H.solver->time() < end_time) {
    H.solver->step(end_time - H.solver->time());
    momentum_error = std::max(momentum_error, std::abs(total_momentum_x(H) - P0));
  }
  const double left_behind = particle_energy(*H.solver, -1, 1) / E_pulse;
  const auto far = H.coupling.energy();
  const auto v = H.far->velocity();
  double peak_far = 0;
  for (std::size_t a = 0; a < H.far->node_count(); ++a) peak_far = std::max(peak_far, v[3 * a]);

  auto all = bar_solver(mpm_cells + fe_cells);
  pulse(*all);
  all->initialise();
  while (all->time() < end_time) all->step(end_time - all->time());
  const double mpm_left = particle_energy(*all, -1, mpm_cells * h) / E_pulse;
  const double mpm_right = particle_energy(*all, mpm_cells * h, 1) / E_pulse;
  double peak_mpm = 0;
  for (std::size_t p = 0; p < all->particles().size(); ++p)
    if (all->particles().position[3 * p] > mpm_cells * h)
      peak_mpm = std::max(peak_mpm, all->particles().velocity[3 * p]);

  std::printf(
      "pulse: left in the MPM zone %.3e of its energy (all-MPM bar: %.3e); transmitted "
      "%.4f (all-MPM %.4f); peak %.4f m/s (all-MPM %.4f); momentum error %.2e of %.3e\n",
      left_behind, mpm_left, (far.kinetic + far.strain) / E_pulse, mpm_right, peak_far, peak_mpm,
      momentum_error, P0);
  EXPECT_LT(left_behind, 0.01);
  EXPECT_NEAR((far.kinetic + far.strain) / E_pulse / mpm_right, 1.0, 0.02);
  EXPECT_NEAR(peak_far / peak_mpm, 1.0, 0.02);
  EXPECT_LT(momentum_error, 1e-12 * std::abs(P0));
}

}  // namespace
}  // namespace hvi::coupling
