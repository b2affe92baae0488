// The node average behind grid.dilatation = "node-average" (mpm/volumetric_average.hpp): it
// reproduces a constant exactly (partition of unity), keeps bodies and failed points apart, and is
// symmetric in the volume-weighted product, sum V a Abar(b) = sum V b Abar(a): the identity that
// lets the averaged mean stress in the force pay exactly the work of the averaged dilatation (the
// whole scheme's energy balance is tested on the Taylor bar, tests/verification). The solver takes
// both averages inside other transfers (the mean stress's gather in the force scatter, the
// dilatation's scatter in the velocity gradient's pass); they give what the separate passes give.
#include <algorithm>
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
  Cloud(std::size_t n, ShapeFunction shape, std::uint64_t seed)
      : grid(test::grid({-0.006, -0.006, -0.006}, 1e-3, {12, 12, 12})) {
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
  for (std::size_t p = 0; p < value.size(); ++p)
    ASSERT_NEAR(out[p], value[p], 1e-13 * std::fabs(value[p])) << p;
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

// The force scatter with TransferContext::mean_stress gathers mbar_p - m_p itself: the nodal forces
// are those of a plain scatter of sigma_p + (mbar_p - m_p) 1, with mbar from node_average, to
// round-off (the two add V sigma and V shift in another order).
TEST_P(NodeAverageTest, ForceScatterTakesTheMeanStressAverageInItsPass) {
  Cloud c(3000, GetParam(), 14);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e8, 1e8);
  std::vector<double> mean(c.P.size()), skip(c.P.size(), 0.0);
  for (std::size_t p = 0; p < c.P.size(); ++p) {
    for (int k = 0; k < 6; ++k) c.P.stress[6 * p + k] = u(rng);
    c.P.mass[p] = 2700 * c.P.volume[p];
    mean[p] = trace_sym(&c.P.stress[6 * p]) / 3.0;
    if (p % 9 == 4) skip[p] = 1.0;
  }
  NodeAverageSums sums{NodeAverage{mean.data(), c.P.body.data(), 2, skip.data()}, nullptr};
  std::vector<double> storage;
  sums.sums = &storage;
  node_average_scatter(c.P, c.bins, c.grid, c.context, sums);
  TransferContext fused = c.context;
  fused.mean_stress = &sums;
  particles_to_grid(Scatter::force, c.P, c.bins, c.grid, fused);
  std::vector<double> f_fused;
  for (std::uint32_t b = 0; b < c.grid.block_count(); ++b)
    for (int k = 0; k < SparseGrid::block_size; ++k)
      for (int d = 0; d < 3; ++d) f_fused.push_back(c.grid.node(b, k).f[d]);

  std::vector<double> average;
  node_average_gather(c.P, c.bins, c.grid, c.context, sums, average);
  for (std::size_t p = 0; p < c.P.size(); ++p)
    if (skip[p] == 0.0)
      for (const int k : {sym::xx, sym::yy, sym::zz}) c.P.stress[6 * p + k] += average[p] - mean[p];
  for (std::uint32_t b = 0; b < c.grid.block_count(); ++b)
    for (int k = 0; k < SparseGrid::block_size; ++k)
      for (int d = 0; d < 3; ++d) c.grid.node(b, k).f[d] = 0.0;
  particles_to_grid(Scatter::force, c.P, c.bins, c.grid, c.context);
  double scale = 0.0, worst = 0.0;
  std::size_t i = 0;
  for (std::uint32_t b = 0; b < c.grid.block_count(); ++b)
    for (int k = 0; k < SparseGrid::block_size; ++k)
      for (int d = 0; d < 3; ++d, ++i) {
        scale = std::max(scale, std::fabs(c.grid.node(b, k).f[d]));
        worst = std::max(worst, std::fabs(c.grid.node(b, k).f[d] - f_fused[i]));
      }
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(worst, 1e-13 * scale);
}

// The velocity gradient with the dilatation's sums leaves d_p = tr L_p and the sums exactly as a
// plain velocity gradient followed by node_average_scatter of tr L_p does (the same additions in
// the same order).
TEST_P(NodeAverageTest, VelocityGradientScattersTheDilatationInItsPass) {
  Cloud c(3000, GetParam(), 15);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> skip(c.P.size(), 0.0);
  for (std::size_t p = 0; p < c.P.size(); ++p) {
    c.P.mass[p] = 2700 * c.P.volume[p];
    for (int d = 0; d < 3; ++d) c.P.velocity[3 * p + d] = 100 * u(rng);
    if (p % 5 == 2) skip[p] = 1.0;
  }
  particles_to_grid(Scatter::mass_momentum, c.P, c.bins, c.grid,
                    c.context);  // some nodal p to take L from
  std::vector<double> trace(c.P.size()), fused_sums;
  const NodeAverageSums fused{NodeAverage{trace.data(), c.P.body.data(), 2, skip.data()},
                              &fused_sums};
  velocity_gradient(c.P, c.bins, c.grid, c.context, NodalVelocity::start, &fused, &trace);
  const std::vector<double> L_fused = c.P.velocity_gradient;

  std::vector<double> plain_trace(c.P.size()), plain_sums;
  velocity_gradient(c.P, c.bins, c.grid, c.context, NodalVelocity::start);
  for (std::size_t p = 0; p < c.P.size(); ++p) {
    const double* L = &c.P.velocity_gradient[9 * p];
    plain_trace[p] = L[0] + L[4] + L[8];
  }
  const NodeAverageSums plain{NodeAverage{plain_trace.data(), c.P.body.data(), 2, skip.data()},
                              &plain_sums};
  node_average_scatter(c.P, c.bins, c.grid, c.context, plain);
  EXPECT_EQ(L_fused, c.P.velocity_gradient);
  EXPECT_EQ(trace, plain_trace);
  EXPECT_EQ(fused_sums, plain_sums);
  EXPECT_GT(*std::max_element(plain_sums.begin(), plain_sums.end()), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Shapes, NodeAverageTest,
                         ::testing::Values(ShapeFunction::linear, ShapeFunction::gimp));

}  // namespace
}  // namespace hvi::mpm
