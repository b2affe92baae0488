#include "mpm/transfers.hpp"

#include <algorithm>
#include <cstdint>
#include <type_traits>

#include "mpm/types.hpp"

namespace hvi::mpm {
namespace {

// The stencil of one particle, resolved to node addresses inside its owner block's neighbourhood.
template <class Shape>
struct NodeStencil {
  static constexpr int W = Shape::width;
  double N[3][W], dN[3][W];
  int lowest[3];          // lowest node per axis, relative to the owner block's first node
  int node_offset[3][W];  // local node index contribution per axis
  int block_bit[3][W];    // neighbour bit per axis
  int first[3], last[3];  // the nodes with nonzero weight per axis (GIMP: 2 or 3 of the 3)

  // a: GIMP half-width per axis in cells (nullptr for linear shape functions).
  void evaluate(const double* x, const GridGeometry& g, double inv_h, const double* a,
                const std::array<int, 3>& block_origin) {
    for (int d = 0; d < 3; ++d) {
      const double s = (x[d] - g.origin[d]) * inv_h;
      const double ad = a ? a[d] : 0.0;
      const int base = Shape::lowest(s, ad);
      Shape::weights(s, base, ad, N[d], dN[d]);
      lowest[d] = base - block_origin[d];
      // Skipping nodes of zero weight adds nothing to any sum, so results are unchanged.
      first[d] = 0;
      last[d] = W - 1;
      if constexpr (W > 2) {
        while (N[d][first[d]] == 0.0 && dN[d][first[d]] == 0.0) ++first[d];
        while (N[d][last[d]] == 0.0 && dN[d][last[d]] == 0.0) --last[d];
      }
    }
    resolve_nodes();
  }

  // Into and out of a StencilCache (the weights, lowest nodes and nonzero ranges).
  void store(StencilWeights<W>& c) const {
    for (int d = 0; d < 3; ++d) {
      for (int k = 0; k < W; ++k) {
        c.N[d][k] = N[d][k];
        c.dN[d][k] = dN[d][k];
      }
      c.lowest[d] = static_cast<std::int8_t>(lowest[d]);
      c.first[d] = static_cast<std::int8_t>(first[d]);
      c.last[d] = static_cast<std::int8_t>(last[d]);
    }
  }
  void load(const StencilWeights<W>& c) {
    for (int d = 0; d < 3; ++d) {
      for (int k = 0; k < W; ++k) {
        N[d][k] = c.N[d][k];
        dN[d][k] = c.dN[d][k];
      }
      lowest[d] = c.lowest[d];
      first[d] = c.first[d];
      last[d] = c.last[d];
    }
    resolve_nodes();
  }

  void resolve_nodes() {
    static constexpr int stride[3] = {1, SparseGrid::block_edge, SparseGrid::block_edge * SparseGrid::block_edge};
    for (int d = 0; d < 3; ++d)
      for (int k = 0; k < W; ++k) {
        const int l = lowest[d] + k;  // 0 .. 2*edge-1
        block_bit[d][k] = (l / SparseGrid::block_edge) << d;
        node_offset[d][k] = (l % SparseGrid::block_edge) * stride[d];
      }
  }

  // f(node, weight, gradient[3]) for every node of the stencil; gradient in 1/m.
  template <class Node, class F>
  void for_each(Node* const* blocks, double inv_h, F&& f) const {
    // Linear stencils always use both nodes: constant bounds let the compiler unroll them.
    const int z0 = W > 2 ? first[2] : 0, z1 = W > 2 ? last[2] : W - 1;
    const int y0 = W > 2 ? first[1] : 0, y1 = W > 2 ? last[1] : W - 1;
    const int x0 = W > 2 ? first[0] : 0, x1 = W > 2 ? last[0] : W - 1;
    for (int kz = z0; kz <= z1; ++kz)
      for (int ky = y0; ky <= y1; ++ky) {
        const double nyz = N[1][ky] * N[2][kz];
        const double dy = dN[1][ky] * N[2][kz] * inv_h, dz = N[1][ky] * dN[2][kz] * inv_h;
        const int bit_yz = block_bit[1][ky] | block_bit[2][kz];
        const int off_yz = node_offset[1][ky] + node_offset[2][kz];
        for (int kx = x0; kx <= x1; ++kx) {
          Node* node = blocks[block_bit[0][kx] | bit_yz] + (node_offset[0][kx] + off_yz);
          const double grad[3] = {dN[0][kx] * nyz * inv_h, N[0][kx] * dy, N[0][kx] * dz};
          f(*node, N[0][kx] * nyz, grad);
        }
      }
  }
};

struct Setup {
  const GridGeometry& g;
  double inv_h;
  const double* half_width;  // 3 per particle, m
  const NodeAverageSums* mean_stress;  // gathered into the force scatter; nullptr for none
  // GIMP with a StencilCache: read the step's stencils from `read`, or evaluate them and, in a
  // pass that visits every binned point, store them in `fill`. Both nullptr: evaluate.
  const GimpStencil* read;
  GimpStencil* fill;
  // Half-widths of particle p in cells, per axis, in `out`; nullptr for linear shape functions.
  const double* a(std::size_t p, double* out) const {
    if (!half_width) return nullptr;
    for (int d = 0; d < 3; ++d) out[d] = half_width[3 * p + d] * inv_h;
    return out;
  }
  // Particle p's stencil in st.
  template <class Shape>
  void stencil(NodeStencil<Shape>& st, const Particles& P, std::uint32_t p,
               const std::array<int, 3>& origin) const {
    if constexpr (std::is_same_v<Shape, GimpShape>)
      if (read) {
        st.load(read[p]);
        return;
      }
    double a_cells[3];
    st.evaluate(&P.position[3 * p], g, inv_h, a(p, a_cells), origin);
    if constexpr (std::is_same_v<Shape, GimpShape>)
      if (fill) st.store(fill[p]);
  }
};

// Where a node average keeps its sums for a particle's group at node n: (sum N V a, sum N V) at
// sums[slot], sums[slot + 1]. Nodes are indexed by their place in the grid's storage.
struct SumsSlot {
  const GridNode* base;
  int groups;
  std::size_t operator()(const GridNode& n, std::int64_t group) const {
    return 2 * (static_cast<std::size_t>(&n - base) * groups + static_cast<std::size_t>(group));
  }
};

// Zeroed sums for every block of the grid, 64 nodes x groups x 2 values per block.
void zero_sums(const SparseGrid& grid, int groups, std::vector<double>& sums) {
  const auto block_values = static_cast<std::int64_t>(SparseGrid::block_size) * groups * 2;
  const auto blocks = static_cast<std::int64_t>(grid.block_count());
  sums.resize(static_cast<std::size_t>(blocks * block_values));
  double* zero = sums.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) std::fill_n(zero + b * block_values, block_values, 0.0);
}

// abar_p = sum_I N_I(x_p) (sum N V a / sum N V)_(I, group of p) over the nodes of p's stencil.
template <class Shape, class Node>
double gather_average(const NodeStencil<Shape>& st, Node* const* blocks, double inv_h, const double* sums,
                      const SumsSlot& slot, std::int64_t group) {
  double average = 0.0;
  st.for_each(blocks, inv_h, [&](const GridNode& n, double w, const double*) {
    const double* sum = &sums[slot(n, group)];
    if (sum[1] > 0.0) average += w * sum[0] / sum[1];
  });
  return average;
}

// Runs f(b, blocks, origin) for every owner block b, with blocks[o] the eight blocks its
// particles' stencils reach and origin its first node. Coloured: blocks of one colour in
// parallel, colour after colour, so f may write nodes (see particle_bins.hpp). Plain: all blocks
// in parallel, f may only read nodes.
template <class F>
void for_each_block_coloured(const ParticleBins& bins, SparseGrid& grid, F&& f) {
  for (const auto& colour : bins.colour) {
    const auto count = static_cast<std::int64_t>(colour.size());
#pragma omp parallel for schedule(dynamic, 1)
    for (std::int64_t i = 0; i < count; ++i) {
      const std::uint32_t b = colour[i];
      GridNode* blocks[8];
      for (int o = 0; o < 8; ++o) blocks[o] = grid.block(bins.neighbours[b][o]);
      f(b, blocks, grid.block_origin(b));
    }
  }
}

template <class F>
void for_each_block(const ParticleBins& bins, const SparseGrid& grid, F&& f) {
  const auto owners = static_cast<std::int64_t>(bins.owner_count());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t i = 0; i < owners; ++i) {
    const auto b = static_cast<std::uint32_t>(i);
    const GridNode* blocks[8];
    for (int o = 0; o < 8; ++o) blocks[o] = grid.block(bins.neighbours[b][o]);
    f(b, blocks, grid.block_origin(b));
  }
}

template <class Shape, Scatter What>
void scatter(const Particles& P, const ParticleBins& bins, SparseGrid& grid, const Setup& s) {
  constexpr bool mass = What != Scatter::force;
  constexpr bool momentum = What != Scatter::force;
  constexpr bool force = What == Scatter::mass_momentum_force || What == Scatter::force;
  const NodeAverageSums* mean = force ? s.mean_stress : nullptr;
  const SumsSlot slot{grid.block(0), mean ? mean->average.groups : 1};
  for_each_block_coloured(
      bins, grid, [&](std::uint32_t b, GridNode* const* blocks, const std::array<int, 3>& origin) {
        NodeStencil<Shape> st;
        for (std::uint32_t k = bins.offset[b]; k < bins.offset[b + 1]; ++k) {
          const std::uint32_t p = bins.order[k];
          s.stencil(st, P, p, origin);
          const double m = P.mass[p];
          const double* v = &P.velocity[3 * p];
          const double mv[3] = {m * v[0], m * v[1], m * v[2]};
          double vs[6] = {};  // V_p sigma_p
          if constexpr (force) {
            const double V = P.volume[p];
            for (int c = 0; c < 6; ++c) vs[c] = V * P.stress[6 * p + c];
            if (mean) {  // V_p (mbar_p - m_p) 1, mbar_p from the sums scattered before this pass
              const NodeAverage& a = mean->average;
              const double shift =
                  a.counts(p) ? gather_average(st, blocks, s.inv_h, mean->sums->data(), slot, a.group[p]) - a.value[p]
                              : 0.0;
              for (const int c : {sym::xx, sym::yy, sym::zz}) vs[c] += V * shift;
            }
          }
          st.for_each(blocks, s.inv_h, [&](GridNode& n, double w, const double* g) {
            if constexpr (mass) n.mass += w * m;
            if constexpr (momentum) {
              n.p[0] += w * mv[0];
              n.p[1] += w * mv[1];
              n.p[2] += w * mv[2];
            }
            if constexpr (force) {
              n.f[0] -= vs[sym::xx] * g[0] + vs[sym::xy] * g[1] + vs[sym::xz] * g[2];
              n.f[1] -= vs[sym::xy] * g[0] + vs[sym::yy] * g[1] + vs[sym::yz] * g[2];
              n.f[2] -= vs[sym::xz] * g[0] + vs[sym::yz] * g[1] + vs[sym::zz] * g[2];
            }
          });
        }
      });
}

// One particle's velocity update; with Remap also its share of the remapped momentum.
template <class Shape, bool Remap, class Blocks>
void gather_velocity_of(Particles& P, std::uint32_t p, Blocks blocks,
                        const std::array<int, 3>& origin, const Setup& s, double flip,
                        NodeStencil<Shape>& st) {
  s.stencil(st, P, p, origin);
  double dv[3] = {0, 0, 0}, vg[3] = {0, 0, 0};
  st.for_each(blocks, s.inv_h, [&](const GridNode& n, double w, const double*) {
    for (int d = 0; d < 3; ++d) {
      dv[d] += w * n.f[d];
      vg[d] += w * (n.p[d] + n.f[d]);
    }
  });
  double* v = &P.velocity[3 * p];
  for (int d = 0; d < 3; ++d) {
    v[d] = flip * (v[d] + dv[d]) + (1.0 - flip) * vg[d];
    P.grid_velocity[3 * p + d] = vg[d];
  }
  if constexpr (Remap) {
    const double m = P.mass[p];
    const double mv[3] = {m * v[0], m * v[1], m * v[2]};
    st.for_each(blocks, s.inv_h, [&](GridNode& n, double w, const double*) {
      n.q[0] += w * mv[0];
      n.q[1] += w * mv[1];
      n.q[2] += w * mv[2];
    });
  }
}

template <class Shape>
void gather_velocity(Particles& P, const ParticleBins& bins, SparseGrid& grid, const Setup& s,
                     double flip, bool remap) {
  if (remap) {  // scatters too: colour by colour, like particles_to_grid
    for_each_block_coloured(
        bins, grid,
        [&](std::uint32_t b, GridNode* const* blocks, const std::array<int, 3>& origin) {
          NodeStencil<Shape> st;
          for (std::uint32_t k = bins.offset[b]; k < bins.offset[b + 1]; ++k)
            gather_velocity_of<Shape, true>(P, bins.order[k], blocks, origin, s, flip, st);
        });
    return;
  }
  for_each_block(
      bins, grid,
      [&](std::uint32_t b, const GridNode* const* blocks, const std::array<int, 3>& origin) {
        NodeStencil<Shape> st;
        for (std::uint32_t k = bins.offset[b]; k < bins.offset[b + 1]; ++k)
          gather_velocity_of<Shape, false>(P, bins.order[k], blocks, origin, s, flip, st);
      });
}

// L_p of the particles of owner block b; with Average also a_p = tr L_p into the dilatation's
// values and sums (blocks then writable: colour by colour).
template <class Shape, NodalVelocity Which, bool Average, class Node>
void gradient_of_block(Particles& P, const ParticleBins& bins, std::uint32_t b, Node* const* blocks,
                       const std::array<int, 3>& origin, const Setup& s, const NodeAverageSums* dilatation,
                       double* trace, const SumsSlot& slot) {
  NodeStencil<Shape> st;
  for (std::uint32_t k = bins.offset[b]; k < bins.offset[b + 1]; ++k) {
    const std::uint32_t p = bins.order[k];
    s.stencil(st, P, p, origin);
    double L[9] = {};
    st.for_each(blocks, s.inv_h, [&](const GridNode& n, double, const double* g) {
      double v[3];
      for (int d = 0; d < 3; ++d) {
        if constexpr (Which == NodalVelocity::start) v[d] = n.p[d];
        if constexpr (Which == NodalVelocity::end) v[d] = n.p[d] + n.f[d];
        if constexpr (Which == NodalVelocity::remapped) v[d] = n.q[d];
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) L[3 * i + j] += v[i] * g[j];
    });
    double* Lp = &P.velocity_gradient[9 * p];
    for (int c = 0; c < 9; ++c) Lp[c] = L[c];
    if constexpr (Average) {
      const NodeAverage& a = dilatation->average;
      trace[p] = Lp[0] + Lp[4] + Lp[8];
      if (!a.counts(p)) continue;
      const double V = P.volume[p], Va = V * trace[p];
      double* sums = dilatation->sums->data();
      st.for_each(blocks, s.inv_h, [&](GridNode& n, double w, const double*) {
        double* sum = &sums[slot(n, a.group[p])];
        sum[0] += w * Va;
        sum[1] += w * V;
      });
    }
  }
}

template <class Shape, NodalVelocity Which>
void gather_gradient(Particles& P, const ParticleBins& bins, SparseGrid& grid, const Setup& s,
                     const NodeAverageSums* dilatation, std::vector<double>* trace) {
  const SumsSlot slot{grid.block(0), dilatation ? dilatation->average.groups : 1};
  if (!dilatation) {
    for_each_block(bins, grid, [&](std::uint32_t b, const GridNode* const* blocks, const std::array<int, 3>& origin) {
      gradient_of_block<Shape, Which, false>(P, bins, b, blocks, origin, s, nullptr, nullptr, slot);
    });
    return;
  }
  zero_sums(grid, dilatation->average.groups, *dilatation->sums);
  double* t = trace->data();
  for_each_block_coloured(bins, grid, [&](std::uint32_t b, GridNode* const* blocks, const std::array<int, 3>& origin) {
    gradient_of_block<Shape, Which, true>(P, bins, b, blocks, origin, s, dilatation, t, slot);
  });
}

// Without a cache (and for outward_normals, which runs on either field of a contact pair).
Setup make_setup(const SparseGrid& grid, const TransferContext& c) {
  return {grid.geometry(), 1.0 / grid.geometry().cell_size,
          c.half_width ? c.half_width->data() : nullptr, c.mean_stress, nullptr, nullptr};
}

// With GIMP and a StencilCache: read it if it is filled; else, if this pass visits every binned
// point (`visits_all`), fill it as the pass evaluates (finish_pass then marks it filled).
Setup make_setup(const Particles& P, const SparseGrid& grid, const TransferContext& c, bool visits_all) {
  Setup s = make_setup(grid, c);
  if (!c.stencils || c.shape == ShapeFunction::linear) return s;
  if (c.stencils->valid())
    s.read = c.stencils->filled();
  else if (visits_all)
    s.fill = c.stencils->storage(P.size()).data();
  return s;
}

void finish_pass(const Setup& s, const TransferContext& c) {
  if (s.fill) c.stencils->mark_valid();
}

// sums[(node, group)] = (sum N_I V_p a_p, sum N_I V_p) over the counted particles of the group.
template <class Shape>
void node_average_scatter_impl(const Particles& P, const ParticleBins& bins, SparseGrid& grid, const Setup& s,
                               const NodeAverageSums& na) {
  const NodeAverage& a = na.average;
  zero_sums(grid, a.groups, *na.sums);
  double* sums = na.sums->data();
  const SumsSlot slot{grid.block(0), a.groups};
  for_each_block_coloured(bins, grid, [&](std::uint32_t b, GridNode* const* blocks, const std::array<int, 3>& origin) {
    NodeStencil<Shape> st;
    for (std::uint32_t k = bins.offset[b]; k < bins.offset[b + 1]; ++k) {
      const std::uint32_t p = bins.order[k];
      if (!a.counts(p)) {
        if (s.fill) s.stencil(st, P, p, origin);  // the cache holds every point's
        continue;
      }
      s.stencil(st, P, p, origin);
      const double V = P.volume[p], Va = V * a.value[p];
      st.for_each(blocks, s.inv_h, [&](GridNode& n, double w, const double*) {
        double* sum = &sums[slot(n, a.group[p])];
        sum[0] += w * Va;
        sum[1] += w * V;
      });
    }
  });
}

// out_p = sum_I N_I(x_p) (sum N V a / sum N V)_(I, group of p) for the binned counted particles.
template <class Shape>
void node_average_gather_impl(const Particles& P, const ParticleBins& bins, const SparseGrid& grid, const Setup& s,
                              const NodeAverageSums& na, std::vector<double>& out) {
  const NodeAverage& a = na.average;
  const double* sums = na.sums->data();
  const SumsSlot slot{grid.block(0), a.groups};
  out.resize(P.size());
  for_each_block(bins, grid, [&](std::uint32_t b, const GridNode* const* blocks, const std::array<int, 3>& origin) {
    NodeStencil<Shape> st;
    for (std::uint32_t k = bins.offset[b]; k < bins.offset[b + 1]; ++k) {
      const std::uint32_t p = bins.order[k];
      if (!a.counts(p)) {
        out[p] = 0.0;
        continue;
      }
      s.stencil(st, P, p, origin);
      out[p] = gather_average(st, blocks, s.inv_h, sums, slot, a.group[p]);
    }
  });
}

template <class Shape>
void outward_normals_impl(const Particles& P, const ParticleBins& bins, SparseGrid& grid, const Setup& s,
                          std::vector<double>& out, const std::vector<std::uint8_t>* owners) {
  const GridNode* base = grid.block(0);
  const auto values = static_cast<std::int64_t>(grid.block_count()) * SparseGrid::block_size * 3;
  out.resize(static_cast<std::size_t>(values));
  double* zero = out.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < values; ++i) zero[i] = 0.0;
  for_each_block_coloured(bins, grid, [&](std::uint32_t b, GridNode* const* blocks, const std::array<int, 3>& origin) {
    if (owners && !(*owners)[b]) return;
    NodeStencil<Shape> st;
    for (std::uint32_t k = bins.offset[b]; k < bins.offset[b + 1]; ++k) {
      const std::uint32_t p = bins.order[k];
      double a_cells[3];
      st.evaluate(&P.position[3 * p], s.g, s.inv_h, s.a(p, a_cells), origin);
      const double m = P.mass[p];
      st.for_each(blocks, s.inv_h, [&](GridNode& n, double, const double* g) {
        double* o = &out[3 * static_cast<std::size_t>(&n - base)];
        for (int d = 0; d < 3; ++d) o[d] += m * g[d];
      });
    }
  });
}

template <class Shape>
void scatter_dispatch(Scatter what, const Particles& P, const ParticleBins& bins, SparseGrid& grid,
                      const Setup& s) {
  switch (what) {
    case Scatter::mass_momentum_force:
      scatter<Shape, Scatter::mass_momentum_force>(P, bins, grid, s);
      break;
    case Scatter::mass_momentum:
      scatter<Shape, Scatter::mass_momentum>(P, bins, grid, s);
      break;
    case Scatter::force:
      scatter<Shape, Scatter::force>(P, bins, grid, s);
      break;
  }
}

}  // namespace

void particles_to_grid(Scatter what, const Particles& particles, const ParticleBins& bins,
                       SparseGrid& grid, const TransferContext& context) {
  const Setup s = make_setup(particles, grid, context, true);
  if (context.shape == ShapeFunction::linear)
    scatter_dispatch<LinearShape>(what, particles, bins, grid, s);
  else
    scatter_dispatch<GimpShape>(what, particles, bins, grid, s);
  finish_pass(s, context);
}

void node_average(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                  const TransferContext& context, const NodeAverage& average, std::vector<double>& sums,
                  std::vector<double>& out) {
  const NodeAverageSums na{average, &sums};
  node_average_scatter(particles, bins, grid, context, na);
  node_average_gather(particles, bins, grid, context, na, out);
}

void node_average_scatter(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                          const TransferContext& context, const NodeAverageSums& sums) {
  const Setup s = make_setup(particles, grid, context, true);
  if (context.shape == ShapeFunction::linear)
    node_average_scatter_impl<LinearShape>(particles, bins, grid, s, sums);
  else
    node_average_scatter_impl<GimpShape>(particles, bins, grid, s, sums);
  finish_pass(s, context);
}

void node_average_gather(const Particles& particles, const ParticleBins& bins, const SparseGrid& grid,
                         const TransferContext& context, const NodeAverageSums& sums, std::vector<double>& out) {
  const Setup s = make_setup(particles, grid, context, false);  // skips the points that do not count
  if (context.shape == ShapeFunction::linear)
    node_average_gather_impl<LinearShape>(particles, bins, grid, s, sums, out);
  else
    node_average_gather_impl<GimpShape>(particles, bins, grid, s, sums, out);
}

void outward_normals(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                     const TransferContext& context, std::vector<double>& out,
                     const std::vector<std::uint8_t>* owners) {
  const Setup s = make_setup(grid, context);
  if (context.shape == ShapeFunction::linear)
    outward_normals_impl<LinearShape>(particles, bins, grid, s, out, owners);
  else
    outward_normals_impl<GimpShape>(particles, bins, grid, s, out, owners);
}

void grid_to_particles(Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                       const TransferContext& context, bool remap) {
  const Setup s = make_setup(particles, grid, context, true);
  if (context.shape == ShapeFunction::linear)
    gather_velocity<LinearShape>(particles, bins, grid, s, context.flip, remap);
  else
    gather_velocity<GimpShape>(particles, bins, grid, s, context.flip, remap);
  finish_pass(s, context);
}

void velocity_gradient(Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                       const TransferContext& context, NodalVelocity which, const NodeAverageSums* dilatation,
                       std::vector<double>* trace) {
  const Setup s = make_setup(particles, grid, context, true);
  const bool linear = context.shape == ShapeFunction::linear;
  switch (which) {
    case NodalVelocity::start:
      if (linear)
        gather_gradient<LinearShape, NodalVelocity::start>(particles, bins, grid, s, dilatation, trace);
      else
        gather_gradient<GimpShape, NodalVelocity::start>(particles, bins, grid, s, dilatation, trace);
      break;
    case NodalVelocity::end:
      if (linear)
        gather_gradient<LinearShape, NodalVelocity::end>(particles, bins, grid, s, dilatation, trace);
      else
        gather_gradient<GimpShape, NodalVelocity::end>(particles, bins, grid, s, dilatation, trace);
      break;
    case NodalVelocity::remapped:
      if (linear)
        gather_gradient<LinearShape, NodalVelocity::remapped>(particles, bins, grid, s, dilatation, trace);
      else
        gather_gradient<GimpShape, NodalVelocity::remapped>(particles, bins, grid, s, dilatation, trace);
      break;
  }
  finish_pass(s, context);
}

}  // namespace hvi::mpm
