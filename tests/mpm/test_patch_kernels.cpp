// The transfers' patch kernels (mpm/transfers.cpp, mpm/transfer_kernels.hpp: short vectors on a
// block's patch, lanes summed apart) against the plain sums they stand for, node by node and point
// by point, on random clouds with GIMP and linear shape functions:
//   scatter:  m_I = sum N m_p, p_I = sum N m_p v_p, f_I = -sum V_p sigma_p grad N_I
//   gather:   dv_p = sum N dv_I, vg_p = sum N (v_I + dv_I), q_I = sum N m_p v_p (the MUSL remap)
//   gradient: L_p = sum q_I (x) grad N_I
//   average:  a_I = sum N V a / sum N V over a group, abar_p = sum N a_I
// The plain sums run node by node in another order, so the two agree to round-off: within 1e-13
// of the sum of the terms' magnitudes (a few hundred terms of a few ulps each).
#include <array>
#include <cmath>
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "mpm/grid.hpp"
#include "mpm/particle_bins.hpp"
#include "mpm/particles.hpp"
#include "mpm/shape_functions.hpp"
#include "mpm/transfers.hpp"
#include "mpm/types.hpp"

namespace hvi::mpm {
namespace {

constexpr double h = 1e-3, tolerance = 1e-13;

struct Cloud {
  Particles P;
  std::vector<double> half_width;  // GIMP, m
  std::vector<std::int64_t> group;
  std::vector<double> value, skip;
};

// n points in [-6, 6) mm: a few per cell, so blocks hold several and the patches overlap.
void fill(Cloud& c, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  c.P.resize(n);
  c.half_width.resize(3 * n);
  for (std::size_t p = 0; p < n; ++p) {
    for (int d = 0; d < 3; ++d) {
      c.P.position[3 * p + d] = -6e-3 + 12e-3 * u(rng);
      c.P.velocity[3 * p + d] = 100.0 * (u(rng) - 0.5);
      c.half_width[3 * p + d] = h * (0.05 + 0.45 * u(rng));
    }
    c.P.mass[p] = 1e-6 * (1.0 + u(rng));
    c.P.volume0[p] = c.P.volume[p] = 1e-10 * (1.0 + u(rng));
    for (int k = 0; k < 6; ++k) c.P.stress[6 * p + k] = 1e8 * (2.0 * u(rng) - 1.0);
    c.group.push_back(static_cast<std::int64_t>(p % 3));
    c.value.push_back(u(rng) - 0.3);
    c.skip.push_back(p % 7 == 0 ? 1.0 : 0.0);
  }
}

GridGeometry geometry() {
  GridGeometry g;
  g.origin = {-0.01, -0.01, -0.01};
  g.cell_size = h;
  g.cells = {20, 20, 20};
  return g;
}

// Point p's nodes: f(i, j, k, N, grad N) with the general weights (GimpShape::weights). Its
// coordinates in cells are formed as the transfers form them, x / h as x (1 / h): a weight on the
// support's tail, (1 + a - |d|)^2 / (4a), takes the last bit of s and a to a relative 1e-12.
template <class F>
void for_each_node(const Cloud& c, ShapeFunction shape, std::size_t p, F&& f) {
  const GridGeometry g = geometry();
  const double inv_h = 1.0 / h;
  const int W = shape == ShapeFunction::linear ? 2 : 3;
  int i0[3];
  double N[3][3], dN[3][3];
  for (int d = 0; d < 3; ++d) {
    const double s = (c.P.position[3 * p + d] - g.origin[d]) * inv_h;
    if (W == 2) {
      i0[d] = LinearShape::lowest(s, 0.0);
      LinearShape::weights(s, i0[d], 0.0, N[d], dN[d]);
    } else {
      const double a = c.half_width[3 * p + d] * inv_h;
      i0[d] = GimpShape::lowest(s, a);
      GimpShape::weights(s, i0[d], a, N[d], dN[d]);
    }
  }
  for (int z = 0; z < W; ++z)
    for (int y = 0; y < W; ++y)
      for (int x = 0; x < W; ++x) {
        const double grad[3] = {dN[0][x] * N[1][y] * N[2][z] / h, N[0][x] * dN[1][y] * N[2][z] / h,
                                N[0][x] * N[1][y] * dN[2][z] / h};
        f(std::array<int, 3>{i0[0] + x, i0[1] + y, i0[2] + z}, N[0][x] * N[1][y] * N[2][z], grad);
      }
}

// A value and the sum of its terms' magnitudes, the scale its round-off is judged against.
struct Sum {
  double value = 0.0, scale = 0.0;
  void add(double x) {
    value += x;
    scale += std::fabs(x);
  }
};
void expect_near(double kernel, const Sum& plain, const char* what) {
  EXPECT_NEAR(kernel, plain.value, tolerance * plain.scale + 1e-300) << what;
}

struct Setup {
  ShapeFunction shape;
  Cloud c;
  SparseGrid grid{geometry()};
  ParticleBins bins;
  TransferContext ctx;
  explicit Setup(ShapeFunction s, std::uint64_t seed) : shape(s) {
    fill(c, 3000, seed);
    const std::vector<double>* hw = shape == ShapeFunction::linear ? nullptr : &c.half_width;
    bin_particles(c.P, {shape, hw}, grid, bins, {});
    ctx.shape = shape;
    ctx.half_width = hw;
  }
};

void check_scatter(ShapeFunction shape) {
  Setup s(shape, 11);
  particles_to_grid(Scatter::mass_momentum_force, s.c.P, s.bins, s.grid, s.ctx);
  std::map<std::array<int, 3>, std::array<Sum, 7>> plain;
  for (std::size_t p = 0; p < s.c.P.size(); ++p)
    for_each_node(s.c, shape, p, [&](const std::array<int, 3>& n, double w, const double* g) {
      auto& node = plain[n];
      const double m = s.c.P.mass[p], V = s.c.P.volume[p];
      const double* v = &s.c.P.velocity[3 * p];
      const double* sig = &s.c.P.stress[6 * p];
      const double S[3][3] = {{sig[sym::xx], sig[sym::xy], sig[sym::xz]},
                              {sig[sym::xy], sig[sym::yy], sig[sym::yz]},
                              {sig[sym::xz], sig[sym::yz], sig[sym::zz]}};
      node[0].add(w * m);
      for (int d = 0; d < 3; ++d) {
        node[1 + d].add(w * m * v[d]);
        for (int j = 0; j < 3; ++j) node[4 + d].add(-V * S[d][j] * g[j]);
      }
    });
  ASSERT_GT(plain.size(), 1000u);
  for (const auto& [n, sums] : plain) {
    const auto node = s.grid.node(n[0], n[1], n[2]);
    ASSERT_TRUE(node.has_value());
    expect_near(node->mass, sums[0], "mass");
    for (int d = 0; d < 3; ++d) {
      expect_near(node->p[d], sums[1 + d], "momentum");
      expect_near(node->f[d], sums[4 + d], "force");
    }
  }
}

TEST(PatchKernels, ScatterIsThePlainSumGimp) {
  check_scatter(ShapeFunction::gimp);
}
TEST(PatchKernels, ScatterIsThePlainSumLinear) {
  check_scatter(ShapeFunction::linear);
}

// Random nodal v_I, dv_I and q_I (as after update_grid and the remap), so the gathers see values
// with no structure that could hide a wrong node.
void fill_nodes(SparseGrid& grid, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::uint32_t b = 0; b < grid.block_count(); ++b)
    for (int l = 0; l < SparseGrid::block_size; ++l) {
      const GridNode n = grid.node(b, l);
      n.mass = 1.0;
      for (int d = 0; d < 3; ++d) {
        n.p[d] = 100.0 * u(rng);
        n.f[d] = 10.0 * u(rng);
        n.q[d] = 100.0 * u(rng);
      }
    }
}

void check_gathers(ShapeFunction shape) {
  Setup s(shape, 12);
  fill_nodes(s.grid, 13);
  // The remap adds to q: start it at zero, keep the gradient's input apart.
  std::map<std::array<int, 3>, std::array<double, 3>> q_in;
  for (std::uint32_t b = 0; b < s.grid.block_count(); ++b)
    for (int l = 0; l < SparseGrid::block_size; ++l)
      for (int d = 0; d < 3; ++d) s.grid.node(b, l).q[d] = 0.0;
  const std::vector<double> v0 = s.c.P.velocity;
  s.ctx.flip = 0.9;
  grid_to_particles(s.c.P, s.bins, s.grid, s.ctx, true);
  std::map<std::array<int, 3>, std::array<Sum, 3>> q;
  for (std::size_t p = 0; p < s.c.P.size(); ++p) {
    Sum dv[3], vg[3];
    for_each_node(s.c, shape, p, [&](const std::array<int, 3>& n, double w, const double*) {
      const auto node = std::as_const(s.grid).node(n[0], n[1], n[2]);
      for (int d = 0; d < 3; ++d) {
        dv[d].add(w * node->f[d]);
        vg[d].add(w * (node->p[d] + node->f[d]));
      }
    });
    for (int d = 0; d < 3; ++d) {
      expect_near(s.c.P.grid_velocity[3 * p + d], vg[d], "grid velocity");
      Sum v;
      v.add(0.9 * (v0[3 * p + d] + dv[d].value));
      v.add(0.1 * vg[d].value);
      v.scale += dv[d].scale + vg[d].scale;
      expect_near(s.c.P.velocity[3 * p + d], v, "velocity");
    }
    for_each_node(s.c, shape, p, [&](const std::array<int, 3>& n, double w, const double*) {
      for (int d = 0; d < 3; ++d) q[n][d].add(w * s.c.P.mass[p] * s.c.P.velocity[3 * p + d]);
    });
  }
  for (const auto& [n, sums] : q)
    for (int d = 0; d < 3; ++d)
      expect_near(s.grid.node(n[0], n[1], n[2])->q[d], sums[d], "remapped momentum");

  // The gradient of the remapped field as it now stands.
  velocity_gradient(s.c.P, s.bins, s.grid, s.ctx, NodalVelocity::remapped);
  for (std::size_t p = 0; p < s.c.P.size(); ++p) {
    Sum L[9];
    for_each_node(s.c, shape, p, [&](const std::array<int, 3>& n, double, const double* g) {
      const auto node = std::as_const(s.grid).node(n[0], n[1], n[2]);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) L[3 * i + j].add(node->q[i] * g[j]);
    });
    for (int k = 0; k < 9; ++k)
      expect_near(s.c.P.velocity_gradient[9 * p + k], L[k], "velocity gradient");
  }
}

TEST(PatchKernels, GathersAreThePlainSumsGimp) {
  check_gathers(ShapeFunction::gimp);
}
TEST(PatchKernels, GathersAreThePlainSumsLinear) {
  check_gathers(ShapeFunction::linear);
}

void check_average(ShapeFunction shape) {
  Setup s(shape, 14);
  std::vector<double> sums, out;
  const NodeAverage average{s.c.value.data(), s.c.group.data(), 3, s.c.skip.data()};
  node_average(s.c.P, s.bins, s.grid, s.ctx, average, sums, out);
  std::map<std::pair<std::array<int, 3>, std::int64_t>, std::array<Sum, 2>> node;
  for (std::size_t p = 0; p < s.c.P.size(); ++p) {
    if (s.c.skip[p] > 0.0) continue;
    for_each_node(s.c, shape, p, [&](const std::array<int, 3>& n, double w, const double*) {
      auto& a = node[{n, s.c.group[p]}];
      a[0].add(w * s.c.P.volume[p] * s.c.value[p]);
      a[1].add(w * s.c.P.volume[p]);
    });
  }
  for (std::size_t p = 0; p < s.c.P.size(); ++p) {
    if (s.c.skip[p] > 0.0) {
      EXPECT_EQ(out[p], 0.0);
      continue;
    }
    Sum abar;
    for_each_node(s.c, shape, p, [&](const std::array<int, 3>& n, double w, const double*) {
      const auto& a = node[{n, s.c.group[p]}];
      if (a[1].value > 0.0) {
        abar.add(w * a[0].value / a[1].value);
        abar.scale += w * a[0].scale / a[1].value;  // the round-off of the node's own sums
      }
    });
    expect_near(out[p], abar, "node average");
  }
}

TEST(PatchKernels, NodeAverageIsThePlainAverageGimp) {
  check_average(ShapeFunction::gimp);
}
TEST(PatchKernels, NodeAverageIsThePlainAverageLinear) {
  check_average(ShapeFunction::linear);
}

}  // namespace
}  // namespace hvi::mpm
