// Shape functions (mpm/shape_functions.hpp): partition of unity and zero gradient sum in 1D and
// for the 3D tensor product, hand-computed uGIMP values, continuity across the pieces, that
// the fixed stencil starting at lowest() covers the whole support, and that the branch-free uGIMP
// weights are bit for bit the piecewise formula.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "mpm/shape_functions.hpp"

namespace hvi::mpm {
namespace {

// Weights are sums of 2 or 3 (1D) or at most 27 products (3D) of numbers <= 1: a few ulp each,
// so 1e-14 is round-off with a margin of ~10.
constexpr double kRoundOff = 1e-14;
constexpr int kSamples = 20000;
const double kHalfWidths[] = {1e-3, 0.05, 0.125, 0.25, 1.0 / 3.0, 0.4, 0.5};

// N and dN of node i (d = s - i) for half-width a, straight from GimpShape::weights (node i0 = i).
double gimp_N(double d, double a) {
  double N[3], dN[3];
  GimpShape::weights(d, 0, a, N, dN);
  return N[0];
}
double gimp_dN(double d, double a) {
  double N[3], dN[3];
  GimpShape::weights(d, 0, a, N, dN);
  return dN[0];
}

TEST(ShapeFunctions, LinearPartitionOfUnity1D) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  for (int k = 0; k < kSamples; ++k) {
    const double s = u(rng);
    const int i0 = LinearShape::lowest(s, 0.0);
    double N[2], dN[2];
    LinearShape::weights(s, i0, 0.0, N, dN);
    ASSERT_NEAR(N[0] + N[1], 1.0, kRoundOff) << "s = " << s;
    ASSERT_EQ(dN[0] + dN[1], 0.0) << "s = " << s;  // -1 + 1: exact
    ASSERT_GE(N[0], 0.0);
    ASSERT_GE(N[1], 0.0);
    // The hat function itself: N_i = 1 - |s - i| (ulp-level, one subtraction each).
    ASSERT_NEAR(N[0], 1.0 - std::fabs(s - i0), kRoundOff);
    ASSERT_NEAR(N[1], 1.0 - std::fabs(s - (i0 + 1)), kRoundOff);
  }
}

TEST(ShapeFunctions, GimpPartitionOfUnity1D) {
  std::mt19937_64 rng(23456);
  std::uniform_real_distribution<double> u(-50.0, 50.0);
  for (const double a : kHalfWidths) {
    SCOPED_TRACE("a = " + std::to_string(a));
    for (int k = 0; k < kSamples; ++k) {
      const double s = u(rng);
      const int i0 = GimpShape::lowest(s, a);
      double N[3], dN[3];
      GimpShape::weights(s, i0, a, N, dN);
      ASSERT_NEAR(N[0] + N[1] + N[2], 1.0, kRoundOff) << "s = " << s;
      // Derivatives are bounded by 1 (|d|/a < 1, u/(2a) <= 1): the sum is round-off of O(1) terms.
      ASSERT_NEAR(dN[0] + dN[1] + dN[2], 0.0, kRoundOff) << "s = " << s;
      for (int j = 0; j < 3; ++j) ASSERT_GE(N[j], 0.0);
      // The stencil covers the support: the nodes just outside it carry exactly nothing.
      ASSERT_EQ(gimp_N(s - (i0 - 1), a), 0.0) << "s = " << s;
      ASSERT_EQ(gimp_N(s - (i0 + 3), a), 0.0) << "s = " << s;
    }
  }
}

// The 1D weights and derivatives of a 3D stencil, as the transfers evaluate them.
template <class Shape>
struct Stencil {
  double N[3][Shape::width], dN[3][Shape::width];
  void evaluate(const double* s, double a) {
    for (int d = 0; d < 3; ++d) Shape::weights(s[d], Shape::lowest(s[d], a), a, N[d], dN[d]);
  }
};

template <class Shape>
void check_tensor_product(double a, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-20.0, 20.0);
  for (int k = 0; k < kSamples / 4; ++k) {
    const double s[3] = {u(rng), u(rng), u(rng)};
    Stencil<Shape> st;
    st.evaluate(s, a);
    double sum = 0.0, grad[3] = {0, 0, 0};
    constexpr int W = Shape::width;
    for (int i = 0; i < W; ++i)
      for (int j = 0; j < W; ++j)
        for (int l = 0; l < W; ++l) {
          sum += st.N[0][i] * st.N[1][j] * st.N[2][l];
          grad[0] += st.dN[0][i] * st.N[1][j] * st.N[2][l];
          grad[1] += st.N[0][i] * st.dN[1][j] * st.N[2][l];
          grad[2] += st.N[0][i] * st.N[1][j] * st.dN[2][l];
        }
    ASSERT_NEAR(sum, 1.0, kRoundOff) << s[0] << " " << s[1] << " " << s[2];
    for (int d = 0; d < 3; ++d) ASSERT_NEAR(grad[d], 0.0, kRoundOff) << "axis " << d;
  }
}

TEST(ShapeFunctions, LinearTensorProduct3D) {
  check_tensor_product<LinearShape>(0.0, 777);
}

TEST(ShapeFunctions, GimpTensorProduct3D) {
  std::uint64_t seed = 888;
  for (const double a : kHalfWidths) {
    SCOPED_TRACE("a = " + std::to_string(a));
    check_tensor_product<GimpShape>(a, seed++);
  }
}

// Values worked out by hand from the uGIMP formula (exact binary fractions where possible, so
// the comparison is to round-off).
TEST(ShapeFunctions, GimpHandValues) {
  const double a = 0.25;
  // Centre: 1 - a/2.
  EXPECT_NEAR(gimp_N(0.0, a), 0.875, kRoundOff);
  EXPECT_NEAR(gimp_dN(0.0, a), 0.0, kRoundOff);
  // Inner parabola, d = -0.1: 1 - (0.01 + 0.0625) / 0.5 = 0.855; dN = 0.1 / 0.25 = 0.4.
  EXPECT_NEAR(gimp_N(-0.1, a), 0.855, kRoundOff);
  EXPECT_NEAR(gimp_dN(-0.1, a), 0.4, kRoundOff);
  // Linear region a <= |d| < 1 - a: the hat function.
  EXPECT_NEAR(gimp_N(0.5, a), 0.5, kRoundOff);
  EXPECT_NEAR(gimp_dN(0.5, a), -1.0, kRoundOff);
  EXPECT_NEAR(gimp_N(-0.6, a), 0.4, kRoundOff);
  EXPECT_NEAR(gimp_dN(-0.6, a), 1.0, kRoundOff);
  // Quadratic tail, d = 1: (1 + a - 1)^2 / (4a) = 0.0625 / 1; dN = -(0.25) / 0.5 = -0.5.
  EXPECT_NEAR(gimp_N(1.0, a), 0.0625, kRoundOff);
  EXPECT_NEAR(gimp_dN(1.0, a), -0.5, kRoundOff);
  // d = -1.125: u = 0.125, N = 0.015625, dN = +0.25.
  EXPECT_NEAR(gimp_N(-1.125, a), 0.015625, kRoundOff);
  EXPECT_NEAR(gimp_dN(-1.125, a), 0.25, kRoundOff);
  // End of the support 1 + a and beyond: exactly zero.
  EXPECT_EQ(gimp_N(1.25, a), 0.0);
  EXPECT_EQ(gimp_N(-1.3, a), 0.0);
  // a = 1/2: no linear region; centre 3/4, tail at d = 1: 0.25 / 2 = 0.125.
  EXPECT_NEAR(gimp_N(0.0, 0.5), 0.75, kRoundOff);
  EXPECT_NEAR(gimp_N(1.0, 0.5), 0.125, kRoundOff);
  // As a -> 0 uGIMP tends to the hat function: |N - (1 - |d|)| <= a/2 (the centre defect).
  for (double d = -0.95; d < 1.0; d += 0.1) EXPECT_NEAR(gimp_N(d, 1e-6), 1.0 - std::fabs(d), 1e-6);
}

// N and dN/ds are continuous at the piece boundaries |d| = a, 1 - a, 1 + a: the jump across
// [b - e, b + e] is at most slope * 2e (N) or curvature * 2e (dN). With e = 1e-9 and slopes,
// curvatures <= 1/a <= 1e3 here, a jump of 1e-5 would be a real discontinuity (the uGIMP pieces
// join with value and slope, so a wrong piece would jump by O(a) or O(1)).
TEST(ShapeFunctions, GimpContinuity) {
  const double e = 1e-9;
  for (const double a : kHalfWidths) {
    if (a < 0.01) continue;  // curvature 1/a makes the bound loose; covered by the others
    SCOPED_TRACE("a = " + std::to_string(a));
    for (const double b : {a, 1.0 - a, 1.0 + a}) {
      for (const double sign : {-1.0, 1.0}) {
        const double lo = sign * (b - e), hi = sign * (b + e);
        EXPECT_NEAR(gimp_N(lo, a), gimp_N(hi, a), 2 * e / a + 1e-15) << "N at d = " << sign * b;
        EXPECT_NEAR(gimp_dN(lo, a), gimp_dN(hi, a), 2 * e / a + 1e-15) << "dN at d = " << sign * b;
      }
    }
    // And the derivative is the derivative: central difference of N (truncation O(e^2 N''') = 0
    // on quadratics; round-off ~ 1e-16 / 1e-6 = 1e-10) at random points away from the joints.
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> u(-1.6, 1.6);
    for (int k = 0; k < 2000; ++k) {
      const double d = u(rng);
      const double de = 1e-6;
      bool near_joint = false;
      for (const double b : {a, 1.0 - a, 1.0 + a, 0.0})
        near_joint |= std::fabs(std::fabs(d) - b) < 2 * de;
      if (near_joint) continue;
      const double fd = (gimp_N(d + de, a) - gimp_N(d - de, a)) / (2 * de);
      ASSERT_NEAR(fd, gimp_dN(d, a), 1e-8) << "d = " << d;
    }
  }
}

// GimpShape::weights selects its piece without branching, for the three nodes in one short vector
// (for speed, mpm/shape_functions.hpp). The piecewise form, written out as the uGIMP formula reads
// (its quotients by 2a and 4a as products with 1/a, as the kernel forms them), must give the same
// bits: a run's output is compared byte for byte between builds and thread counts. Random points,
// and points on and beside the joints |d| = a, 1 - a, 1 + a (where a wrong comparison would pick
// the neighbouring piece, whose value agrees to round-off only), all bit for bit.
void piecewise_gimp(double d, double a, double& N, double& dN) {
  const double ad = std::fabs(d);
  const double sgn = d < 0.0 ? -1.0 : 1.0;
  const double r = 1.0 / a;
  if (ad < a) {
    N = 1.0 - (d * d + a * a) * (0.5 * r);
    dN = -d * r;
  } else if (ad < 1.0 - a) {
    N = 1.0 - ad;
    dN = -sgn;
  } else if (ad < 1.0 + a) {
    const double u = 1.0 + a - ad;
    N = u * u * (0.25 * r);
    dN = -sgn * u * (0.5 * r);
  } else {
    N = 0.0;
    dN = 0.0;
  }
}

void expect_bitwise_piecewise(double s, double a) {
  const int i0 = GimpShape::lowest(s, a);
  double N[3], dN[3];
  GimpShape::weights(s, i0, a, N, dN);
  for (int k = 0; k < 3; ++k) {
    double Nr, dNr;
    piecewise_gimp(s - (i0 + k), a, Nr, dNr);
    ASSERT_EQ(std::signbit(N[k]), std::signbit(Nr));
    ASSERT_EQ(N[k], Nr) << "s = " << s << ", a = " << a << ", node " << k;
    ASSERT_EQ(dN[k], dNr) << "s = " << s << ", a = " << a << ", node " << k;
  }
}

TEST(ShapeFunctions, GimpWeightsBitwiseThePiecewiseForm) {
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> u(-50.0, 50.0), half(0.01, 0.5);
  for (int k = 0; k < kSamples; ++k) expect_bitwise_piecewise(u(rng), half(rng));
  for (const double a : kHalfWidths)
    for (const double b : {0.0, a, 1.0 - a, 1.0 + a})
      for (const double i : {-3.0, 0.0, 7.0})
        for (const double sign : {-1.0, 1.0}) {
          const double s = i + sign * b;
          expect_bitwise_piecewise(s, a);
          expect_bitwise_piecewise(std::nextafter(s, -1e9), a);
          expect_bitwise_piecewise(std::nextafter(s, 1e9), a);
        }
}

// GimpShape::weights_from_lowest, the transfers' path: one piece test per axis, the three axes in
// one short vector. Each value is the expression weights() forms for its piece, so the two agree
// to the bit, but where weights() and the one test pick neighbouring pieces, within round-off of
// a joint |d| = a, 1 - a, 1 + a. There the pieces agree to within the round-off of d, a few ulps of
// s, times their slopes (dN' <= 1 / a): 8 ulp(|s| + 1) / a.
TEST(ShapeFunctions, GimpWeightsFromTheLowestNodeAreWeights) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> u(-50.0, 50.0), half(0.01, 0.5);
  int exact = 0, samples = 0;
  for (int k = 0; k < kSamples; ++k) {
    double s[3], a[3], N[3][4], dN[3][4];
    int i0[3];
    for (int d = 0; d < 3; ++d) {
      s[d] = u(rng);
      a[d] = half(rng);
      if (k % 4 == 0)
        s[d] = std::round(s[d]) + (d == 0 ? a[d] : d == 1 ? 1.0 - a[d] : -a[d]);  // on joints
      i0[d] = GimpShape::lowest(s[d], a[d]);
    }
    GimpShape::weights_from_lowest(s, a, i0, N, dN);
    for (int d = 0; d < 3; ++d) {
      double Nr[3], dNr[3];
      GimpShape::weights(s[d], i0[d], a[d], Nr, dNr);
      bool same = N[d][3] == 0.0 && dN[d][3] == 0.0;
      const double tolerance =
          8 * std::numeric_limits<double>::epsilon() * (std::fabs(s[d]) + 1.0) / a[d];
      for (int j = 0; j < 3; ++j) {
        ASSERT_NEAR(N[d][j], Nr[j], tolerance)
            << "s = " << s[d] << ", a = " << a[d] << ", node " << j;
        ASSERT_NEAR(dN[d][j], dNr[j], tolerance)
            << "s = " << s[d] << ", a = " << a[d] << ", node " << j;
        same = same && N[d][j] == Nr[j] && dN[d][j] == dNr[j];
      }
      exact += same;
      ++samples;
    }
  }
  // Away from the joints every value is the same bits: all but a few of the points on them.
  EXPECT_GT(exact, samples * 9 / 10);
}

// simd::sum4 adds each vector's lanes in the order of simd::sum, so the four sums are the same
// bits.
TEST(Simd, FourSumsAtOnceAddInTheOrderOfOne) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 1000; ++k) {
    simd::d4 v[4];
    for (auto& x : v) x = simd::d4{u(rng), 1e10 * u(rng), u(rng), 1e-10 * u(rng)};
    const simd::d4 s = simd::sum4(v[0], v[1], v[2], v[3]);
    for (int j = 0; j < 4; ++j) ASSERT_EQ(s[j], simd::sum(v[j]));
  }
}

}  // namespace
}  // namespace hvi::mpm
