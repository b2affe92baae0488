// J2 facesheets of the far field against the closed form of uniaxial strain: a block of one
// plastic layer strained homogeneously, u = (e x, 0, 0), loaded to 1% and unloaded to 0 through
// the matrix-free force (so the return mapping, its state per quadrature point and the assembly
// are all checked), and the layers that do not name plasticity keep no state.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "fem/far_field.hpp"
#include "fem/j2_plasticity.hpp"
#include "block.hpp"

namespace hvi::fem {
namespace {

using namespace test;

// sigma_xx and sigma_yy read from the internal force: for a homogeneous stress the forces on the
// nodes of the face x = L add up to -sigma_xx times its area (and likewise for y).
std::pair<double, double> stresses(FarField& f) {
  std::vector<double> force(3 * f.node_count());
  f.internal_force(force);
  return {-face_force(force, f, 0)[0] / (L * L), -face_force(force, f, 1)[1] / (L * L)};
}

}  // namespace

TEST(J2Plasticity, UniaxialStrainLoadAndUnloadFollowTheClosedForm) {
  const double V = L * L * L, K = E / (3 * (1 - 2 * nu));
  const Uniaxial exact{mu, K, al6061()};
  for (const int degree : {1, 2}) {
    FarField f(block(degree, true));
    ASSERT_TRUE(f.plastic());
    auto set_strain = [&](double e) {
      auto u = f.displacement();
      const auto x = f.reference_positions();
      for (std::size_t i = 0; i < u.size(); ++i) u[i] = i % 3 == 0 ? e * x[i] : 0.0;
    };
    // Loading to 1% in 100 steps: yield at e = A / 2 mu = 0.63%, then hardening. Every quadrature
    // point sees the same strain, so the stresses match the closed form to the Newton tolerance
    // of the return (1e-14 in alpha): 1e-9 relative.
    const int n = 100;
    const double e_max = 0.01;
    double alpha_prev = 0, max_step = 0;
    for (int k = 1; k <= n; ++k) {
      const double e = e_max * k / n;
      set_strain(e);
      const auto [sxx, syy] = stresses(f);
      const double alpha = exact.alpha_on_loading(e);
      EXPECT_NEAR(sxx, exact.sxx(e, alpha), 1e-9 * exact.sxx(e, alpha)) << "degree " << degree << ", e " << e;
      EXPECT_NEAR(syy, exact.syy(e, alpha), 1e-9 * exact.sxx(e, alpha)) << "degree " << degree << ", e " << e;
      max_step = std::max(max_step, alpha - alpha_prev);
      alpha_prev = alpha;
    }
    EXPECT_NEAR(f.max_equivalent_plastic_strain(), alpha_prev, 1e-12);
    EXPECT_GT(alpha_prev, 1e-3);  // the test reaches well into the plastic range
    // Plastic work: the code adds dgamma sigma_y(alpha_n+1) per step, a right-endpoint sum of
    // int sigma_y dalpha = A alpha + B alpha^(n+1) / (n+1), which exceeds the integral by at most
    // the largest increment times the rise of sigma_y (sigma_y grows monotonically).
    const auto jc = al6061();
    const double W = (jc.A * alpha_prev + jc.B * std::pow(alpha_prev, jc.n + 1) / (jc.n + 1)) * V;
    EXPECT_GE(f.plastic_work(), W * (1 - 1e-9));
    EXPECT_LE(f.plastic_work() - W, max_step * (jc.hardening(alpha_prev) - jc.A) * V * (1 + 1e-6));
    // Unloading to zero strain stays elastic (reverse yield needs e < e_max - sigma_y / mu < 0):
    // the residual stress is the plastic strain's, s_xx = -2 mu alpha, and the stored elastic
    // energy 1/2 eps_p : C eps_p V = 3/2 mu alpha^2 V.
    for (int k = n - 1; k >= 0; --k) {
      const double e = e_max * k / n;
      set_strain(e);
      const auto [sxx, syy] = stresses(f);
      EXPECT_NEAR(sxx, exact.sxx(e, alpha_prev), 1e-9 * std::abs(exact.sxx(e_max, alpha_prev)));
      EXPECT_NEAR(syy, exact.syy(e, alpha_prev), 1e-9 * std::abs(exact.sxx(e_max, alpha_prev)));
    }
    EXPECT_NEAR(f.max_equivalent_plastic_strain(), alpha_prev, 1e-12);
    EXPECT_NEAR(f.strain_energy(), 1.5 * mu * alpha_prev * alpha_prev * V, 1e-9 * 1.5 * mu * alpha_prev * alpha_prev * V);
  }
}

TEST(J2Plasticity, ElasticLayersKeepNoPlasticState) {
  FarField elastic(block(1, false)), plastic(block(1, true));
  EXPECT_FALSE(elastic.plastic());
  EXPECT_TRUE(elastic.plastic_state().empty());
  EXPECT_EQ(plastic.plastic_state().size(), 2u);
  EXPECT_LT(elastic.bytes(), plastic.bytes());
  // Below yield the plastic layer is the elastic one, to round-off.
  for (FarField* f : {&elastic, &plastic}) {
    auto u = f->displacement();
    const auto x = f->reference_positions();
    for (std::size_t i = 0; i < u.size(); ++i) u[i] = i % 3 == 0 ? 1e-3 * x[i] : 0.0;
  }
  EXPECT_NEAR(stresses(plastic).first, stresses(elastic).first, 1e-12 * stresses(elastic).first);
  EXPECT_EQ(plastic.plastic_work(), 0.0);
}

TEST(J2Plasticity, APlasticLayerMustBeIsotropic) {
  LayeredMesh m = block(1, true);
  m.layers[0].elasticity = honeycomb_core(70e9, 0.33, 3e-3, 0.05e-3);
  EXPECT_THROW(FarField f(m), std::invalid_argument);
}


// With finite strain the closed form above holds in the Green-Lagrange strain: a uniaxial stretch
// F = diag(lambda, 1, 1) has E_xx = (lambda^2 - 1)/2, S as s_xx, s_yy above with e = E_xx, and the
// faces carry P = F S on their reference areas (P_xx = lambda S_xx, P_yy = S_yy). Turning the
// stretched block rigidly by up to 90 degrees (F -> R F) leaves E, S and alpha as they were: the
// face's force turns with R and no plastic work is done. With small strain the same turn reads as
// a compressive strain of order one and yields the block through and through.
TEST(J2Plasticity, FiniteStrainStretchThenRigidTurnIsObjective) {
  const double K = E / (3 * (1 - 2 * nu));
  const Uniaxial exact{mu, K, al6061()};
  for (const int degree : {1, 2}) {
    FarField f(block(degree, true, true)), small(block(degree, true, false));
    std::vector<double> force(3 * f.node_count());
    const int n = 100;
    const double E_max = 0.01;
    double alpha = 0, lambda = 1;
    for (int k = 1; k <= n; ++k) {
      const double Exx = E_max * k / n;
      lambda = std::sqrt(1 + 2 * Exx);
      for (FarField* g : {&f, &small}) deform(*g, {{{lambda - 1, 0, 0}, {0, 0, 0}, {0, 0, 0}}});
      small.internal_force(force);
      f.internal_force(force);
      alpha = exact.alpha_on_loading(Exx);
      const double Sxx = exact.sxx(Exx, alpha);
      EXPECT_NEAR(-face_force(force, f, 0)[0] / (L * L), lambda * Sxx, 1e-9 * Sxx) << "degree " << degree;
      EXPECT_NEAR(-face_force(force, f, 1)[1] / (L * L), exact.syy(Exx, alpha), 1e-9 * Sxx) << "degree " << degree;
    }
    EXPECT_GT(alpha, 1e-3);
    EXPECT_NEAR(f.max_equivalent_plastic_strain(), alpha, 1e-12);
    const double work = f.plastic_work(), Sxx = exact.sxx(E_max, alpha);
    for (int k = 1; k <= 10; ++k) {
      const double turn = 0.5 * std::numbers::pi * k / 10, c = std::cos(turn), s = std::sin(turn);
      for (FarField* g : {&f, &small}) deform(*g, {{{c * lambda - 1, -s, 0}, {s * lambda, c - 1, 0}, {0, 0, 0}}});
      small.internal_force(force);
      f.internal_force(force);
      const auto fx = face_force(force, f, 0);
      EXPECT_NEAR(-fx[0] / (L * L), c * lambda * Sxx, 1e-9 * Sxx) << "degree " << degree << ", turn " << k;
      EXPECT_NEAR(-fx[1] / (L * L), s * lambda * Sxx, 1e-9 * Sxx) << "degree " << degree << ", turn " << k;
      EXPECT_NEAR(fx[2] / (L * L), 0.0, 1e-9 * Sxx) << "degree " << degree << ", turn " << k;
    }
    EXPECT_NEAR(f.max_equivalent_plastic_strain(), alpha, 1e-12);
    EXPECT_NEAR(f.plastic_work(), work, 1e-9 * work);
    EXPECT_GT(small.max_equivalent_plastic_strain(), 0.1);
  }
}

}  // namespace hvi::fem
