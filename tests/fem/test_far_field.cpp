// The far field: mass, rigid motion and uniform strain (patch test), the stable time step against
// the assembled eigenvalue problem, and the first bending frequency of simply supported plates
// against plate theory (sandwich: the 2%; a thin plate one element thick: no locking with
// Q2, and Q1's locking shown), with the energy of 10 periods of free vibration.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <omp.h>

#include <Eigen/Dense>

#include "fem/far_field.hpp"
#include "plate_theory.hpp"
#include "tests/support/sanitizers.hpp"

namespace hvi::fem {
namespace {

using std::numbers::pi;

std::vector<double> uniform(double length, int n) {
  return std::vector<double>(n, length / n);
}

// The paper's study panel materials (Table 4): Al6061 faces, Al5052 walls.
const double E_face = 75e9, nu = 0.33, rho_face = 2770, E_wall = 73e9, rho_wall = 2680;

// A sandwich quarter plate [0, a/2]^2 with faces t, core c (cells D, walls t_hc).
LayeredMesh sandwich_mesh(double a, double t, double c, double D, double t_hc, int n, int degree) {
  LayeredMesh m;
  m.lower = {0, 0};
  m.x_steps = m.y_steps = uniform(a / 2, n);
  const Orthotropic face = isotropic(E_face, nu), core = honeycomb_core(E_wall, nu, D, t_hc);
  const double rho_core = rho_wall * honeycomb_core_solidity(D, t_hc);
  m.layers = {{"rear", 0, t, 1, face, rho_face, {}, {}, {}},
              {"core", t, t + c, 2, core, rho_core, {}, {}, {}},
              {"front", t + c, 2 * t + c, 1, face, rho_face, {}, {}, {}}};
  m.degree = degree;
  return m;
}

// Simply supported edges x = 0 and y = 0 (deflection and tangential displacement held, the
// conditions the Navier mode satisfies), symmetry planes x = y = a/2.
void support_quarter_plate(FarField& f, double half) {
  const auto x = f.reference_positions();
  for (std::size_t n = 0; n < f.node_count(); ++n) {
    const double px = x[3 * n], py = x[3 * n + 1];
    const double tol = 1e-9 * half;
    if (std::abs(px) < tol) f.fix(n, 0b110);
    if (std::abs(py) < tol) f.fix(n, 0b101);
    if (std::abs(px - half) < tol) f.fix(n, 0b001);
    if (std::abs(py - half) < tol) f.fix(n, 0b010);
  }
}

struct Vibration {
  double omega = 0;  // from the zero crossings of the centre deflection, rad/s
  // max |E - E0| / E0 over the run, with the energy of a whole step n
  //   E^n = 1/2 v^(n-1/2) . M v^(n+1/2) + 1/2 u^n . K u^n,
  // which central differences conserve exactly for a linear system: what is left is drift from
  // round-off or a wrong operator (the average of the half-step velocities instead oscillates by
  // up to ~9% here with the high modes the initial shape excites).
  double energy_error = 0;
  double periods = 0;
  long steps = 0;
};

// Starts from the plate-theory mode shape (deflection W, rotation Theta) at rest and integrates
// by central differences until `crossings` zero crossings of the centre deflection.
Vibration vibrate(FarField& f, double a, double z_mid, double W, double theta, int crossings) {
  const double k = pi / a * std::sqrt(2.0);
  const auto x = f.reference_positions();
  auto u = f.displacement();
  std::size_t centre = 0;
  double best = -1;
  for (std::size_t n = 0; n < f.node_count(); ++n) {
    const double px = x[3 * n], py = x[3 * n + 1], pz = x[3 * n + 2];
    const double s = std::sin(pi * px / a), sy = std::sin(pi * py / a);
    const double cx = std::cos(pi * px / a), cy = std::cos(pi * py / a);
    u[3 * n + 0] = -(pz - z_mid) * theta * (pi / a) / k * cx * sy;
    u[3 * n + 1] = -(pz - z_mid) * theta * (pi / a) / k * s * cy;
    u[3 * n + 2] = W * s * sy;
    for (int d = 0; d < 3; ++d)
      if (f.fixed(n) & (1u << d)) u[3 * n + d] = 0.0;
    const double score = px + py + pz;
    if (score > best) best = score, centre = n;
  }
  const double dt = 0.9 * f.stable_time_step();
  const std::size_t nd = 3 * f.node_count();
  std::vector<double> force(nd), v_prev(nd);
  const auto m = f.lumped_mass();
  auto v = f.velocity();
  // Half kick: v^(1/2) = dt/2 M^-1 f(u^0).
  f.internal_force(force);
  for (std::size_t i = 0; i < nd; ++i)
    v[i] = (f.fixed(i / 3) & (1u << (i % 3))) ? 0.0 : 0.5 * dt * force[i] / m[i / 3];
  // Starting from rest, v^(-1/2) = -v^(1/2): E^0 = 1/2 u.K u - 1/2 v^(1/2).M v^(1/2).
  const double E0 = f.strain_energy() - f.kinetic_energy(v);
  for (std::size_t i = 0; i < nd; ++i) u[i] += dt * v[i];

  Vibration r;
  std::vector<double> times;
  double w_old = u[3 * centre + 2], t = dt;
  while (static_cast<int>(times.size()) < crossings) {
    const bool check = r.steps % 20 == 0;
    double strain = 0;
    if (check) {
      std::copy(v.begin(), v.end(), v_prev.begin());
      strain = f.strain_energy();
    }
    f.step(dt);
    ++r.steps;
    if (check) {
      double kinetic = 0;
      for (std::size_t i = 0; i < nd; ++i) kinetic += 0.5 * m[i / 3] * v_prev[i] * v[i];
      const double E = kinetic + strain;
      r.energy_error = std::max(r.energy_error, std::abs(E - E0) / E0);
    }
    const double w = u[3 * centre + 2];
    if ((w_old > 0) != (w > 0)) times.push_back(t + dt * w_old / (w_old - w));
    w_old = w;
    t += dt;
  }
  const double period = 2.0 * (times.back() - times.front()) / (times.size() - 1);
  r.omega = 2 * pi / period;
  r.periods = (times.back() - times.front()) / period;
  return r;
}

TEST(FarField, LumpedMassIsTheLayersMassAndPositive) {
  const auto mesh = sandwich_mesh(0.1, 1e-3, 10e-3, 3e-3, 0.05e-3, 3, 2);
  FarField f(mesh);
  double total = 0;
  for (const double m : f.lumped_mass()) {
    EXPECT_GT(m, 0.0);
    total += m;
  }
  double exact = 0;
  for (const auto& l : mesh.layers) exact += l.density * (l.z_upper - l.z_lower) * 0.05 * 0.05;
  EXPECT_NEAR(total / exact, 1.0, 1e-12);
  // Q2 bricks: (2n+1)^2 in plane times (2 * 4 elements + 1) through the thickness.
  EXPECT_EQ(f.node_count(), 7u * 7u * 9u);
}

// Rigid translation and rotation give no force; a uniform strain gives none at interior nodes
// and stores 1/2 eps:C:eps per volume (the patch test).
TEST(FarField, RigidMotionAndUniformStrainPatchTest) {
  for (const int degree : {1, 2}) {
    auto mesh = sandwich_mesh(0.06, 1e-3, 6e-3, 3e-3, 0.05e-3, 3, degree);
    mesh.x_steps = {0.01, 0.005, 0.015};  // uneven elements
    FarField f(mesh);
    const auto x = f.reference_positions();
    const std::size_t nd = 3 * f.node_count();
    std::vector<double> force(nd);
    auto u = f.displacement();
    // Translation plus a small rotation about z and about x.
    for (std::size_t n = 0; n < f.node_count(); ++n) {
      u[3 * n + 0] = 1e-4 - 1e-3 * x[3 * n + 1];
      u[3 * n + 1] = 2e-4 + 1e-3 * x[3 * n + 0] - 2e-3 * x[3 * n + 2];
      u[3 * n + 2] = -3e-4 + 2e-3 * x[3 * n + 1];
    }
    f.internal_force(force);
    double fmax = 0;
    for (const double v : force) fmax = std::max(fmax, std::abs(v));
    // Forces scale as E h eps ~ 75e9 * 1e-3 * 1e-3 = 7.5e4 N; zero to round-off.
    EXPECT_LT(fmax, 1e-9 * 7.5e4) << "degree " << degree;

    // Uniform strain eps_xx = 1e-4 in every layer: u_x = 1e-4 x, others zero.
    for (std::size_t n = 0; n < f.node_count(); ++n) {
      u[3 * n] = 1e-4 * x[3 * n];
      u[3 * n + 1] = u[3 * n + 2] = 0.0;
    }
    f.internal_force(force);
    double interior = 0, boundary = 0;
    for (std::size_t n = 0; n < f.node_count(); ++n) {
      const double px = x[3 * n];
      const bool on_x_face = px < 1e-12 || px > 0.03 - 1e-12;
      // Only nodes on the faces x = 0, 0.03 carry the traction; y and z faces are free of sigma_xx
      // but the Poisson couplings give sigma_yy, sigma_zz, whose divergence is zero inside.
      const bool on_boundary =
          on_x_face || x[3 * n + 1] < 1e-12 || x[3 * n + 1] > 0.03 - 1e-12 ||
          std::abs(x[3 * n + 2]) < 1e-12 || std::abs(x[3 * n + 2] - 8e-3) < 1e-12 ||
          std::abs(x[3 * n + 2] - 1e-3) < 1e-12 || std::abs(x[3 * n + 2] - 7e-3) < 1e-12;
      for (int d = 0; d < 3; ++d)
        (on_boundary ? boundary : interior) =
            std::max(on_boundary ? boundary : interior, std::abs(force[3 * n + d]));
    }
    EXPECT_GT(boundary, 1.0);
    EXPECT_LT(interior, 1e-9 * boundary) << "degree " << degree;
    double exact = 0;
    for (const auto& l : mesh.layers)
      exact += 0.5 * stiffness(l.elasticity)[0] * 1e-8 * (l.z_upper - l.z_lower) * 0.03 * 0.03;
    EXPECT_NEAR(f.strain_energy() / exact, 1.0, 1e-12) << "degree " << degree;
  }
}

// The stable step is 2 / sqrt(lambda) with lambda the element bound; the assembled generalized
// eigenvalue problem K phi = lambda M phi (built column by column from the matrix-free operator)
// must not exceed it, and the bound should not waste more than half the step.
TEST(FarField, StableTimeStepBoundsTheAssembledSpectrum) {
  for (const int degree : {1, 2}) {
    const auto mesh = sandwich_mesh(0.02, 1e-3, 3e-3, 3e-3, 0.05e-3, 2, degree);
    FarField f(mesh);
    const std::size_t nd = 3 * f.node_count();
    Eigen::MatrixXd K(nd, nd);
    std::vector<double> e(nd, 0.0), Ke(nd);
    for (std::size_t j = 0; j < nd; ++j) {
      e[j] = 1.0;
      f.apply_stiffness(e, Ke);
      for (std::size_t i = 0; i < nd; ++i) K(i, j) = Ke[i];
      e[j] = 0.0;
    }
    EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
    Eigen::VectorXd s(nd);
    for (std::size_t i = 0; i < nd; ++i) s[i] = 1.0 / std::sqrt(f.lumped_mass()[i / 3]);
    const Eigen::MatrixXd A = s.asDiagonal() * K * s.asDiagonal();
    const double lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly)
                              .eigenvalues()
                              .maxCoeff();
    const double dt_exact = 2.0 / std::sqrt(lambda);
    EXPECT_LE(f.stable_time_step(), dt_exact * (1 + 1e-12)) << "degree " << degree;
    EXPECT_GT(f.stable_time_step(), 0.5 * dt_exact) << "degree " << degree;
  }
}

// The test sandwich: 200 mm square, faces 1 mm, core 10 mm (D_hc 3 mm, t_hc 0.05 mm), and its
// first bending mode in plate theory.
struct TestSandwich {
  double a = 0.2, t = 1e-3, c = 10e-3, D = 3e-3, t_hc = 0.05e-3;
  double k2 = 2 * pi * pi / (a * a);
  test::PlateStiffness p =
      test::sandwich(E_face, nu, rho_face, t, honeycomb_core(E_wall, nu, D, t_hc).G13,
                     rho_wall* honeycomb_core_solidity(D, t_hc), c);
  double omega2 = test::first_bending_omega2(p, k2);
};

// Simply supported sandwich plate, 200 mm square, faces 1 mm, core 10 mm (D_hc 3 mm, t_hc
// 0.05 mm): first bending frequency within the 2% of thick-face sandwich theory with core
// shear and rotary inertia (plate_theory.hpp), and the energy of free vibration within 0.1% over
// 10 periods (central differences conserve energy up to an O((omega dt)^2) oscillation).
TEST(FarField, SandwichPlateFirstBendingFrequency) {
  HVI_SKIP_UNDER_SANITIZERS(
      "16 s in Release; the same operator runs in FarField.SandwichPlateInQ1");
  const TestSandwich S;
  const auto& [a, t, c, D, t_hc, k2, p, omega2] = S;
  FarField f(sandwich_mesh(a, t, c, D, t_hc, 4, 2));
  support_quarter_plate(f, a / 2);
  const double W = 1e-4;
  const auto r = vibrate(f, a, t + c / 2, W, test::mode_rotation(p, k2, omega2) * W, 21);
  const double omega = std::sqrt(omega2);
  std::printf(
      "sandwich plate: omega %.2f rad/s (theory %.2f, %+.3f%%), %.1f periods, %ld steps, "
      "energy error %.2e\n",
      r.omega, omega, 100 * (r.omega / omega - 1), r.periods, r.steps, r.energy_error);
  EXPECT_NEAR(r.omega / omega, 1.0, 0.02);
  EXPECT_GE(r.periods, 10.0 - 1e-9);
  EXPECT_LT(r.energy_error, 1e-3);
}

// The same sandwich in trilinear Q1 bricks (the hybrid's far field, whose nodes must match the
// MPM grid's linear shape functions at the interface). The panel bends through face membrane
// forces and core shear, which Q1 carries without locking; only the faces' own bending locks, by
// a factor growing as (element length / face thickness)^2: 5.1% too stiff at 12.5 t_f elements,
// 1.4% at 6.25 t_f. Hence the hybrid's rule: far-field elements at most 6 t_f long.
TEST(FarField, SandwichPlateInQ1) {
  const TestSandwich S;
  const auto& [a, t, c, D, t_hc, k2, p, omega2] = S;
  double error[2] = {};
  for (const int n : {8, 16}) {
    auto mesh = sandwich_mesh(a, t, c, D, t_hc, n, 1);
    mesh.layers[1].elements = 4;
    FarField f(mesh);
    support_quarter_plate(f, a / 2);
    const double W = 1e-4;
    const auto r = vibrate(f, a, t + c / 2, W, test::mode_rotation(p, k2, omega2) * W, 3);
    std::printf("sandwich plate Q1 %d elements: omega %.2f rad/s (theory %.2f, %+.3f%%)\n", n,
                r.omega, std::sqrt(omega2), 100 * (r.omega / std::sqrt(omega2) - 1));
    error[n / 16] = r.omega / std::sqrt(omega2) - 1;
  }
  EXPECT_GT(error[0], 0.02);            // 12.5 t_f: locking shows
  EXPECT_LT(std::abs(error[1]), 0.02);  // 6.25 t_f: within the 2%
}

// A thin homogeneous plate (200 mm, 2 mm thick, a/h = 100) one element through its thickness:
// Q2 bends freely (within 2% of plate theory); trilinear Q1 bricks lock in shear and come out far
// too stiff, which is why the far field uses Q2.
TEST(FarField, ThinPlateBendsWithoutLockingInQ2) {
  const double a = 0.2, h = 2e-3;
  const auto p = test::homogeneous(E_face, nu, rho_face, h);
  const double k2 = 2 * pi * pi / (a * a);
  const double omega = std::sqrt(test::first_bending_omega2(p, k2));
  double error[3] = {};
  for (const int degree : {1, 2}) {
    LayeredMesh m;
    m.x_steps = m.y_steps = uniform(a / 2, degree == 2 ? 4 : 8);
    m.layers = {{"plate", 0, h, 1, isotropic(E_face, nu), rho_face, {}, {}, {}}};
    m.degree = degree;
    FarField f(m);
    support_quarter_plate(f, a / 2);
    const double W = 1e-4;
    const auto r = vibrate(f, a, h / 2, W, std::sqrt(k2) * W, 2);
    error[degree] = r.omega / omega - 1;
    std::printf("thin plate Q%d: omega %.2f rad/s (theory %.2f, %+.2f%%)\n", degree, r.omega, omega,
                100 * error[degree]);
  }
  EXPECT_LT(std::abs(error[2]), 0.02);
  EXPECT_GT(error[1], 0.5);  // locked: at least 50% too stiff in frequency
}

// The cell loops run on OpenMP threads colour by colour (no two batches of a colour share a
// node): 200 steps of the sandwich plate, elastic and with J2 facesheets driven into yield, give
// the same bits on 1, 2 and 3 threads.
TEST(FarField, ThreadCountDoesNotChangeABit) {
  auto run = [](int threads, bool plastic) {
    omp_set_num_threads(threads);
    LayeredMesh m = sandwich_mesh(0.1, 1e-3, 10e-3, 3e-3, 0.05e-3, 6, 1);
    if (plastic) {
      materials::JohnsonCookStrength jc;
      jc.A = 324e6;
      jc.B = 114e6;
      jc.n = 0.42;
      m.layers[0].plasticity = m.layers[2].plasticity = jc;
    }
    FarField f(m);
    support_quarter_plate(f, 0.05);
    auto v = f.velocity();
    const auto x = f.reference_positions();
    for (std::size_t a = 0; a < f.node_count(); ++a)  // a hard blow at the centre: it yields
      v[3 * a + 2] = -200.0 * std::exp(-(x[3 * a] * x[3 * a] + x[3 * a + 1] * x[3 * a + 1]) / 1e-4);
    const double dt = 0.9 * f.stable_time_step();
    for (int s = 0; s < 200; ++s) f.step(dt);
    std::vector<double> state(f.displacement().begin(), f.displacement().end());
    state.push_back(f.strain_energy());
    state.push_back(f.plastic_work());
    return state;
  };
  for (const bool plastic : {false, true}) {
    const auto one = run(1, plastic);
    EXPECT_TRUE(one == run(2, plastic)) << "plastic " << plastic;
    EXPECT_TRUE(one == run(3, plastic)) << "plastic " << plastic;
    if (plastic) {
      EXPECT_GT(one.back(), 0.0);  // the facesheets did yield
    }
  }
  omp_set_num_threads(omp_get_num_procs());
}

TEST(FarField, GradedStepsKeepTheFineRegionAndAddUp) {
  const auto s = graded_steps(-30e-3, 30e-3, -6e-3, 6e-3, 0.8e-3, 1.3, 5e-3, 2);
  double sum = 0;
  for (const double v : s) sum += v;
  EXPECT_NEAR(sum, 60e-3, 1e-15);
  // The fine region starts at a node: the steps from -30 mm reach -6 mm exactly.
  double x = -30e-3;
  std::size_t i = 0;
  while (x < -6e-3 - 1e-12) x += s[i++];
  EXPECT_NEAR(x, -6e-3, 1e-15);
  for (std::size_t j = i; j < i + 15; ++j) EXPECT_DOUBLE_EQ(s[j], 0.8e-3);
  // The two kept steps next to the fine region are fine too; growth never exceeds the ratio
  // by more than the final rescaling.
  EXPECT_DOUBLE_EQ(s[i - 1], 0.8e-3);
  EXPECT_DOUBLE_EQ(s[i - 2], 0.8e-3);
  for (const double v : s) EXPECT_LE(v, 5e-3 * 1.5);
}

}  // namespace
}  // namespace hvi::fem
