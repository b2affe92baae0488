// J2 facesheets of the far field against the closed form of uniaxial strain: a block of one
// plastic layer strained homogeneously, u = (e x, 0, 0), loaded to 1% and unloaded to 0 through
// the matrix-free force (so the return mapping, its state per quadrature point and the assembly
// are all checked), and the layers that do not name plasticity keep no state.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fem/far_field.hpp"
#include "fem/j2_plasticity.hpp"

namespace hvi::fem {
namespace {

// Al6061 as in the paper's Table 4 (E, nu; Johnson-Cook A, B, n).
const double E = 69e9, nu = 0.33, rho = 2700;
mpm::JohnsonCookStrength al6061() {
  mpm::JohnsonCookStrength jc;
  jc.A = 324e6;
  jc.B = 114e6;
  jc.n = 0.42;
  return jc;
}

LayeredMesh block(int degree, bool plastic) {
  LayeredMesh m;
  m.lower = {0, 0};
  m.x_steps = {0.5e-3, 0.5e-3};
  m.y_steps = {0.5e-3, 0.5e-3};
  m.layers = {{"face", 0, 1e-3, 2, isotropic(E, nu), rho, plastic ? std::optional(al6061()) : std::nullopt}};
  m.degree = degree;
  return m;
}

// Uniaxial strain e along x with J2 and radial flow: eps_p = alpha diag(1, -1/2, -1/2), so
//   s_xx = 2 mu (2e/3 - alpha),  s_yy = s_zz = 2 mu (alpha/2 - e/3),  q = 2 mu |e - 3/2 alpha|,
// and on loading the consistency condition 2 mu (e - 3/2 alpha) = A + B alpha^n fixes alpha
// (solved here by bisection, independently of the code's Newton iteration).
struct Uniaxial {
  double mu, K;
  mpm::JohnsonCookStrength jc;
  double alpha_on_loading(double e) const {
    if (2 * mu * e <= jc.A) return 0.0;
    double lo = 0, hi = e / 1.5;
    for (int i = 0; i < 200; ++i) {
      const double a = 0.5 * (lo + hi);
      (2 * mu * (e - 1.5 * a) > jc.hardening(a) ? lo : hi) = a;
    }
    return 0.5 * (lo + hi);
  }
  double sxx(double e, double alpha) const { return K * e + 2 * mu * (2 * e / 3 - alpha); }
  double syy(double e, double alpha) const { return K * e + 2 * mu * (alpha / 2 - e / 3); }
};

// sigma_xx and sigma_yy read from the internal force: for a homogeneous stress the forces on the
// nodes of the face x = L add up to -sigma_xx times its area (and likewise for y).
std::pair<double, double> stresses(FarField& f, double L) {
  std::vector<double> force(3 * f.node_count());
  f.internal_force(force);
  const auto x = f.reference_positions();
  double fx = 0, fy = 0;
  for (std::size_t a = 0; a < f.node_count(); ++a) {
    if (std::abs(x[3 * a] - L) < 1e-12) fx += force[3 * a];
    if (std::abs(x[3 * a + 1] - L) < 1e-12) fy += force[3 * a + 1];
  }
  return {-fx / (L * L), -fy / (L * L)};
}

}  // namespace

TEST(J2Plasticity, UniaxialStrainLoadAndUnloadFollowTheClosedForm) {
  const double L = 1e-3, V = L * L * L;
  const double mu = E / (2 * (1 + nu)), K = E / (3 * (1 - 2 * nu));
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
      const auto [sxx, syy] = stresses(f, L);
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
      const auto [sxx, syy] = stresses(f, L);
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
  EXPECT_NEAR(stresses(plastic, 1e-3).first, stresses(elastic, 1e-3).first, 1e-12 * stresses(elastic, 1e-3).first);
  EXPECT_EQ(plastic.plastic_work(), 0.0);
}

TEST(J2Plasticity, APlasticLayerMustBeIsotropic) {
  LayeredMesh m = block(1, true);
  m.layers[0].elasticity = honeycomb_core(70e9, 0.33, 3e-3, 0.05e-3);
  EXPECT_THROW(FarField f(m), std::invalid_argument);
}

}  // namespace hvi::fem
