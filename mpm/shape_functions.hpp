#pragma once
// Grid shape functions in one dimension, in cell units: s is the particle coordinate measured
// from the grid origin in cells, node i sits at s = i. A 3D weight is the tensor product
// N_I(x) = N_i(s_x) N_j(s_y) N_k(s_z); its gradient carries 1/h.
//
// Each shape function has a fixed stencil `width` of nodes per axis starting at `lowest(s, a)`;
// weights outside the support come out as exact zeros.
#include <cmath>

#include "mpm/simd.hpp"

namespace hvi::mpm {

enum class ShapeFunction {
  linear,  // hat functions (standard MPM)
  gimp,    // uGIMP: particle domains keep their initial size
  cpgimp,  // GIMP with axis-aligned domains that stretch with the flow: a_d <- a_d (1 + dt L_dd)
};
inline bool is_gimp(ShapeFunction s) {
  return s != ShapeFunction::linear;
}

// Standard MPM hat functions: N = 1 - |s - i| for |s - i| < 1 (the paper's choice, Sec. 2.3).
struct LinearShape {
  static constexpr int width = 2;
  static int lowest(double s, double /*half_width*/) { return static_cast<int>(std::floor(s)); }
  static void weights(double s, int i0, double /*half_width*/, double* N, double* dN) {
    const double r = s - i0;
    N[0] = 1.0 - r;
    N[1] = r;
    dN[0] = -1.0;
    dN[1] = 1.0;
  }
};

// uGIMP (Bardenhagen & Kober 2004): the hat function convolved with the particle's
// characteristic function of half-width a (in cells, a <= 1/2, fixed at its initial value).
// With d = s - i:
//   |d| < a          N = 1 - (d^2 + a^2) / (2a)
//   a <= |d| < 1-a   N = 1 - |d|
//   1-a <= |d| < 1+a N = (1 + a - |d|)^2 / (4a)
// The support 1 + a <= 3/2 spans at most three nodes per axis.
struct GimpShape {
  static constexpr int width = 3;
  static int lowest(double s, double a) { return static_cast<int>(std::floor(s - a)); }
  // The nodes i0, i0 + 1, i0 + 2 for any i0, in lanes 0-2 of four (lane 3 is i0 + 3). Which piece
  // a node falls on depends on where the particle sits in its cell, random from one particle to
  // the next, so each node forms every piece's value and selects its own, without a branch; the
  // quotients by 2a and 4a are products with 1/a, one division a point and axis.
  static void weights4(double s, int i0, double a, double* N, double* dN) {
    using v = simd::d4;
    const double r = 1.0 / a, half_r = 0.5 * r, quarter_r = 0.25 * r;
    const v d = s - (static_cast<double>(i0) + v{0.0, 1.0, 2.0, 3.0});
    const v ad = d < 0.0 ? -d : d;
    const v sgn = d < 0.0 ? v{} - 1.0 : v{} + 1.0;
    const v u = (1.0 + a) - ad;
    const auto inner = ad < a, middle = ad < 1.0 - a, outer = ad < 1.0 + a;
    const v zero{};
    const v n = inner    ? 1.0 - (d * d + a * a) * half_r
                : middle ? 1.0 - ad
                : outer  ? u * u * quarter_r
                         : zero;
    const v dn = inner ? -d * r : middle ? -sgn : outer ? -sgn * u * half_r : zero;
    simd::store<4>(N, n);
    simd::store<4>(dN, dn);
  }
  static void weights(double s, int i0, double a, double* N, double* dN) {
    double n[4], dn[4];
    weights4(s, i0, a, n, dn);
    for (int k = 0; k < width; ++k) {
      N[k] = n[k];
      dN[k] = dn[k];
    }
  }

  // The stencil from the lowest node, i0 = lowest(s, a), on the three axes at once (lanes x, y,
  // z): N[axis][k], dN[axis][k] of node i0 + k, k = 0..2, and 0 for k = 3. There the pieces
  // follow from one test per axis: the middle node is inside the particle's domain (|d_1| < a)
  // when the particle reaches three nodes, and then the outer nodes are on the tails,
  //   N_0 = u_0^2 / (4a), N_1 = 1 - (d_1^2 + a^2) / (2a), N_2 = u_2^2 / (4a),  u_k = 1 + a - |d_k|;
  // else it reaches two, on the hat's flanks: N_0 = 1 - d_0, N_1 = 1 - |d_1|, N_2 = 0. Each value
  // is the expression weights() forms for its piece, so the two agree to the bit but within
  // round-off of a joint, where the pieces agree to round-off (tests/mpm/test_shape_functions.cpp).
  static void weights_from_lowest(const double* s, const double* a, const int* i0, double (*N)[4],
                                  double (*dN)[4]) {
    using v = simd::d4;
    const v sv = {s[0], s[1], s[2], 0.5},
            av = {a[0], a[1], a[2], 0.25};  // lane 3: a harmless filler
    const v base = {static_cast<double>(i0[0]), static_cast<double>(i0[1]),
                    static_cast<double>(i0[2]), 0.0};
    const v r = 1.0 / av, half_r = 0.5 * r, quarter_r = 0.25 * r;
    const v d0 = sv - base, d1 = sv - (base + 1.0), d2 = sv - (base + 2.0);
    const auto three = d1 < av && -d1 < av;              // |d_1| < a
    const v u0 = (1.0 + av) - d0, u2 = (1.0 + av) + d2;  // 1 + a - |d|: d_0 > 0, d_2 < 0
    const v one = v{} + 1.0, zero{};
    const v n[3] = {three ? u0 * u0 * quarter_r : 1.0 - d0,
                    three ? 1.0 - (d1 * d1 + av * av) * half_r : 1.0 + d1,
                    three ? u2 * u2 * quarter_r : zero};
    const v dn[3] = {three ? -u0 * half_r : -one, three ? -d1 * r : one,
                     three ? u2 * half_r : zero};
    for (int axis = 0; axis < 3; ++axis) {
      for (int k = 0; k < 3; ++k) {
        N[axis][k] = n[k][axis];
        dN[axis][k] = dn[k][axis];
      }
      N[axis][3] = dN[axis][3] = 0.0;
    }
  }
};

}  // namespace hvi::mpm
