#pragma once
// A solid block of the far field for the tests that strain it homogeneously: one isotropic layer
// of Al6061 (the paper's Table 4: E, nu, density; Johnson-Cook A, B, n for J2; D1-D3 for failing
// J2), L = 1 mm on each side, 2 x 2 x 2 elements, and the nodal forces' sums over a face of the
// block; the closed form of J2 in uniaxial strain.
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "fem/far_field.hpp"

namespace hvi::fem::test {

inline constexpr double E = 69e9, nu = 0.33, rho = 2700, L = 1e-3;
inline const double mu = E / (2 * (1 + nu)), lame = E * nu / ((1 + nu) * (1 - 2 * nu));

inline materials::JohnsonCookStrength al6061() {
  materials::JohnsonCookStrength jc;
  jc.A = 324e6;
  jc.B = 114e6;
  jc.n = 0.42;
  return jc;
}

// Table 4's Al6061 damage, its rate and thermal terms left out (the far field's are 1).
inline materials::JohnsonCookDamage al6061_damage() {
  materials::JohnsonCookDamage d;
  d.D1 = -0.77;
  d.D2 = 1.45;
  d.D3 = -0.47;
  return d;
}

inline LayeredMesh block(int degree, bool plastic, bool finite_strain = false) {
  LayeredMesh m;
  m.lower = {0, 0};
  m.x_steps = {0.5 * L, 0.5 * L};
  m.y_steps = {0.5 * L, 0.5 * L};
  m.layers = {{"face", 0, L, 2, isotropic(E, nu), rho,
               plastic ? std::optional(al6061()) : std::nullopt, std::nullopt, std::nullopt}};
  m.degree = degree;
  m.finite_strain = finite_strain;
  return m;
}

// u = A X + c at every node (A = F - I of a homogeneous deformation).
inline void deform(FarField& f, const std::array<std::array<double, 3>, 3>& A,
                   const std::array<double, 3>& c = {}) {
  auto u = f.displacement();
  const auto x = f.reference_positions();
  for (std::size_t a = 0; a < f.node_count(); ++a)
    for (int i = 0; i < 3; ++i)
      u[3 * a + i] = c[i] + A[i][0] * x[3 * a] + A[i][1] * x[3 * a + 1] + A[i][2] * x[3 * a + 2];
}

// A block in motion: the nodes at z = 0 fixed, the others at v = (vx, 0, vz) z / L.
inline void throw_block(FarField& f, double vx, double vz) {
  const auto x = f.reference_positions();
  for (std::size_t a = 0; a < f.node_count(); ++a) {
    const bool base = x[3 * a + 2] < 1e-12 * L;
    if (base) f.fix(a, 7u);
    f.velocity()[3 * a] = base ? 0.0 : vx * x[3 * a + 2] / L;
    f.velocity()[3 * a + 2] = base ? 0.0 : vz * x[3 * a + 2] / L;
  }
}

// The internal force summed over the nodes of the reference face X_axis = L: for a homogeneous
// first Piola-Kirchhoff stress P it is -P N L^2 with N the face's normal, so column `axis` of P
// is -sum / L^2.
inline std::array<double, 3> face_force(const std::vector<double>& force, const FarField& f,
                                        int axis) {
  const auto x = f.reference_positions();
  std::array<double, 3> sum{};
  for (std::size_t a = 0; a < f.node_count(); ++a)
    if (std::abs(x[3 * a + axis] - L) < 1e-12)
      for (int i = 0; i < 3; ++i) sum[i] += force[3 * a + i];
  return sum;
}

// Uniaxial strain e along x with J2 and radial flow: eps_p = alpha diag(1, -1/2, -1/2), so
//   s_xx = 2 mu (2e/3 - alpha),  s_yy = s_zz = 2 mu (alpha/2 - e/3),  q = 2 mu |e - 3/2 alpha|,
// and on loading the consistency condition 2 mu (e - 3/2 alpha) = A + B alpha^n fixes alpha
// (solved here by bisection, independently of the code's Newton iteration).
// With a rate factor k (eq. 1's 1 + C ln epsdot*) the yield stress is k (A + B alpha^n).
struct Uniaxial {
  double mu, K;
  materials::JohnsonCookStrength jc;
  double k = 1.0;
  double alpha_on_loading(double e) const {
    if (2 * mu * e <= k * jc.A) return 0.0;
    double lo = 0, hi = e / 1.5;
    for (int i = 0; i < 200; ++i) {
      const double a = 0.5 * (lo + hi);
      (2 * mu * (e - 1.5 * a) > k * jc.hardening(a) ? lo : hi) = a;
    }
    return 0.5 * (lo + hi);
  }
  double sxx(double e, double alpha) const { return K * e + 2 * mu * (2 * e / 3 - alpha); }
  double syy(double e, double alpha) const { return K * e + 2 * mu * (alpha / 2 - e / 3); }
};

}  // namespace hvi::fem::test
