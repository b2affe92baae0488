// The node average behind grid.dilatation = "node-average" (mpm/volumetric_average.hpp): it
// reproduces a constant exactly (partition of unity), keeps bodies and failed points apart, and is
// symmetric in the volume-weighted product, sum V a Abar(b) = sum V b Abar(a): the identity that
// lets the averaged mean stress in the force pay exactly the work of the averaged dilatation (the
// whole scheme's energy balance is tested on the Taylor bar, tests/verification).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "mpm/transfers.hpp"
#include "tests/mpm/mpm_test_helpers.hpp"

namespace hvi::mpm {
namespace {

struct Cloud {
  Particles P;
  std::vector<double> half_width;
  SparseGrid grid;
  ParticleBins bins;
  TransferContext context;

  // n random particles in [-4, 4) mm^3 on 1 mm cells, bodies 0 and 1 interleaved.
  Cloud(std::size_t n, ShapeFunction shape, std::uint64_t seed) : grid(test::grid({-0.006, -0.006, -0.006}, 1e-3, {12, 12, 12})) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    P.resize(n);
    half_width.resize(3 * n);
    for (std::size_t p = 0; p < n; ++p) {
      for (int d = 0; d < 3; ++d) P.position[3 * p + d] = -0.004 + 0.008 * u(rng);
      const double size = 1e-3 * (0.3 + 0.7 * u(rng));
      P.volume0[p] = P.volume[p] = size * size * size;
      for (int d = 0; d < 3; ++d) half_width[3 * p + d] = 0.5 * size;
      P.body[p] = static_cast<std::int64_t>(p % 2);
      P.id[p] = static_cast<std::int64_t>(p);
    }
    context.shape = shape;
    context.half_width = shape == ShapeFunction::linear ? nullptr : &half_width;
    bin_particles(P, {shape, context.half_width}, grid, bins, {});
  }
  std::vector<double> average(const std::vector<double>& value, const double* skip = nullptr) {
    NodeAverage a;
    a.value = value.data();
    a.group = P.body.data();
    a.groups = 2;
    a.skip = skip;
    std::vector<double> sums, out;
    node_average(P, bins, grid, context, a, sums, out);
    return out;
  }
};

class NodeAverageTest : public ::testing::TestWithParam<ShapeFunction> {};

TEST_P(NodeAverageTest, ReproducesAConstantPerBody) {
  Cloud c(3000, GetParam(), 11);
  std::vector<double> value(c.P.size());
  for (std::size_t p = 0; p < value.size(); ++p) value[p] = c.P.body[p] == 0 ? 3.7 : -250.0;
  const auto out = c.average(value);
  // Partition of unity: each body gets back its own constant wherever the bodies overlap.
  for (std::size_t p = 0; p < value.size(); ++p) ASSERT_NEAR(out[p], value[p], 1e-13 * std::fabs(value[p])) << p;
}

TEST_P(NodeAverageTest, FailedPointsNeitherCountNorChange) {
  Cloud c(3000, GetParam(), 12);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> value(c.P.size()), skip(c.P.size(), 0.0);
  for (std::size_t p = 0; p < value.size(); ++p) {
    value[p] = u(rng);
    if (p % 7 == 3) skip[p] = 1.0;
  }
  const auto a = c.average(value, skip.data());
  for (std::size_t p = 0; p < value.size(); ++p)
    if (skip[p] > 0.0) value[p] = 1e6;  // what failed points carry must not matter
  const auto b = c.average(value, skip.data());
  for (std::size_t p = 0; p < value.size(); ++p) {
    if (skip[p] > 0.0)
      EXPECT_EQ(b[p], 0.0);
    else
      ASSERT_EQ(a[p], b[p]) << p;
  }
}

TEST_P(NodeAverageTest, IsSymmetricInTheVolumeWeightedProduct) {
  Cloud c(3000, GetParam(), 13);
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> a(c.P.size()), b(c.P.size());
  for (std::size_t p = 0; p < a.size(); ++p) {
    a[p] = u(rng);
    b[p] = u(rng);
  }
  const auto abar = c.average(a), bbar = c.average(b);
  double left = 0.0, right = 0.0, scale = 0.0;
  for (std::size_t p = 0; p < a.size(); ++p) {
    left += c.P.volume[p] * a[p] * bbar[p];
    right += c.P.volume[p] * b[p] * abar[p];
    scale += c.P.volume[p] * std::fabs(a[p] * bbar[p]);
  }
  EXPECT_NEAR(left, right, 1e-13 * scale);
}

INSTANTIATE_TEST_SUITE_P(Shapes, NodeAverageTest,
                         ::testing::Values(ShapeFunction::linear, ShapeFunction::gimp));

}  // namespace
}  // namespace hvi::mpm
