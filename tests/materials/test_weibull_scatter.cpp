// Failure thresholds with scatter (materials/weibull_scatter.hpp): over 10^5 point ids the factors
// have the Weibull distribution's closed-form moments and distribution function, and a point's
// factor depends on its id and the seed alone.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "materials/weibull_scatter.hpp"

namespace hvi::materials {
namespace {

constexpr int kPoints = 100000;

std::vector<double> factors(const WeibullScatter& w, std::int64_t first = 0) {
  std::vector<double> k(kPoints);
  for (int i = 0; i < kPoints; ++i) k[i] = w.factor(first + i);
  return k;
}

// Mean 1 and variance Gamma(1 + 2/m) / Gamma(1 + 1/m)^2 - 1, for a narrow and a wide scatter. The
// sample mean's standard error is sqrt(variance / 10^5): 4.7e-4 at m = 8; the tolerances are 6 of
// those, and 2% on the variance (its standard error is about 0.6% at these moduli).
TEST(WeibullScatter, MomentsOverATenthOfAMillionPoints) {
  for (const double m : {4.0, 8.0, 16.0}) {
    SCOPED_TRACE(m);
    const WeibullScatter w{m, 7};
    const auto k = factors(w);
    double sum = 0, sum2 = 0;
    for (const double x : k) {
      sum += x;
      sum2 += x * x;
    }
    const double mean = sum / kPoints, variance = sum2 / kPoints - mean * mean;
    const double g1 = std::tgamma(1 + 1 / m), g2 = std::tgamma(1 + 2 / m);
    const double exact_variance = g2 / (g1 * g1) - 1;
    EXPECT_NEAR(mean, 1.0, 6 * std::sqrt(exact_variance / kPoints));
    EXPECT_NEAR(variance / exact_variance, 1.0, 0.02);
    EXPECT_GT(*std::min_element(k.begin(), k.end()), 0.0);
  }
}

// The empirical distribution against P(k' <= k) = 1 - exp(-(k Gamma(1 + 1/m))^m): the
// Kolmogorov-Smirnov distance stays below its 1% critical value, 1.63 / sqrt(n).
TEST(WeibullScatter, DistributionFunctionIsWeibulls) {
  const double m = 8.0;
  const WeibullScatter w{m, 3};
  auto k = factors(w);
  std::sort(k.begin(), k.end());
  const double g1 = std::tgamma(1 + 1 / m);
  double distance = 0.0;
  for (int i = 0; i < kPoints; ++i) {
    const double F = 1.0 - std::exp(-std::pow(k[i] * g1, m));
    distance = std::max(
        {distance, std::fabs(F - double(i) / kPoints), std::fabs(F - double(i + 1) / kPoints)});
  }
  EXPECT_LT(distance, 1.63 / std::sqrt(double(kPoints)));
}

// The same id and seed give the same bits (any thread, any rank, any order of the points); another
// seed, or neighbouring ids, draw factors that are not correlated.
TEST(WeibullScatter, AFactorIsItsIdsAndSeedsAlone) {
  const WeibullScatter a{8.0, 1}, b{8.0, 2};
  const WeibullScatter again{8.0, 1};
  EXPECT_EQ(a.factor(123456), again.factor(123456));
  const auto ka = factors(a), kb = factors(b);
  double ab = 0, aa = 0, bb = 0, lag = 0;
  for (int i = 0; i < kPoints; ++i) {
    const double x = ka[i] - 1, y = kb[i] - 1;
    ab += x * y;
    aa += x * x;
    bb += y * y;
    if (i > 0) lag += x * (ka[i - 1] - 1);
  }
  EXPECT_LT(std::fabs(ab / std::sqrt(aa * bb)),
            0.015);  // 4.7 standard errors of a zero correlation
  EXPECT_LT(std::fabs(lag / aa), 0.015);
}

}  // namespace
}  // namespace hvi::materials
