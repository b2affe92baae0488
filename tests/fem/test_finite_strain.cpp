// The far field's finite-strain kinematics (total Lagrangian, orthotropic Saint Venant-Kirchhoff;
// fem/far_field.hpp) against closed forms: a rigid rotation of any size stresses nothing; a
// uniaxial stretch or compression, turned or not, gives P = F S with S = C E of the Green-Lagrange
// strain; the stable step bounds the spectrum of the tangent stiffness at the deformed state; and
// a block spinning through a quarter turn keeps its kinetic energy. Small strain fails the first
// and the last, which is why the option exists.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "block.hpp"
#include "fem/far_field.hpp"

namespace hvi::fem {
namespace {

using namespace test;
using std::numbers::pi;
using Matrix = std::array<std::array<double, 3>, 3>;

Matrix product(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}

Matrix minus_identity(Matrix a) {
  for (int i = 0; i < 3; ++i) a[i][i] -= 1.0;
  return a;
}

// Rotation by `angle` about the unit vector n (Rodrigues).
Matrix rotation(std::array<double, 3> n, double angle) {
  const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (auto& x : n) x /= norm;
  const double c = std::cos(angle), s = std::sin(angle);
  Matrix R{};
  const Matrix K{{{0, -n[2], n[1]}, {n[2], 0, -n[0]}, {-n[1], n[0], 0}}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = (i == j ? c : 0.0) + s * K[i][j] + (1 - c) * n[i] * n[j];
  return R;
}

// The block with an orthotropic (honeycomb-core) layer under the isotropic one, so both kinds of
// layer are checked.
LayeredMesh two_layers(int degree, bool finite_strain) {
  LayeredMesh m = block(degree, false, finite_strain);
  m.layers = {
      {"core", 0, 0.5 * L, 1, honeycomb_core(E, nu, 3e-3, 0.05e-3), rho * 0.034, std::nullopt,
       std::nullopt, std::nullopt},
      {"face", 0.5 * L, L, 1, isotropic(E, nu), rho, std::nullopt, std::nullopt, std::nullopt}};
  return m;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

// u = (R - I) X + c with R a 75 degree turn about an oblique axis: no force and no strain energy
// with finite strain (to round-off: forces scale as E L^2 = 6.9e4 N for a strain of one, energy as
// E L^3 = 69 J), and the stable step of the undeformed block (F^T F = I). Small strain reads the
// same motion as a strain of order one.
TEST(FiniteStrain, RigidRotationOfAnySizeGivesNoForceAndNoEnergy) {
  const Matrix A = minus_identity(rotation({1, 2, 3}, 75 * pi / 180));
  const double force_scale = E * L * L, energy_scale = E * L * L * L;
  for (const int degree : {1, 2}) {
    FarField finite(two_layers(degree, true)), small(two_layers(degree, false));
    const double dt0 = finite.stable_time_step();
    std::vector<double> force(3 * finite.node_count());
    deform(finite, A, {1e-4, -2e-4, 3e-4});
    finite.internal_force(force);
    EXPECT_LT(max_abs(force), 1e-9 * force_scale) << "degree " << degree;
    EXPECT_LT(std::abs(finite.strain_energy()), 1e-12 * energy_scale) << "degree " << degree;
    EXPECT_NEAR(finite.stable_time_step(), dt0, 1e-12 * dt0) << "degree " << degree;
    deform(small, A, {1e-4, -2e-4, 3e-4});
    small.internal_force(force);
    EXPECT_GT(max_abs(force), 1e-2 * force_scale) << "degree " << degree;
  }
}

// F = R diag(lambda, 1, 1): E_xx = (lambda^2 - 1)/2, S_xx = (lame + 2 mu) E_xx, S_yy = S_zz =
// lame E_xx, P = F S; the face X = L carries P e_x L^2 = R (lambda S_xx, 0, 0) L^2 and the face
// Y = L carries R (0, S_yy, 0) L^2; the strain energy is 1/2 (lame + 2 mu) E_xx^2 L^3. For a
// stretch and a compression (lambda 1.3, 0.7), untouched and turned by 30 degrees about z, Q1
// and Q2: within 1e-10 of S_xx (the quadrature is exact for a homogeneous state; what is left is
// round-off).
TEST(FiniteStrain, UniaxialStretchFollowsSaintVenantKirchhoff) {
  for (const int degree : {1, 2})
    for (const double lambda : {1.3, 0.7})
      for (const double turn : {0.0, 30.0}) {
        FarField f(block(degree, false, true));
        const Matrix R = rotation({0, 0, 1}, turn * pi / 180);
        deform(f, minus_identity(product(R, Matrix{{{lambda, 0, 0}, {0, 1, 0}, {0, 0, 1}}})));
        std::vector<double> force(3 * f.node_count());
        f.internal_force(force);
        const double Exx = 0.5 * (lambda * lambda - 1), Sxx = (lame + 2 * mu) * Exx,
                     Syy = lame * Exx;
        const auto fx = face_force(force, f, 0), fy = face_force(force, f, 1);
        const double tol = 1e-10 * std::abs(Sxx);
        for (int i = 0; i < 3; ++i) {
          EXPECT_NEAR(-fx[i] / (L * L), R[i][0] * lambda * Sxx, tol)
              << degree << " " << lambda << " " << turn;
          EXPECT_NEAR(-fy[i] / (L * L), R[i][1] * Syy, tol)
              << degree << " " << lambda << " " << turn;
        }
        const double W = 0.5 * (lame + 2 * mu) * Exx * Exx * L * L * L;
        EXPECT_NEAR(f.strain_energy(), W, 1e-12 * W);
      }
}

// At a deformed state the tangent K_t = d(-f)/du (central differences of the matrix-free force)
// has a spectrum, against the lumped mass, whose largest eigenvalue lambda_t sets the critical
// step 2 / sqrt(lambda_t); the step the far field reports after a force evaluation at that state
// must not exceed it and should not waste more than half of it. Stretch 1.3 (where the bound's
// (3 s - 1)/2 is the continuum's exact stiffening), compression 0.8 and a shear of 0.4.
TEST(FiniteStrain, StableStepBoundsTheTangentSpectrum) {
  const Matrix cases[] = {{{{1.3, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                          {{{0.8, 0, 0}, {0, 1, 0}, {0, 0, 1}}},
                          {{{1, 0.4, 0}, {0, 1, 0}, {0, 0, 1}}}};
  for (const int degree : {1, 2})
    for (const Matrix& F : cases) {
      FarField f(two_layers(degree, true));
      deform(f, minus_identity(F));
      const std::size_t nd = 3 * f.node_count();
      std::vector<double> plus(nd), minus(nd);
      Eigen::MatrixXd K(nd, nd);
      auto u = f.displacement();
      const double h = 1e-9;  // m: 1e-6 of the block
      for (std::size_t j = 0; j < nd; ++j) {
        const double u0 = u[j];
        u[j] = u0 + h;
        f.internal_force(plus);
        u[j] = u0 - h;
        f.internal_force(minus);
        u[j] = u0;
        for (std::size_t i = 0; i < nd; ++i) K(i, j) = -(plus[i] - minus[i]) / (2 * h);
      }
      f.internal_force(plus);  // the stretch bound of the deformed state itself
      Eigen::VectorXd s(nd);
      for (std::size_t i = 0; i < nd; ++i) s[i] = 1.0 / std::sqrt(f.lumped_mass()[i / 3]);
      const Eigen::MatrixXd A = s.asDiagonal() * (0.5 * (K + K.transpose())) * s.asDiagonal();
      const double lambda_t =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly)
              .eigenvalues()
              .maxCoeff();
      const double dt_t = 2.0 / std::sqrt(lambda_t);
      EXPECT_LE(f.stable_time_step(), dt_t * (1 + 1e-6))
          << "degree " << degree << ", F_xx " << F[0][0];
      EXPECT_GT(f.stable_time_step(), 0.5 * dt_t) << "degree " << degree << ", F_xx " << F[0][0];
    }
}

// A free block spun about z at omega = 1e5 rad/s (its corners at 100 m/s) through a quarter turn
// by central differences at 0.9 of the reported stable step: with finite strain the kinetic plus
// strain energy stays within 1e-3 of the start's 1/2 I omega^2 (the leapfrog's energy error is of
// order (omega_max dt)^2 in the fast modes the start excites, and the centrifugal stretch rho
// omega^2 L^2 / E = 4e-7 stores nothing measurable), and the block has turned: a corner lies within
// 1% of L of the rigidly rotated one. With small strain the same start is resisted by a spurious
// strain of order one and the block does not turn.
TEST(FiniteStrain, SpinningBlockKeepsItsEnergy) {
  const double omega = 1e5, xc = 0.5 * L, yc = 0.5 * L;
  for (const bool finite : {true, false}) {
    FarField f(block(1, false, finite));
    const auto x = f.reference_positions();
    auto v = f.velocity();
    std::size_t corner = 0;
    for (std::size_t a = 0; a < f.node_count(); ++a) {
      v[3 * a] = -omega * (x[3 * a + 1] - yc);
      v[3 * a + 1] = omega * (x[3 * a] - xc);
      if (x[3 * a] > L - 1e-12 && x[3 * a + 1] > L - 1e-12 && x[3 * a + 2] > L - 1e-12) corner = a;
    }
    // 1/2 I omega^2 with the lumped mass's own moment of inertia (on these 2 x 2 x 2 bricks 1.5
    // times the continuum's rho L^5 / 6, the mass sitting at the nodes).
    const double E0 = f.kinetic_energy();
    const double t_end = 0.5 * pi / omega;
    double t = 0;
    while (t < t_end) {
      const double dt = std::min(0.9 * f.stable_time_step(), t_end - t);
      f.step(dt);
      t += dt;
    }
    const double energy = f.kinetic_energy() + f.strain_energy();
    const auto u = f.displacement();
    // The corner (L, L, L) turned by 90 degrees about (xc, yc): (xc - (L - yc), yc + (L - xc)).
    const double dx = x[3 * corner] + u[3 * corner] - (xc - (L - yc)),
                 dy = x[3 * corner + 1] + u[3 * corner + 1] - (yc + (L - xc));
    const double miss = std::hypot(dx, dy);
    if (finite) {
      EXPECT_NEAR(energy / E0, 1.0, 1e-3);
      EXPECT_LT(miss, 1e-2 * L);
    } else {
      EXPECT_GT(miss, 0.5 * L);
    }
    std::printf("%s strain: energy %.6f of 1/2 I omega^2, corner %.3g L from the turned one\n",
                finite ? "finite" : "small", energy / E0, miss / L);
  }
}

}  // namespace hvi::fem
