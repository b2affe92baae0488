// ExactSum (mpm/exact_sum.hpp): sums that cancel exactly, every order of a wide-ranged set giving
// the same bits, subnormals and values near the largest double, merged accumulators, non-finite
// terms; and against long double sums of well-conditioned terms (to one part in 1e15).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "mpm/exact_sum.hpp"

namespace hvi::mpm {
namespace {

double sum(const std::vector<double>& terms) {
  ExactSum s;
  for (const double x : terms) s += x;
  return s.value();
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

TEST(ExactSum, CancellationIsExact) {
  EXPECT_EQ(sum({1e16, 1.0, -1e16}), 1.0);
  EXPECT_EQ(sum({1.0, 1e100, 1.0, -1e100}), 2.0);
  EXPECT_EQ(sum({}), 0.0);
  EXPECT_EQ(sum({3.5, -3.5}), 0.0);
  EXPECT_EQ(sum({-2.0, -0.5}), -2.5);
  // 0.1 + 0.2 - 0.3 in exact arithmetic of the three doubles: 2^-55 (not what the plain sum gives).
  EXPECT_EQ(sum({0.1, 0.2, -0.3}), std::ldexp(1.0, -55));
}

TEST(ExactSum, EveryOrderGivesTheSameBits) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-60, 60);
  std::vector<double> terms(10000);
  for (auto& x : terms) x = std::ldexp(mantissa(random), exponent(random));
  const double first = sum(terms);
  for (int k = 0; k < 20; ++k) {
    std::shuffle(terms.begin(), terms.end(), random);
    ASSERT_TRUE(same_bits(sum(terms), first));
  }
  // Split in two accumulators at any point and merged: the same bits.
  ExactSum a, b;
  for (std::size_t k = 0; k < terms.size(); ++k) (k % 3 == 0 ? a : b) += terms[k];
  b += a;
  EXPECT_TRUE(same_bits(b.value(), first));
  long double plain = 0.0L;
  for (const double x : terms) plain += x;
  EXPECT_NEAR(first, static_cast<double>(plain), 1e-15 * std::ldexp(1.0, 60));
}

TEST(ExactSum, ExtremesOfTheRange) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  EXPECT_EQ(sum({tiny, tiny, tiny}), 3 * tiny);
  EXPECT_EQ(sum({std::numeric_limits<double>::min(), -tiny}),
            std::numeric_limits<double>::min() - tiny);
  const double big = std::numeric_limits<double>::max();
  EXPECT_EQ(sum({big, big, -big}), big);  // no overflow on the way
  EXPECT_EQ(sum({big, big}), std::numeric_limits<double>::infinity());
  EXPECT_EQ(sum({big, tiny, -big}), tiny);
}

TEST(ExactSum, NonFiniteTerms) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(sum({1.0, inf, 2.0}), inf);
  EXPECT_EQ(sum({-inf, 1.0}), -inf);
  EXPECT_TRUE(std::isnan(sum({inf, 1.0, -inf})));
  EXPECT_TRUE(std::isnan(sum({1.0, std::numeric_limits<double>::quiet_NaN()})));
}

}  // namespace
}  // namespace hvi::mpm
