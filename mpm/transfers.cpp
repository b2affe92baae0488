#include "mpm/transfers.hpp"

#include <algorithm>
#include <cstdint>
#include <type_traits>

#include "mpm/group_sums.hpp"
#include "mpm/patch.hpp"
#include "mpm/transfer_kernels.hpp"
#include "mpm/types.hpp"

// Each pass runs owner block by owner block (particle_bins.hpp): it evaluates the stencils of the
// block's points (or reads them from a StencilCache), copies the nodal values it reads into the
// block's patch (patch.hpp), runs the per-point kernels (transfer_kernels.hpp) and adds what they
// scattered to its group's sums, which go to the nodes once the group's blocks are done
// (group_sums.hpp). A pass that scatters runs colour by colour, groups of one colour in parallel,
// so each node receives its groups' sums in the same order for any thread count.

namespace hvi::mpm {
namespace {

// ---------------------------------------------------------------------------------------------
// Stencils

// Particle p's stencil from its position and (GIMP) half-widths a in cells (nullptr: linear).
template <class Shape>
void evaluate(PatchStencil<Shape::width>& st, const double* x, const GridGeometry& g, double inv_h,
              const double* a, const std::array<int, 3>& origin) {
  constexpr int W = Shape::width;
  double s[3];
  int base[3];
  for (int d = 0; d < 3; ++d) {
    s[d] = (x[d] - g.origin[d]) * inv_h;
    base[d] = Shape::lowest(s[d], a ? a[d] : 0.0);
    st.lowest[d] = base[d] - origin[d];
  }
  if constexpr (W == 3) {
    Shape::weights_from_lowest(s, a, base, st.N, st.dN);
  } else {
    for (int d = 0; d < 3; ++d) Shape::weights(s[d], base[d], 0.0, st.N[d], st.dN[d]);
  }
  // Rows of zero weight add nothing to any sum, so skipping them leaves results unchanged.
  st.y0 = st.z0 = 0;
  st.y1 = st.z1 = W - 1;
  if constexpr (W > 2) {
    while (st.N[1][st.y0] == 0.0 && st.dN[1][st.y0] == 0.0) ++st.y0;
    while (st.N[1][st.y1] == 0.0 && st.dN[1][st.y1] == 0.0) --st.y1;
    while (st.N[2][st.z0] == 0.0 && st.dN[2][st.z0] == 0.0) ++st.z0;
    while (st.N[2][st.z1] == 0.0 && st.dN[2][st.z1] == 0.0) --st.z1;
  }
}

void store(const PatchStencil<3>& st, GimpStencil& c) {
  for (int d = 0; d < 3; ++d)
    for (int k = 0; k < 3; ++k) {
      c.N[d][k] = st.N[d][k];
      c.dN[d][k] = st.dN[d][k];
    }
  for (int d = 0; d < 3; ++d) c.lowest[d] = static_cast<std::int8_t>(st.lowest[d]);
  c.first[0] = static_cast<std::int8_t>(st.y0);
  c.last[0] = static_cast<std::int8_t>(st.y1);
  c.first[1] = static_cast<std::int8_t>(st.z0);
  c.last[1] = static_cast<std::int8_t>(st.z1);
}

void load(const GimpStencil& c, PatchStencil<3>& st) {
  for (int d = 0; d < 3; ++d) {
    for (int k = 0; k < 3; ++k) {
      st.N[d][k] = c.N[d][k];
      st.dN[d][k] = c.dN[d][k];
    }
    st.N[d][3] = st.dN[d][3] = 0.0;
  }
  for (int d = 0; d < 3; ++d) st.lowest[d] = c.lowest[d];
  st.y0 = c.first[0];
  st.y1 = c.last[0];
  st.z0 = c.first[1];
  st.z1 = c.last[1];
}

struct Setup {
  const GridGeometry* g;
  double inv_h;
  const double* half_width;  // 3 per particle, m
  // GIMP with a StencilCache: read the step's stencils from `read`, or evaluate them and, in a
  // pass that visits every binned point, store them in `fill`. Both nullptr: evaluate.
  const GimpStencil* read;
  GimpStencil* fill;

  template <class Shape>
  void stencil(PatchStencil<Shape::width>& st, const Particles& P, std::uint32_t p,
               const std::array<int, 3>& origin) const {
    if constexpr (std::is_same_v<Shape, GimpShape>)
      if (read) {
        load(read[p], st);
        return;
      }
    double a[3];
    if (half_width)
      for (int d = 0; d < 3; ++d) a[d] = half_width[3 * p + d] * inv_h;
    evaluate<Shape>(st, &P.position[3 * p], *g, inv_h, half_width ? a : nullptr, origin);
    if constexpr (std::is_same_v<Shape, GimpShape>)
      if (fill) store(st, fill[p]);
  }
};

// ---------------------------------------------------------------------------------------------
// Passes

enum class Pass { scatter, velocity, gradient, average_scatter, average_gather, normals };

// Everything a pass reads and writes; the fields a pass does not use stay at their defaults.
struct PassArgs {
  Pass pass;
  Particles* P;
  const ParticleBins* bins;
  SparseGrid* grid;
  Setup s;
  Scatter what = Scatter::mass_momentum_force;
  const NodeAverageSums* average = nullptr;  // scatter: mean stress; gradient: dilatation; averages
  bool remap = false;
  double flip = 1.0;
  NodalVelocity which = NodalVelocity::start;
  double* out = nullptr;  // average_gather: abar_p; normals: g_I; gradient: tr L_p
  const std::vector<std::uint8_t>* owners = nullptr;
  SharedBlocks* shared = nullptr;  // a pass that adds, in a run spread over ranks
};

// Per thread: the stencils of the block in hand and the patch's components.
struct Scratch {
  std::vector<PatchStencil<2>> linear;
  std::vector<PatchStencil<3>> gimp;
  std::vector<double> values;
  std::vector<double*> pointers;
  GroupSums sums;  // of the group in hand, in a pass that adds
  template <int W>
  std::vector<PatchStencil<W>>& stencils() {
    if constexpr (W == 2)
      return linear;
    else
      return gimp;
  }
  double* const* components(int count) {
    values.resize(static_cast<std::size_t>(count) * patch::size);
    pointers.resize(static_cast<std::size_t>(count));
    for (int k = 0; k < count; ++k)
      pointers[k] = values.data() + static_cast<std::size_t>(k) * patch::size;
    return pointers.data();
  }
};

// A node average's sums, as the grid's values block by block (structure of arrays): array k
// (0: value, 1: weight) of group g of block b, 64 nodes.
inline std::size_t sums_at(std::uint32_t b, int groups, std::int64_t g, int k) {
  return ((static_cast<std::size_t>(b) * static_cast<std::size_t>(groups) +
           static_cast<std::size_t>(g)) *
              2 +
          static_cast<std::size_t>(k)) *
         SparseGrid::block_size;
}

// Four nodes' values at once.
using d4 = simd::d4;
inline d4 row(const double* p) {
  return simd::load<4>(p);
}
inline void set_row(double* p, d4 v) {
  simd::store<4>(p, v);
}
inline void add_row(double* p, d4 v) {
  simd::store<4>(p, simd::load<4>(p) + v);
}

template <class Shape>
class BlockPass {
 public:
  static constexpr int W = Shape::width;

  BlockPass(const PassArgs& a, std::uint32_t b, Scratch& scratch)
      : a_(a),
        P_(*a.P),
        nb_(a.bins->neighbours[b]),
        order_(a.bins->order.data() + a.bins->offset[b]),
        count_(a.bins->offset[b + 1] - a.bins->offset[b]),
        st_(scratch.stencils<W>()),
        scratch_(scratch),
        grid_(*a.grid),
        inv_h_(a.s.inv_h) {
    const auto c = SparseGrid::block_coords(a.grid->key(b));
    reach_ = (c[0] & 1) + 3 * (c[1] & 1) + 9 * (c[2] & 1);  // the owner's place in its group
    const auto origin = a.grid->block_origin(b);
    st_.resize(count_);
    for (std::uint32_t k = 0; k < count_; ++k) {
      a.s.template stencil<Shape>(st_[k], P_, order_[k], origin);
      region_.add(st_[k]);
    }
    region_.finish();
  }

  void run() {
    switch (a_.pass) {
      case Pass::scatter:
        if (a_.what == Scatter::mass_momentum) return scatter<true, true, false>();
        if (a_.what == Scatter::force)
          return a_.average ? scatter<false, false, true, true>() : scatter<false, false, true>();
        return a_.average ? scatter<true, true, true, true>() : scatter<true, true, true>();
      case Pass::velocity:
        return a_.remap ? velocity<true>() : velocity<false>();
      case Pass::gradient:
        switch (a_.which) {
          case NodalVelocity::start:
            return a_.average ? gradient<NodalVelocity::start, true>()
                              : gradient<NodalVelocity::start, false>();
          case NodalVelocity::end:
            return a_.average ? gradient<NodalVelocity::end, true>()
                              : gradient<NodalVelocity::end, false>();
          case NodalVelocity::remapped:
            return a_.average ? gradient<NodalVelocity::remapped, true>()
                              : gradient<NodalVelocity::remapped, false>();
          case NodalVelocity::mid:
            return a_.average ? gradient<NodalVelocity::mid, true>()
                              : gradient<NodalVelocity::mid, false>();
        }
        return;
      case Pass::average_scatter:
        return average_scatter();
      case Pass::average_gather:
        return average_gather();
      case Pass::normals:
        return normals();
    }
  }

 private:
  // f(block, local node, patch index) for each row of four nodes of the region.
  template <class F>
  void each_row(F&& f) const {
    for_each_patch_row(nb_, region_, f);
  }

  // f(r, local index, patch index) for each row of four nodes of the region, in a pass that adds:
  // r is the row's block among the group's reach blocks, whose sums (acc(r, c)) run_pass adds to
  // the nodes once the group is done.
  template <class F>
  void each_added_row(F&& f) const {
    GroupSums& sums = scratch_.sums;
    int r = 0;
    for_each_patch_row(
        nb_, region_,
        [&](std::uint32_t, int l, int i) {
          sums.open_row(r, l);
          f(r, l, i);
        },
        [&](int o, std::uint32_t b) {
          r = reach_ + (o & 1) + 3 * ((o >> 1) & 1) + 9 * (o >> 2);
          sums.touch(r, b);
        });
  }
  double* acc(int r, int c) const { return scratch_.sums.at(r, c); }

  // The node average's values abar_I of every group into components c[0 .. groups).
  void load_averages(double* const* c) const {
    const NodeAverageSums& na = *a_.average;
    const double* sums = na.sums->data();
    const int groups = na.average.groups;
    each_row([&](std::uint32_t b, int l, int i) {
      for (int g = 0; g < groups; ++g) set_row(c[g] + i, row(sums + sums_at(b, groups, g, 0) + l));
    });
  }
  // Adds the (value, weight) pairs of every group in c[0 .. 2 groups) to the node average's sums
  // (component 2 g + k, added_target).
  void add_sums(double* const* c) const {
    const int components = 2 * a_.average->average.groups;
    each_added_row([&](int r, int l, int i) {
      for (int k = 0; k < components; ++k) add_row(acc(r, k) + l, row(c[k] + i));
    });
  }

  // m_I, p_I and f_I; with Mean, each counted point's stress carries V_p (mbar_p - m_p) 1 of the
  // mean stress's node average.
  template <bool Mass, bool Momentum, bool Force, bool Mean = false>
  void scatter() {
    namespace sp = kernels::scatter_patch;
    const int groups = Mean ? a_.average->average.groups : 0;
    double* const* c = scratch_.components(sp::count + groups);
    zero_patch(c, sp::count, region_);
    if constexpr (Mean) load_averages(c + sp::count);
    for (std::uint32_t k = 0; k < count_; ++k) {
      const std::uint32_t p = order_[k];
      double vs[6] = {};  // V_p sigma_p
      if constexpr (Force) {
        const double V = P_.volume[p];
        for (int i = 0; i < 6; ++i) vs[i] = V * P_.stress[6 * p + i];
        if constexpr (Mean) {
          const NodeAverage& av = a_.average->average;
          const double shift =
              av.counts(p)
                  ? kernels::gather_scalar(st_[k], inv_h_, c[sp::count + av.group[p]]) - av.value[p]
                  : 0.0;
          for (const int i : {sym::xx, sym::yy, sym::zz}) vs[i] += V * shift;
        }
      }
      kernels::scatter_point<W, Mass, Momentum, Force>(st_[k], inv_h_, P_.mass[p],
                                                       &P_.velocity[3 * p], vs, c);
    }
    // Components as added_target numbers them: m, p, f, leaving out those not scattered.
    constexpr int momentum = Mass ? 1 : 0, force = momentum + (Momentum ? 3 : 0);
    each_added_row([&](int r, int l, int i) {
      if constexpr (Mass) add_row(acc(r, 0) + l, row(c[sp::mass] + i));
      for (int d = 0; d < 3; ++d) {
        if constexpr (Momentum) add_row(acc(r, momentum + d) + l, row(c[sp::momentum + d] + i));
        if constexpr (Force) add_row(acc(r, force + d) + l, row(c[sp::force + d] + i));
      }
    });
  }

  // v_p <- flip (v_p + sum N dv_I) + (1 - flip) sum N (v_I + dv_I); with Remap, q_I += N m_p v_p.
  template <bool Remap>
  void velocity() {
    namespace vp = kernels::velocity_patch;
    double* const* c = scratch_.components(vp::count + (Remap ? 3 : 0));
    each_row([&](std::uint32_t b, int l, int i) {
      for (int d = 0; d < 3; ++d) {
        const d4 f = row(grid_.values(b, node_value::f + d) + l);
        set_row(c[vp::increment + d] + i, f);
        set_row(c[vp::end + d] + i, row(grid_.values(b, node_value::p + d) + l) + f);
      }
    });
    if constexpr (Remap) zero_patch(c + vp::count, 3, region_);
    const double flip = a_.flip;
    for (std::uint32_t k = 0; k < count_; ++k) {
      const std::uint32_t p = order_[k];
      double dv[3], vg[3];
      kernels::gather_velocity_point(st_[k], inv_h_, c, dv, vg);
      double* v = &P_.velocity[3 * p];
      for (int d = 0; d < 3; ++d) {
        v[d] = flip * (v[d] + dv[d]) + (1.0 - flip) * vg[d];
        P_.grid_velocity[3 * p + d] = vg[d];
      }
      if constexpr (Remap) {
        const double m = P_.mass[p];
        const double mv[3] = {m * v[0], m * v[1], m * v[2]};
        kernels::scatter_vector(st_[k], inv_h_, mv, c + vp::count);
      }
    }
    if constexpr (Remap)
      each_added_row([&](int r, int l, int i) {
        for (int d = 0; d < 3; ++d) add_row(acc(r, d) + l, row(c[vp::count + d] + i));
      });
  }

  // L_p = sum v_I (x) grad N_I; with Average also tr L_p into out and (V tr L, V) into the sums.
  template <NodalVelocity Which, bool Average>
  void gradient() {
    const int groups = Average ? a_.average->average.groups : 0;
    double* const* c = scratch_.components(3 + 2 * groups);
    each_row([&](std::uint32_t b, int l, int i) {
      for (int d = 0; d < 3; ++d) {
        const double* p = grid_.values(b, node_value::p + d) + l;
        if constexpr (Which == NodalVelocity::start) set_row(c[d] + i, row(p));
        if constexpr (Which == NodalVelocity::end)
          set_row(c[d] + i, row(p) + row(grid_.values(b, node_value::f + d) + l));
        if constexpr (Which == NodalVelocity::remapped)
          set_row(c[d] + i, row(grid_.values(b, node_value::q + d) + l));
        if constexpr (Which == NodalVelocity::mid)
          set_row(c[d] + i, row(p) + 0.5 * row(grid_.values(b, node_value::f + d) + l));
      }
    });
    if constexpr (Average) zero_patch(c + 3, 2 * groups, region_);
    for (std::uint32_t k = 0; k < count_; ++k) {
      const std::uint32_t p = order_[k];
      double* L = &P_.velocity_gradient[9 * p];
      kernels::gather_gradient_point(st_[k], inv_h_, c, L);
      if constexpr (Average) {
        const NodeAverage& av = a_.average->average;
        a_.out[p] = L[0] + L[4] + L[8];
        if (!av.counts(p)) continue;
        const double V = P_.volume[p];
        const auto g = av.group[p];
        kernels::scatter_pair(st_[k], inv_h_, V * a_.out[p], V, c[3 + 2 * g], c[4 + 2 * g]);
      }
    }
    if constexpr (Average) add_sums(c + 3);
  }

  // (V_p a_p, V_p) of the counted points into the sums.
  void average_scatter() {
    const NodeAverage& av = a_.average->average;
    double* const* c = scratch_.components(2 * av.groups);
    zero_patch(c, 2 * av.groups, region_);
    for (std::uint32_t k = 0; k < count_; ++k) {
      const std::uint32_t p = order_[k];
      if (!av.counts(p)) continue;
      const double V = P_.volume[p];
      const auto g = av.group[p];
      kernels::scatter_pair(st_[k], inv_h_, V * av.value[p], V, c[2 * g], c[2 * g + 1]);
    }
    add_sums(c);
  }

  // abar_p of the counted points (0 for the others).
  void average_gather() {
    const NodeAverage& av = a_.average->average;
    double* const* c = scratch_.components(av.groups);
    load_averages(c);
    for (std::uint32_t k = 0; k < count_; ++k) {
      const std::uint32_t p = order_[k];
      a_.out[p] = av.counts(p) ? kernels::gather_scalar(st_[k], inv_h_, c[av.group[p]]) : 0.0;
    }
  }

  // g_I += m_p grad N_I into out (3 per node, in node storage order).
  void normals() {
    double* const* c = scratch_.components(3);
    zero_patch(c, 3, region_);
    for (std::uint32_t k = 0; k < count_; ++k)
      kernels::scatter_mass_gradient(st_[k], inv_h_, P_.mass[order_[k]], c);
    each_added_row([&](int r, int l, int i) {
      for (int d = 0; d < 3; ++d) add_row(acc(r, d) + l, row(c[d] + i));
    });
  }

  const PassArgs& a_;
  Particles& P_;
  const std::array<std::uint32_t, 8>& nb_;
  const std::uint32_t* order_;
  std::uint32_t count_;
  std::vector<PatchStencil<W>>& st_;
  Scratch& scratch_;
  SparseGrid& grid_;
  double inv_h_;
  PatchRegion region_;
  int reach_ = 0;
};

// One owner block of a pass, built for the processor at hand (simd.hpp).
HVI_SIMD_KERNEL void run_block_linear(const PassArgs& a, std::uint32_t b, Scratch& scratch) {
  BlockPass<LinearShape>(a, b, scratch).run();
}
HVI_SIMD_KERNEL void run_block_gimp(const PassArgs& a, std::uint32_t b, Scratch& scratch) {
  BlockPass<GimpShape>(a, b, scratch).run();
}

// The arrays of 64 nodes per block a pass that adds adds to, and where component c of block b
// goes: the grid's values (m, p, f as scattered; q), the node average's (value, weight) of each
// group, the outward normals.
int added_components(const PassArgs& a) {
  switch (a.pass) {
    case Pass::scatter:
      return a.what == Scatter::mass_momentum ? 4 : a.what == Scatter::force ? 3 : 7;
    case Pass::velocity:
    case Pass::normals:
      return 3;
    case Pass::gradient:
    case Pass::average_scatter:
      return 2 * a.average->average.groups;
    case Pass::average_gather:
      return 0;
  }
  return 0;
}
double* added_target(const PassArgs& a, std::uint32_t b, int c) {
  switch (a.pass) {
    case Pass::scatter:
      return a.grid->values(b, (a.what == Scatter::force ? node_value::f : node_value::mass) + c);
    case Pass::velocity:
      return a.grid->values(b, node_value::q + c);
    case Pass::gradient:
    case Pass::average_scatter:
      return a.average->sums->data() + sums_at(b, a.average->average.groups, c / 2, c % 2);
    case Pass::normals:
      return a.out + (3 * static_cast<std::size_t>(b) + static_cast<std::size_t>(c)) *
                         SparseGrid::block_size;
    case Pass::average_gather:
      break;
  }
  return nullptr;
}

// Every owner block (with `owners`, those marked), group by group in parallel, a group's blocks
// in order; `coloured` (a pass that adds): colour by colour, each group's sums added to the nodes
// once its blocks are done (group_sums.hpp, particle_bins.hpp), or, for a block shared with
// other ranks, kept apart by colour (shared_blocks.hpp).
void run_pass(const PassArgs& a, ShapeFunction shape, bool coloured) {
  const auto block = shape == ShapeFunction::linear ? run_block_linear : run_block_gimp;
  const ParticleBins& bins = *a.bins;
  const auto* owners = a.owners;
  const auto group = [&](std::uint32_t g, Scratch& scratch, int colour) {
    if (coloured) scratch.sums.begin(added_components(a));
    for (std::uint32_t k = bins.group_offset[g]; k < bins.group_offset[g + 1]; ++k) {
      const std::uint32_t b = bins.group_owner[k];
      if (!owners || (*owners)[b]) block(a, b, scratch);
    }
    if (coloured)
      scratch.sums.flush([&](std::uint32_t b, int c) {
        if (a.shared)
          if (double* kept = a.shared->capture(b, colour, c)) return kept;
        return added_target(a, b, c);
      });
  };
  const bool sharing = coloured && a.shared;
  if (sharing) a.shared->start(added_components(a));
#pragma omp parallel
  {
    static thread_local Scratch scratch;  // kept from pass to pass: no allocation in the step
    if (coloured) {
      for (int k = 0; k < SharedBlocks::colours; ++k) {
        const auto& colour = bins.colour[static_cast<std::size_t>(k)];
        const auto count = static_cast<std::int64_t>(colour.size());
#pragma omp for schedule(dynamic, 1)
        for (std::int64_t i = 0; i < count; ++i) group(colour[i], scratch, k);
      }
    } else {
      const auto count = static_cast<std::int64_t>(bins.group_offset.size()) - 1;
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t i = 0; i < count; ++i) group(static_cast<std::uint32_t>(i), scratch, -1);
    }
  }
  if (sharing)
    a.shared->combine(added_components(a),
                      [&](std::uint32_t b, int c) { return added_target(a, b, c); });
}

// Zeroed sums for every block of the grid, 64 nodes x groups x 2 values per block.
void zero_sums(const SparseGrid& grid, int groups, std::vector<double>& sums) {
  const auto block_values = static_cast<std::int64_t>(SparseGrid::block_size) * groups * 2;
  const auto blocks = static_cast<std::int64_t>(grid.block_count());
  sums.resize(static_cast<std::size_t>(blocks * block_values));
  double* zero = sums.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < blocks; ++b) std::fill_n(zero + b * block_values, block_values, 0.0);
}

// Sums (sum N V a, sum N V) to (abar_I, sum N V): the node values the gathers interpolate.
void finish_averages(std::vector<double>& sums) {
  constexpr int S = SparseGrid::block_size;
  const auto arrays =
      static_cast<std::int64_t>(sums.size() / (2 * S));  // (value, weight) of a block and group
  double* data = sums.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < arrays; ++i) {
    double* value = data + i * 2 * S;
    const double* weight = value + S;
    for (int l = 0; l < S; ++l) value[l] = weight[l] > 0.0 ? value[l] / weight[l] : 0.0;
  }
}

// Without a cache (and for outward_normals, which runs on either field of a contact pair).
Setup make_setup(const SparseGrid& grid, const TransferContext& c) {
  return {&grid.geometry(), 1.0 / grid.geometry().cell_size,
          c.half_width ? c.half_width->data() : nullptr, nullptr, nullptr};
}

// With GIMP and a StencilCache: read it if it is filled; else, if this pass visits every binned
// point (`visits_all`), fill it as the pass evaluates (finish_pass then marks it filled).
Setup make_setup(const Particles& P, const SparseGrid& grid, const TransferContext& c,
                 bool visits_all) {
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

PassArgs pass_args(Pass pass, const Particles& P, const ParticleBins& bins, SparseGrid& grid,
                   const Setup& s) {
  // The passes that only read particles take them as const: the cast is not written through.
  return PassArgs{pass, const_cast<Particles*>(&P), &bins, &grid, s};
}

}  // namespace

void particles_to_grid(Scatter what, const Particles& particles, const ParticleBins& bins,
                       SparseGrid& grid, const TransferContext& context) {
  const Setup s = make_setup(particles, grid, context, true);
  PassArgs a = pass_args(Pass::scatter, particles, bins, grid, s);
  a.what = what;
  a.shared = context.shared;
  if (what != Scatter::mass_momentum) a.average = context.mean_stress;
  run_pass(a, context.shape, true);
  finish_pass(s, context);
}

void node_average(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                  const TransferContext& context, const NodeAverage& average,
                  std::vector<double>& sums, std::vector<double>& out) {
  const NodeAverageSums na{average, &sums};
  node_average_scatter(particles, bins, grid, context, na);
  node_average_gather(particles, bins, grid, context, na, out);
}

void node_average_scatter(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                          const TransferContext& context, const NodeAverageSums& sums) {
  const Setup s = make_setup(particles, grid, context, true);
  zero_sums(grid, sums.average.groups, *sums.sums);
  PassArgs a = pass_args(Pass::average_scatter, particles, bins, grid, s);
  a.average = &sums;
  a.shared = context.shared;
  run_pass(a, context.shape, true);
  finish_averages(*sums.sums);
  finish_pass(s, context);
}

void node_average_gather(const Particles& particles, const ParticleBins& bins,
                         const SparseGrid& grid, const TransferContext& context,
                         const NodeAverageSums& sums, std::vector<double>& out) {
  const Setup s = make_setup(particles, grid, context, false);
  out.resize(particles.size());
  PassArgs a = pass_args(Pass::average_gather, particles, bins, const_cast<SparseGrid&>(grid), s);
  a.average = &sums;
  a.out = out.data();
  run_pass(a, context.shape, false);
}

void outward_normals(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                     const TransferContext& context, std::vector<double>& out,
                     const std::vector<std::uint8_t>* owners) {
  const Setup s = make_setup(grid, context);
  const auto values = static_cast<std::int64_t>(grid.block_count()) * SparseGrid::block_size * 3;
  out.resize(static_cast<std::size_t>(values));
  double* zero = out.data();
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < values; ++i) zero[i] = 0.0;
  PassArgs a = pass_args(Pass::normals, particles, bins, grid, s);
  a.out = out.data();
  a.owners = owners;
  a.shared = context.shared;
  run_pass(a, context.shape, true);
}

void grid_to_particles(Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                       const TransferContext& context, bool remap) {
  const Setup s = make_setup(particles, grid, context, true);
  PassArgs a = pass_args(Pass::velocity, particles, bins, grid, s);
  a.remap = remap;
  a.flip = context.flip;
  if (remap) a.shared = context.shared;
  run_pass(a, context.shape, remap);
  finish_pass(s, context);
}

void velocity_gradient(Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                       const TransferContext& context, NodalVelocity which,
                       const NodeAverageSums* dilatation, std::vector<double>* trace) {
  const Setup s = make_setup(particles, grid, context, true);
  PassArgs a = pass_args(Pass::gradient, particles, bins, grid, s);
  a.which = which;
  a.average = dilatation;
  if (dilatation) {
    zero_sums(grid, dilatation->average.groups, *dilatation->sums);
    a.out = trace->data();
    a.shared = context.shared;
  }
  run_pass(a, context.shape, dilatation != nullptr);
  if (dilatation) finish_averages(*dilatation->sums);
  finish_pass(s, context);
}

}  // namespace hvi::mpm
