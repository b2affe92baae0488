// Particle -> grid transfers (mpm/transfers.hpp, mpm/particle_bins.hpp): a random particle cloud
// scatters exactly its mass and momentum to the nodes and internal forces that sum to zero, for
// linear and GIMP shape functions; the sparse grid allocates blocks only near particles; a
// StencilCache gives the same bits as weights evaluated in every pass; particles grown in bulk
// hold exactly their size.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <random>
#include <utility>

#include <gtest/gtest.h>

#include "mpm/grid.hpp"
#include "mpm/particle_bins.hpp"
#include "mpm/particles.hpp"
#include "mpm/transfers.hpp"

namespace hvi::mpm {
namespace {

struct Cloud {
  Particles P;
  std::vector<double> half_width;  // m, 3 per particle
};

// n particles uniformly at random in [lo, hi)^3 (m), masses in [1, 2) mg, velocities with a
// non-zero mean (so the total momentum is O(n), not a cancellation), stresses of both signs,
// volumes for a quarter-cell-ish size, and a GIMP half-width up to h/2.
void fill_cloud(Cloud& c, std::size_t n, double lo, double hi, double h, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  c.P.resize(n);
  c.half_width.resize(3 * n);
  for (std::size_t p = 0; p < n; ++p) {
    for (int d = 0; d < 3; ++d) {
      c.P.position[3 * p + d] = lo + (hi - lo) * u(rng);
      c.P.velocity[3 * p + d] = 100.0 * (u(rng) - 0.3 + 0.2 * d);
    }
    c.P.mass[p] = 1e-6 * (1.0 + u(rng));
    const double size = h * (0.3 + 0.7 * u(rng));  // particle edge, m
    c.P.volume0[p] = c.P.volume[p] = size * size * size;
    for (int d = 0; d < 3; ++d) c.half_width[3 * p + d] = 0.5 * size;
    for (int k = 0; k < 6; ++k) c.P.stress[6 * p + k] = 1e8 * (2.0 * u(rng) - 1.0);
    c.P.id[p] = static_cast<std::int64_t>(p);
  }
}

struct Sums {
  double mass = 0, momentum[3] = {0, 0, 0}, force[3] = {0, 0, 0};
  double abs_momentum[3] = {0, 0, 0}, abs_force[3] = {0, 0, 0};
};

Sums nodal_sums(const SparseGrid& grid) {
  Sums s;
  for (std::uint32_t b = 0; b < grid.block_count(); ++b) {
    for (int k = 0; k < SparseGrid::block_size; ++k) {
      const ConstGridNode n = grid.node(b, k);
      s.mass += n.mass;
      for (int d = 0; d < 3; ++d) {
        s.momentum[d] += n.p[d];
        s.abs_momentum[d] += std::fabs(n.p[d]);
        s.force[d] += n.f[d];
        s.abs_force[d] += std::fabs(n.f[d]);
      }
    }
  }
  return s;
}

// 40 x 40 x 40 cells of h from (-20, -20, -20) mm.
GridGeometry cube_grid(double h) {
  GridGeometry g;
  g.origin = {-0.02, -0.02, -0.02};
  g.cell_size = h;
  g.cells = {40, 40, 40};
  return g;
}

// Bins the cloud and scatters its mass, momentum and force.
void scatter_cloud(Cloud& c, ShapeFunction shape, SparseGrid& grid, ParticleBins& bins) {
  const std::vector<double>* hw = shape == ShapeFunction::gimp ? &c.half_width : nullptr;
  bin_particles(c.P, {shape, hw}, grid, bins, {});
  TransferContext ctx;
  ctx.shape = shape;
  ctx.half_width = hw;
  particles_to_grid(Scatter::mass_momentum_force, c.P, bins, grid, ctx);
}

void check_conservation(ShapeFunction shape) {
  const double h = 1e-3;
  const GridGeometry g = cube_grid(h);
  Cloud c;
  // 4000 particles in the inner 30 x 30 x 30 cells: ~0.15 per cell, so most blocks hold a few and
  // the colour scatter crosses many block boundaries.
  fill_cloud(c, 4000, -0.015, 0.015, h, shape == ShapeFunction::linear ? 1 : 2);
  SparseGrid grid(g);
  ParticleBins bins;
  scatter_cloud(c, shape, grid, bins);

  double mass = 0, momentum[3] = {0, 0, 0}, abs_momentum[3] = {0, 0, 0};
  for (std::size_t p = 0; p < c.P.size(); ++p) {
    mass += c.P.mass[p];
    for (int d = 0; d < 3; ++d) {
      momentum[d] += c.P.mass[p] * c.P.velocity[3 * p + d];
      abs_momentum[d] += std::fabs(c.P.mass[p] * c.P.velocity[3 * p + d]);
    }
  }
  const Sums s = nodal_sums(grid);
  std::printf(
      "[transfers %s] %zu blocks; relative errors: mass %.1e, momentum %.1e %.1e %.1e, "
      "force sum %.1e %.1e %.1e\n",
      shape == ShapeFunction::linear ? "linear" : "gimp", grid.block_count(),
      std::fabs(s.mass - mass) / mass, std::fabs(s.momentum[0] - momentum[0]) / abs_momentum[0],
      std::fabs(s.momentum[1] - momentum[1]) / abs_momentum[1],
      std::fabs(s.momentum[2] - momentum[2]) / abs_momentum[2],
      std::fabs(s.force[0]) / s.abs_force[0], std::fabs(s.force[1]) / s.abs_force[1],
      std::fabs(s.force[2]) / s.abs_force[2]);
  // Relative 1e-13: each particle's weights sum to 1 within ~1e-15 and the ~4000-term sums lose
  // at most ~sqrt(n) eps ~ 1e-14 (worst case n eps ~ 4e-13 is not reached by random signs); the
  // momentum is compared relative to sum |m v| as its components have terms of both signs.
  EXPECT_NEAR(s.mass, mass, 1e-13 * mass);
  for (int d = 0; d < 3; ++d) {
    EXPECT_NEAR(s.momentum[d], momentum[d], 1e-13 * abs_momentum[d]) << "axis " << d;
    // A non-trivial check: the totals are not a cancellation.
    EXPECT_GT(std::fabs(momentum[d]), 0.05 * abs_momentum[d]);
    // Internal forces sum to zero since sum_I grad N_I = 0 per particle; relative to sum |f_I|
    // (what the nodes carry), 1e-12 is ~10^3 ulp of headroom over the per-node round-off.
    EXPECT_LT(std::fabs(s.force[d]), 1e-12 * s.abs_force[d]) << "axis " << d;
    EXPECT_GT(s.abs_force[d], 0.0);
  }

  // The bins hold every particle exactly once.
  std::vector<int> seen(c.P.size(), 0);
  for (const auto p : bins.order) ++seen.at(p);
  for (const int k : seen) ASSERT_EQ(k, 1);
}

TEST(Transfers, ConservesMassMomentumForceLinear) {
  check_conservation(ShapeFunction::linear);
}
TEST(Transfers, ConservesMassMomentumForceGimp) {
  check_conservation(ShapeFunction::gimp);
}

// Two clusters of particles, each inside 2 x 2 x 2 cells, `separation` cells apart along every
// axis in a domain of 10^6 cells per axis (10^18 nodes if dense). Returns the active block count.
std::size_t blocks_for_two_clusters(int separation, ShapeFunction shape, std::uint64_t seed) {
  const double h = 1.0;
  GridGeometry g;
  g.cell_size = h;
  g.cells = {1000000, 1000000, 1000000};
  Cloud c;
  // Cluster cells [9, 11): linear stencils reach nodes 9..11, GIMP (a <= h/2) nodes 8..12.
  fill_cloud(c, 200, 9.0, 11.0, h, seed);
  const std::size_t n = c.P.size();
  c.P.resize(2 * n);
  c.half_width.resize(6 * n);
  for (std::size_t p = 0; p < n; ++p) {
    for (int d = 0; d < 3; ++d)
      c.P.position[3 * (n + p) + d] = c.P.position[3 * p + d] + separation;
    c.P.mass[n + p] = c.P.mass[p];
    c.P.volume[n + p] = c.P.volume0[n + p] = c.P.volume[p];
    for (int d = 0; d < 3; ++d) c.half_width[3 * (n + p) + d] = c.half_width[3 * p + d];
  }
  SparseGrid grid(g);
  ParticleBins bins;
  bin_particles(c.P, {shape, shape == ShapeFunction::gimp ? &c.half_width : nullptr}, grid, bins,
                {});
  // Nodes midway between the clusters are not stored.
  const int mid = 10 + separation / 2;
  EXPECT_FALSE(grid.node(mid, mid, mid).has_value());
  EXPECT_TRUE(grid.node(10, 10, 10).has_value());
  EXPECT_TRUE(grid.node(10 + separation, 10 + separation, 10 + separation).has_value());
  return grid.block_count();
}

TEST(Transfers, GridAllocatesOnlyNearParticles) {
  for (const auto shape : {ShapeFunction::linear, ShapeFunction::gimp}) {
    // Separations are multiples of the block edge (4 nodes) so both clusters sit alike in their
    // blocks; the count must not depend on the distance at all (exact).
    const std::size_t near = blocks_for_two_clusters(40, shape, 5);
    const std::size_t far = blocks_for_two_clusters(400000, shape, 5);
    EXPECT_EQ(near, far);
    // Nodes 8..12 (+4 shift: 12..16) fall in blocks 3 and 4 per axis: owner blocks and their
    // +1 neighbours give exactly 2^3 = 8 blocks per cluster.
    EXPECT_EQ(near, 16u);
  }
}

// A step's passes with a StencilCache (mpm/transfers.hpp) give the same bits as passes that each
// evaluate their own weights: the node average's scatter (which skips failed points, yet fills the
// cache for all), the force scatter that gathers it, the velocity gather with its remap and the
// velocity gradient, on a GIMP cloud with a third of its points failed. Then the points move:
// invalidated, the cache is filled again and still agrees; left stale, it must not (else the
// comparison could not tell a cache that is read from one that is not). All exact.
struct PassResults {
  std::vector<double> nodes, velocity, grid_velocity, gradient, average;
};

PassResults run_passes(Cloud& c, const GridGeometry& g, StencilCache* cache,
                       const std::vector<double>& failed) {
  SparseGrid grid(g);
  ParticleBins bins;
  bin_particles(c.P, {ShapeFunction::gimp, &c.half_width}, grid, bins, {});
  TransferContext ctx;
  ctx.shape = ShapeFunction::gimp;
  ctx.half_width = &c.half_width;
  ctx.stencils = cache;
  std::vector<double> value(c.P.size()), sums;
  for (std::size_t p = 0; p < c.P.size(); ++p) value[p] = c.P.stress[6 * p] / 3.0;
  NodeAverageSums mean{{value.data(), c.P.body.data(), 1, failed.data()}, &sums};
  node_average_scatter(c.P, bins, grid, ctx, mean);
  ctx.mean_stress = &mean;
  particles_to_grid(Scatter::mass_momentum_force, c.P, bins, grid, ctx);
  ctx.mean_stress = nullptr;
  grid_to_particles(c.P, bins, grid, ctx, true);
  velocity_gradient(c.P, bins, grid, ctx, NodalVelocity::remapped);
  PassResults r;
  node_average_gather(c.P, bins, grid, ctx, mean, r.average);
  for (std::uint32_t b = 0; b < grid.block_count(); ++b)
    for (int k = 0; k < SparseGrid::block_size; ++k) {
      const ConstGridNode n = std::as_const(grid).node(b, k);
      r.nodes.insert(r.nodes.end(), {n.mass, n.p[0], n.p[1], n.p[2], n.f[0], n.f[1], n.f[2], n.q[0],
                                     n.q[1], n.q[2]});
    }
  r.velocity = c.P.velocity;
  r.grid_velocity = c.P.grid_velocity;
  r.gradient = c.P.velocity_gradient;
  return r;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_same_bits(const PassResults& a, const PassResults& b) {
  EXPECT_TRUE(same_bits(a.nodes, b.nodes));
  EXPECT_TRUE(same_bits(a.velocity, b.velocity));
  EXPECT_TRUE(same_bits(a.grid_velocity, b.grid_velocity));
  EXPECT_TRUE(same_bits(a.gradient, b.gradient));
  EXPECT_TRUE(same_bits(a.average, b.average));
}

TEST(Transfers, StencilCacheGivesTheSameBits) {
  const double h = 1e-3;
  GridGeometry g;
  g.origin = {-0.02, -0.02, -0.02};
  g.cell_size = h;
  g.cells = {40, 40, 40};
  Cloud fresh, cached, stale;  // the same cloud three times
  fill_cloud(fresh, 3000, -0.01, 0.01, h, 31);
  fill_cloud(cached, 3000, -0.01, 0.01, h, 31);
  fill_cloud(stale, 3000, -0.01, 0.01, h, 31);
  std::vector<double> failed(3000, 0.0);
  for (std::size_t p = 0; p < failed.size(); p += 3) failed[p] = 1.0;
  StencilCache cache, stale_cache;
  const PassResults first = run_passes(fresh, g, nullptr, failed);
  expect_same_bits(first, run_passes(cached, g, &cache, failed));
  run_passes(stale, g, &stale_cache, failed);
  EXPECT_TRUE(cache.valid());
  EXPECT_EQ(cache.bytes(), 3000 * sizeof(GimpStencil));

  // The points move by up to a third of a cell; the velocities carry over from the passes.
  std::mt19937_64 rng(32);
  std::uniform_real_distribution<double> u(-h / 3, h / 3);
  for (std::size_t i = 0; i < fresh.P.position.size(); ++i) {
    const double dx = u(rng);
    for (Cloud* c : {&fresh, &cached, &stale}) c->P.position[i] += dx;
  }
  const PassResults moved = run_passes(fresh, g, nullptr, failed);
  cache.invalidate();
  expect_same_bits(moved, run_passes(cached, g, &cache, failed));
  EXPECT_FALSE(same_bits(moved.nodes, run_passes(stale, g, &stale_cache, failed).nodes));
}

// What a run over several ranks rests on (group_sums.hpp): a node's scattered mass, momentum and
// force are, to the bit, its groups' sums added colour by colour from zero, each colour's sums
// being what that colour's points alone scatter. So a rank holding some of a node's groups can
// send the others its sums per colour. 20,000 points at ~5 a cell, so that groups hold several
// blocks and nodes receive several colours.
void check_colour_by_colour(ShapeFunction shape) {
  const double h = 1e-3;
  const GridGeometry g = cube_grid(h);
  Cloud all;
  fill_cloud(all, 20000, -0.008, 0.008, h, 41);
  SparseGrid whole(g);
  ParticleBins bins;
  scatter_cloud(all, shape, whole, bins);
  // Each colour's points on their own grid.
  std::vector<std::unique_ptr<SparseGrid>> colour_grid;
  int colours_met = 0;
  for (int colour = 0; colour < 8; ++colour) {
    Cloud part;
    std::vector<std::size_t> mine;
    for (std::size_t p = 0; p < all.P.size(); ++p) {
      const auto c = SparseGrid::block_coords(whole.key(static_cast<std::uint32_t>(bins.owner[p])));
      if ((((c[0] >> 1) & 1) | (((c[1] >> 1) & 1) << 1) | (((c[2] >> 1) & 1) << 2)) == colour)
        mine.push_back(p);
    }
    part.P.resize(mine.size());
    part.half_width.resize(3 * mine.size());
    for (std::size_t k = 0; k < mine.size(); ++k) {
      const std::size_t p = mine[k];
      for (int d = 0; d < 3; ++d) {
        part.P.position[3 * k + d] = all.P.position[3 * p + d];
        part.P.velocity[3 * k + d] = all.P.velocity[3 * p + d];
        part.half_width[3 * k + d] = all.half_width[3 * p + d];
      }
      for (int i = 0; i < 6; ++i) part.P.stress[6 * k + i] = all.P.stress[6 * p + i];
      part.P.mass[k] = all.P.mass[p];
      part.P.volume0[k] = all.P.volume0[p];
      part.P.volume[k] = all.P.volume[p];
      part.P.id[k] = all.P.id[p];
    }
    colour_grid.push_back(std::make_unique<SparseGrid>(g));
    ParticleBins part_bins;
    scatter_cloud(part, shape, *colour_grid.back(), part_bins);
    colours_met += mine.empty() ? 0 : 1;
  }
  EXPECT_EQ(colours_met, 8);
  std::size_t nodes_of_several_colours = 0;
  for (std::uint32_t b = 0; b < whole.block_count(); ++b)
    for (int l = 0; l < SparseGrid::block_size; ++l) {
      int received = 0;
      for (int v = 0; v < node_value::q; ++v) {  // m, p, f
        double sum = 0.0;
        for (const auto& cg : colour_grid) {
          const std::uint32_t at = cg->find(whole.key(b));
          if (at == SparseGrid::none) continue;
          const double x = cg->values(at, v)[l];
          sum += x;
          if (v == node_value::mass && x > 0.0) ++received;
        }
        const double expected = whole.values(b, v)[l];
        ASSERT_EQ(std::memcmp(&sum, &expected, sizeof sum), 0)
            << "block " << b << " node " << l << " value " << v << ": " << expected << " vs "
            << sum;
      }
      if (received > 1) ++nodes_of_several_colours;
    }
  EXPECT_GT(nodes_of_several_colours, 500u);
}

TEST(Transfers, ANodeAddsItsGroupsSumsColourByColourLinear) {
  check_colour_by_colour(ShapeFunction::linear);
}
TEST(Transfers, ANodeAddsItsGroupsSumsColourByColourGimp) {
  check_colour_by_colour(ShapeFunction::gimp);
}

// Particles grown in bulk (a hybrid's zone taking over far-field cells, Particles::resize) hold
// exactly their size: growing 1,000 particles by a tenth, the fields hold 1,100 particles' bytes,
// where a vector past its capacity would double to 2,000 (exact).
TEST(Particles, ResizeHoldsExactlyTheNewSize) {
  Particles P;
  P.add_field("damage", FieldKind::scalar, "1");
  P.resize(1000);
  const std::size_t per_particle = P.bytes() / 1000;
  EXPECT_EQ(P.bytes(), 1000 * per_particle);
  P.resize(1100);
  EXPECT_EQ(P.size(), 1100u);
  EXPECT_EQ(P.bytes(), 1100 * per_particle);
  EXPECT_EQ(P.field("damage")[1099], 0.0);
}

}  // namespace
}  // namespace hvi::mpm
