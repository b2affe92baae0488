#pragma once
// A block's neighbourhood as a dense patch, and one point's stencil inside it: the layout the
// transfer kernels (transfers.cpp) work in.
//
// The points of an owner block have their lowest stencil node in that block, so every node they
// reach lies in the 2 x 2 x 2 blocks from it (particle_bins.hpp), at patch coordinates 0..7 along
// x and 0..5 along y and z from the owner block's first node. A pass copies the nodal values it
// reads into the patch, one array per component (structure of arrays), and scatters into a zeroed
// patch that it adds to the nodes once the block's points are done. Inside the patch a point's
// nodes along x are consecutive, so its stencil is W x W rows of L lanes (L = 4 for GIMP's three
// nodes, the fourth weighing zero; L = 2 for linear), and a row is one short vector operation.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>

#include "mpm/grid.hpp"

namespace hvi::mpm {

namespace patch {
constexpr int nx = 8, ny = 6, nz = 6, size = nx * ny * nz;
constexpr int row = nx, layer = nx * ny;
inline int index(int x, int y, int z) {
  return x + nx * (y + ny * z);
}
}  // namespace patch

// One point's stencil in its owner block's patch: per axis the weights N and derivatives dN (in
// cell units) of its W nodes from the lowest one, in L lanes (those past W zero).
template <int W>
struct PatchStencil {
  static constexpr int L = W == 2 ? 2 : 4;
  double N[3][L], dN[3][L];
  std::array<int, 3> lowest;  // patch coordinates of the lowest node, 0..3 per axis
  int y0, y1, z0, z1;         // the rows of nonzero weight along y and z (inclusive)
  int base() const { return patch::index(lowest[0], lowest[1], lowest[2]); }
};

// The patch region [lo, hi) that a block's points reach; along x in whole rows of a block (4
// nodes), which the grid's values are copied in.
struct PatchRegion {
  int lo[3] = {patch::nx, patch::ny, patch::nz}, hi[3] = {0, 0, 0};
  template <int W>
  void add(const PatchStencil<W>& s) {
    constexpr int reach[3] = {PatchStencil<W>::L, W, W};
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], s.lowest[d]);
      hi[d] = std::max(hi[d], s.lowest[d] + reach[d]);
    }
  }
  // After the last add(): x widened to block rows.
  void finish() {
    constexpr int E = SparseGrid::block_edge;
    lo[0] = lo[0] / E * E;
    hi[0] = (hi[0] + E - 1) / E * E;
  }
  bool empty() const { return lo[0] >= hi[0]; }
};

// f(block, local index of the row's first node, patch index of its first node) for every row of 4
// nodes of `region` (finished), block by block, after on_block(o, block) for each block it
// reaches; `blocks` are the owner block's eight neighbours (ParticleBins::neighbours), block o at
// the owner's coordinates + (o & 1, (o >> 1) & 1, o >> 2).
template <class F, class G>
void for_each_patch_row(const std::array<std::uint32_t, 8>& blocks, const PatchRegion& region,
                        F&& f, G&& on_block) {
  constexpr int E = SparseGrid::block_edge;
  for (int oz = 0; oz < 2; ++oz) {
    const int z0 = std::max(region.lo[2], E * oz), z1 = std::min(region.hi[2], E * oz + E);
    for (int oy = 0; oy < 2 && z0 < z1; ++oy) {
      const int y0 = std::max(region.lo[1], E * oy), y1 = std::min(region.hi[1], E * oy + E);
      for (int ox = 0; ox < 2 && y0 < y1; ++ox) {
        if (region.lo[0] > E * ox || region.hi[0] < E * ox + E) continue;
        const int o = ox | oy << 1 | oz << 2;
        const std::uint32_t b = blocks[o];
        on_block(o, b);
        for (int z = z0; z < z1; ++z)
          for (int y = y0; y < y1; ++y)
            f(b, local_node(0, y - E * oy, z - E * oz), patch::index(E * ox, y, z));
      }
    }
  }
}

template <class F>
void for_each_patch_row(const std::array<std::uint32_t, 8>& blocks, const PatchRegion& region,
                        F&& f) {
  for_each_patch_row(blocks, region, f, [](int, std::uint32_t) {});
}

// Zeroes components [0, count) of a patch over a region (finished: x in rows of 4).
inline void zero_patch(double* const* c, int count, const PatchRegion& r) {
  constexpr int E = SparseGrid::block_edge;
  const double zero[E] = {};
  for (int k = 0; k < count; ++k)
    for (int z = r.lo[2]; z < r.hi[2]; ++z)
      for (int y = r.lo[1]; y < r.hi[1]; ++y)
        for (int x = r.lo[0]; x < r.hi[0]; x += E)
          std::memcpy(c[k] + patch::index(x, y, z), zero, sizeof zero);
}

}  // namespace hvi::mpm
