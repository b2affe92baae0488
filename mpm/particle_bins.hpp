#pragma once
// Particles binned by the grid block that owns their stencil's lowest node. A particle's stencil
// (2 nodes per axis for linear, 3 for GIMP) starts in its owner block and reaches at most one block
// further along each axis. Owner blocks are grouped in 2 x 2 x 2 groups (the blocks whose
// coordinates halved are the same), whose points reach the 3 x 3 x 3 blocks from the group's
// first, and groups whose halved coordinates have the same parity on every axis (one of 8
// "colours") never write to the same node. Scattering colour by colour, groups of one colour in
// parallel, each group summing its owner blocks by key and a block's particles by (material, id)
// from zero before its sums go to the nodes (group_sums.hpp), needs no locks or atomics and adds
// every node's contributions in an order fixed by the points and the blocks: bitwise-reproducible
// results for any thread count and any order of the particle arrays, and the same bits when a
// node's groups are scattered by different processes (a run over several ranks). A group's blocks
// share most of the nodes they reach, which one thread then finds in its cache.
#include <array>
#include <cstdint>
#include <vector>

#include "mpm/grid.hpp"
#include "mpm/particles.hpp"
#include "mpm/shape_functions.hpp"

namespace hvi::mpm {

struct ParticleBins {
  // Per particle: while binning, the key of its owner block; then the owner block's index, or
  // SparseGrid::none for a particle not binned here.
  std::vector<std::uint64_t> owner;
  std::vector<std::uint32_t> order;   // particle indices by owner block, then (material, id)
  std::vector<std::uint32_t> offset;  // owner block b holds order[offset[b], offset[b+1])
  // Owner block b's blocks at b + (dx, dy, dz), dx, dy, dz in {0, 1}, index dx | dy<<1 | dz<<2.
  std::vector<std::array<std::uint32_t, 8>> neighbours;
  // Group g holds the owner blocks group_owner[group_offset[g], group_offset[g+1]), by key.
  std::vector<std::uint32_t> group_owner, group_offset;
  std::array<std::vector<std::uint32_t>, 8> colour;  // groups by parity of their halved coordinates
  std::size_t owner_count() const { return neighbours.size(); }
  std::size_t bytes() const;
};

// Per-particle GIMP half-widths (3 per particle, metres), or nullptr for linear shape functions.
struct StencilSource {
  ShapeFunction shape = ShapeFunction::linear;
  const std::vector<double>* half_width = nullptr;
};

// The key of each particle's owner block (the block of its stencil's lowest node).
void owner_block_keys(const Particles& particles, StencilSource stencil,
                      const GridGeometry& geometry, std::vector<std::uint64_t>& keys);

// Rebuilds the grid's active blocks for this step and bins the particles. Owner blocks get the
// block indices 0 .. owner_count()-1 in order of first appearance in the particle arrays; the
// blocks they reach and the blocks in `extra_keys` follow. With `field` (one entry per particle),
// only the particles whose entry equals `which` are binned: one velocity field of a contact
// model (contact.hpp) gets its own grid and bins.
void bin_particles(const Particles& particles, StencilSource stencil, SparseGrid& grid,
                   ParticleBins& bins, const std::vector<std::uint64_t>& extra_keys,
                   const std::uint8_t* field = nullptr, std::uint8_t which = 0);

}  // namespace hvi::mpm
