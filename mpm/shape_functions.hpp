#pragma once
// Grid shape functions in one dimension, in cell units: s is the particle coordinate measured
// from the grid origin in cells, node i sits at s = i. A 3D weight is the tensor product
// N_I(x) = N_i(s_x) N_j(s_y) N_k(s_z); its gradient carries 1/h.
//
// Each shape function has a fixed stencil `width` of nodes per axis starting at `lowest(s, a)`;
// weights outside the support come out as exact zeros.
#include <cmath>

namespace hvi::mpm {

enum class ShapeFunction {
  linear,  // hat functions (standard MPM)
  gimp,    // uGIMP: particle domains keep their initial size
  cpgimp,  // GIMP with axis-aligned domains that stretch with the flow: a_d <- a_d (1 + dt L_dd)
};
inline bool is_gimp(ShapeFunction s) { return s != ShapeFunction::linear; }

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
  static void weights(double s, int i0, double a, double* N, double* dN) {
    // Which piece a node falls on depends on where the particle sits in its cell, random from
    // one particle to the next, so a branch on it cannot be predicted. Each node therefore forms
    // its two quotients from selected operands and then selects its piece: every selected value
    // is the expression of the piecewise form above, with the same operands in the same order,
    // so the weights are the same to the last bit (tests/mpm/test_shape_functions.cpp).
    const double two_a = 2.0 * a, four_a = 4.0 * a;
    for (int k = 0; k < width; ++k) {
      const double d = s - (i0 + k);
      const double ad = std::fabs(d);
      const double sgn = d < 0.0 ? -1.0 : 1.0;
      const double u = 1.0 + a - ad;
      const bool inner = ad < a, middle = ad < 1.0 - a, outer = ad < 1.0 + a;
      const double n_quotient = (inner ? d * d + a * a : u * u) / (inner ? two_a : four_a);
      const double dn_quotient = (inner ? -d : -sgn * u) / (inner ? a : two_a);
      N[k] = inner ? 1.0 - n_quotient : middle ? 1.0 - ad : outer ? n_quotient : 0.0;
      dN[k] = inner ? dn_quotient : middle ? -sgn : outer ? dn_quotient : 0.0;
    }
  }
};


}  // namespace hvi::mpm
