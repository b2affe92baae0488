#pragma once
// Particle <-> grid transfers, the kernels of every MPM step. A point's weights follow from its
// start-of-step position (and GIMP half-widths); with a StencilCache, GIMP weights are evaluated
// once and read by every later pass until the cache is invalidated, else each pass recomputes
// them. Scatters run colour by colour over owner blocks (see particle_bins.hpp); gathers run over
// owner blocks in any order.
#include <cstdint>
#include <vector>

#include "mpm/grid.hpp"
#include "mpm/particle_bins.hpp"
#include "mpm/particles.hpp"
#include "mpm/shape_functions.hpp"
#include "mpm/shared_blocks.hpp"

namespace hvi::mpm {

// A particle scalar a_p averaged through the grid nodes, group by group:
//   a_I = sum_p N_I(x_p) V_p a_p / sum_p N_I(x_p) V_p   over the counted particles of one group,
//   abar_p = sum_I N_I(x_p) a_I                         with the nodal values of p's group.
// Particles with skip[p] > 0 neither count nor get a value (abar_p = 0).
struct NodeAverage {
  const double* value = nullptr;        // a_p
  const std::int64_t* group = nullptr;  // per particle, in [0, groups)
  int groups = 1;
  const double* skip = nullptr;
  bool counts(std::size_t p) const { return !(skip && skip[p] > 0.0); }
};

// A node average's node values, kept between the pass that scatters them and the ones that gather
// abar_p (in another transfer, which saves that transfer's particles a second pass:
// TransferContext::mean_stress, velocity_gradient). Per block and group, two arrays of the block's
// 64 nodes: once scattered, (sum N_I V_p a_p / sum N_I V_p, sum N_I V_p), the first 0 where the
// second is.
struct NodeAverageSums {
  NodeAverage average;
  std::vector<double>* sums = nullptr;
};

// One point's GIMP stencil as a StencilCache keeps it: the weights N and derivatives dN (in cell
// units) of its 3 nodes per axis, its lowest node per axis relative to its owner block's first
// node, and along y and z the first and last node of nonzero weight.
struct GimpStencil {
  double N[3][3], dN[3][3];
  std::int8_t lowest[3];  // 0 .. 3
  std::int8_t first[2], last[2];
};
static_assert(sizeof(GimpStencil) == 152);  // 18 doubles and 7 bytes, padded to a double

// The GIMP stencils of every point, kept between the passes of one step (grid.stencil_cache,
// off by default). A step's passes see the same positions, half-widths and bins from the binning
// to the domains' stretch, so without the cache each pass evaluates the weights again: with MUSL
// and the node average, 5 times a step. Stored, they cost sizeof(GimpStencil) = 152 bytes a point,
// and streaming them costs more than evaluating them (docs/verification/benchmarks.md). The solver
// invalidates the cache whenever the points are binned again or their domains stretch; the first
// transfer after that which visits every binned point fills it as it evaluates, and the ones after
// read it. The values are the ones each pass would compute, so results are the same to the bit
// (tests/mpm/test_transfers.cpp, tests/driver/test_cli.cpp).
class StencilCache {
 public:
  void invalidate() { valid_ = false; }
  bool valid() const { return valid_; }
  std::size_t bytes() const { return stencils_.capacity() * sizeof(GimpStencil); }
  // For the transfers: the stencils, resized to n, and the mark that they are filled.
  std::vector<GimpStencil>& storage(std::size_t n) {
    // To exactly n, as Particles::resize: a hybrid's growing zone adds points a tenth at a time,
    // and a vector grown past its capacity would double it.
    if (n > stencils_.capacity()) stencils_.reserve(n);
    if (stencils_.size() != n) stencils_.resize(n);
    return stencils_;
  }
  const GimpStencil* filled() const { return valid_ ? stencils_.data() : nullptr; }
  void mark_valid() { valid_ = true; }

 private:
  std::vector<GimpStencil> stencils_;
  bool valid_ = false;
};

struct TransferContext {
  ShapeFunction shape = ShapeFunction::linear;
  const std::vector<double>* half_width = nullptr;  // GIMP particle half-widths, 3 per particle, m
  double flip = 1.0;  // FLIP fraction of the particle velocity update (1 FLIP, 0 PIC)
  double dt = 0.0;
  // With a force scatter: the node average of the mean stress (volumetric_average.hpp), whose
  // mbar_p - m_p the same pass gathers and adds to the diagonal of each counted particle's
  // stress in the internal force; nullptr for none.
  const NodeAverageSums* mean_stress = nullptr;
  // GIMP stencils kept between passes; nullptr: every pass evaluates its own. Only for a single
  // velocity field (the cache holds one stencil per point, on one grid's bins).
  StencilCache* stencils = nullptr;
  // A run spread over ranks: the blocks this rank shares with others, whose sums the passes that
  // add to the nodes (the scatter, the MUSL remap, the node average's sums) keep apart per colour
  // and combine with the other ranks' when the pass ends (shared_blocks.hpp).
  SharedBlocks* shared = nullptr;
};

enum class Scatter {
  mass_momentum_force,  // m_I = sum N m_p; p_I = sum N m_p v_p; f_I = -sum V_p sigma_p grad N
  mass_momentum,
  force,
};

void particles_to_grid(Scatter what, const Particles& particles, const ParticleBins& bins,
                       SparseGrid& grid, const TransferContext& context);

// Particle velocity from the nodal velocity v_I and increment dv_I (after update_grid):
//   v_p <- flip (v_p + sum N dv_I) + (1 - flip) sum N (v_I + dv_I),
// and grid_velocity_p = sum N (v_I + dv_I), the velocity the particle moves with.
// With `remap` (MUSL), the same pass scatters the updated momentum: q_I = sum N m_p v_p.
void grid_to_particles(Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                       const TransferContext& context, bool remap);

// Fills out (one value per particle); sums is scratch storage kept between calls. The same as
// node_average_scatter, then node_average_gather.
void node_average(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                  const TransferContext& context, const NodeAverage& average,
                  std::vector<double>& sums, std::vector<double>& out);
void node_average_scatter(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                          const TransferContext& context, const NodeAverageSums& sums);
// abar_p into out[p] for the binned particles (0 for those that do not count).
void node_average_gather(const Particles& particles, const ParticleBins& bins,
                         const SparseGrid& grid, const TransferContext& context,
                         const NodeAverageSums& sums, std::vector<double>& out);

// g_I = sum_p m_p grad N_I(x_p), about -int N_I grad rho, the outward normal of the particles'
// material at node I (contact.hpp): component d of node l of block b at out[(3 b + d) 64 + l].
// With `owners`, only the particles of owner blocks b with owners[b] != 0 scatter (the others'
// nodes are left at zero).
void outward_normals(const Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                     const TransferContext& context, std::vector<double>& out,
                     const std::vector<std::uint8_t>* owners = nullptr);

// Which nodal velocity the velocity gradient is taken from.
enum class NodalVelocity {
  start,     // p: v_I at the start of the step (USF)
  end,       // p + f: v_I + dv_I (USL)
  remapped,  // q: velocity remapped from the updated particle velocities (MUSL)
  mid,       // p + f / 2: the mid-step velocity the internal force's work is taken at
             // (energy_ledger.hpp)
};

// L_p = sum_I v_I (x) grad N_I(x_p), at the start-of-step positions. With `dilatation`, the same
// pass (then colour by colour) stores tr L_p in `trace`, the values of dilatation->average, and
// fills dilatation's sums from them, as node_average_scatter would.
void velocity_gradient(Particles& particles, const ParticleBins& bins, SparseGrid& grid,
                       const TransferContext& context, NodalVelocity which,
                       const NodeAverageSums* dilatation = nullptr,
                       std::vector<double>* trace = nullptr);

}  // namespace hvi::mpm
