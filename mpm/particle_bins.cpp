#include "mpm/particle_bins.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace hvi::mpm {

std::size_t ParticleBins::bytes() const {
  std::size_t b =
      owner.capacity() * sizeof(std::uint64_t) + order.capacity() * sizeof(std::uint32_t) +
      offset.capacity() * sizeof(std::uint32_t) + neighbours.capacity() * sizeof(neighbours[0]) +
      (group_owner.capacity() + group_offset.capacity()) * sizeof(std::uint32_t);
  for (const auto& c : colour) b += c.capacity() * sizeof(std::uint32_t);
  return b;
}

namespace {

// Key of the block owning the lowest stencil node of each particle.
template <class Shape>
void owner_keys(const Particles& particles, const GridGeometry& g,
                const std::vector<double>* half_width, std::vector<std::uint64_t>& key) {
  const double inv_h = 1.0 / g.cell_size;
  const auto n = static_cast<std::int64_t>(particles.size());
  const double* x = particles.position.data();
  const double* hw = half_width ? half_width->data() : nullptr;
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    int base[3];
    for (int d = 0; d < 3; ++d)
      base[d] =
          Shape::lowest((x[3 * p + d] - g.origin[d]) * inv_h, hw ? hw[3 * p + d] * inv_h : 0.0);
    key[p] = SparseGrid::key_of_node(base[0], base[1], base[2]);
  }
}

// Particles [begin, end) of thread t of T, in thread order.
struct Chunk {
  std::size_t begin, end;
  Chunk(std::size_t n, int t, int threads)
      : begin(n * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads)),
        end(n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads)) {}
};

constexpr std::uint64_t unbinned = SparseGrid::none;

// Each binned particle's owner block, numbered in order of first appearance in the particle
// arrays, in place of its key: every thread lists where runs of one key start in its chunk, in
// parallel; the runs are numbered in order, serially (particles are stored mostly in block order,
// so there are few); the owners are then filled in, in parallel. The same numbering as one serial
// pass.
void number_owner_blocks(std::vector<std::uint64_t>& owner, SparseGrid& grid,
                         const std::uint8_t* field, std::uint8_t which) {
  const std::size_t n = owner.size();
  const int threads = omp_get_max_threads();
  std::vector<std::vector<std::size_t>> starts(static_cast<std::size_t>(threads));
  std::vector<std::vector<std::uint32_t>> blocks(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    const Chunk c(n, t, threads);
    auto& s = starts[static_cast<std::size_t>(t)];
    std::uint64_t last = ~std::uint64_t{0};
    for (std::size_t p = c.begin; p < c.end; ++p) {
      if (field && field[p] != which) continue;
      if (owner[p] != last) s.push_back(p);
      last = owner[p];
    }
  }
  for (int t = 0; t < threads; ++t)
    for (const std::size_t p : starts[static_cast<std::size_t>(t)])
      blocks[static_cast<std::size_t>(t)].push_back(grid.activate(owner[p]));
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    const Chunk c(n, t, threads);
    const auto& s = starts[static_cast<std::size_t>(t)];
    const auto& b = blocks[static_cast<std::size_t>(t)];
    std::size_t run = 0;
    for (std::size_t p = c.begin; p < c.end; ++p) {
      if (field && field[p] != which) {
        owner[p] = unbinned;
        continue;
      }
      while (run + 1 < s.size() && s[run + 1] <= p) ++run;
      owner[p] = b[run];
    }
  }
}

// Counting sort by owner block, stable in particle order: per-thread counts, their prefix sums
// per block in thread order, then each thread places its chunk.
void sort_by_owner(ParticleBins& bins, std::uint32_t owners) {
  const std::size_t n = bins.owner.size();
  const int threads = omp_get_max_threads();
  std::vector<std::vector<std::uint32_t>> next(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    const Chunk c(n, t, threads);
    auto& count = next[static_cast<std::size_t>(t)];
    count.assign(owners, 0);
    for (std::size_t p = c.begin; p < c.end; ++p)
      if (bins.owner[p] != unbinned) ++count[bins.owner[p]];
  }
  bins.offset.assign(owners + 1, 0);
  for (std::uint32_t b = 0; b < owners; ++b) {
    std::uint32_t at = bins.offset[b];
    for (auto& count : next) {  // count -> this thread's first slot in block b
      const std::uint32_t k = count[b];
      count[b] = at;
      at += k;
    }
    bins.offset[b + 1] = at;
  }
  bins.order.resize(bins.offset[owners]);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    const Chunk c(n, t, threads);
    auto& slot = next[static_cast<std::size_t>(t)];
    for (std::size_t p = c.begin; p < c.end; ++p)
      if (bins.owner[p] != unbinned)
        bins.order[slot[bins.owner[p]]++] = static_cast<std::uint32_t>(p);
  }
}

// Each owner block's points by (material, id). A block's patch adds its points in this order, so
// what the block adds to a node is a function of which points it holds, not of where they stand in
// the arrays: the same after any reorder or removal, and on whichever process holds the block. The
// solver keeps its arrays in this order (sort_by_material_and_block), so few blocks need sorting.
void order_points_by_id(ParticleBins& bins, const Particles& particles, std::uint32_t owners) {
  const std::int64_t* material = particles.material.data();
  const std::int64_t* id = particles.id.data();
  const auto before = [&](std::uint32_t a, std::uint32_t b) {
    return material[a] != material[b] ? material[a] < material[b] : id[a] < id[b];
  };
#pragma omp parallel for schedule(dynamic, 64)
  for (std::int64_t b = 0; b < static_cast<std::int64_t>(owners); ++b) {
    std::uint32_t* first = bins.order.data() + bins.offset[static_cast<std::size_t>(b)];
    std::uint32_t* last = bins.order.data() + bins.offset[static_cast<std::size_t>(b) + 1];
    if (!std::is_sorted(first, last, before)) std::sort(first, last, before);
  }
}

// Owner blocks by group of 2 x 2 x 2 (halved coordinates), groups numbered in order of their first
// owner block, a group's owners in order of their keys (so that a node receives a group's patches
// in an order fixed by the blocks, not by the arrays); groups coloured by the parity of their
// halved coordinates.
void group_owner_blocks(ParticleBins& bins, const SparseGrid& grid, std::uint32_t owners) {
  std::unordered_map<std::uint64_t, std::uint32_t> group_of;
  std::vector<std::uint32_t> group(owners), count;
  for (auto& c : bins.colour) c.clear();
  for (std::uint32_t b = 0; b < owners; ++b) {
    const auto c = SparseGrid::block_coords(grid.key(b));
    const auto [it, added] =
        group_of.try_emplace(SparseGrid::block_key(c[0] >> 1, c[1] >> 1, c[2] >> 1),
                             static_cast<std::uint32_t>(count.size()));
    if (added) {
      count.push_back(0);
      bins.colour[((c[0] >> 1) & 1) | (((c[1] >> 1) & 1) << 1) | (((c[2] >> 1) & 1) << 2)]
          .push_back(it->second);
    }
    group[b] = it->second;
    ++count[it->second];
  }
  bins.group_offset.assign(count.size() + 1, 0);
  for (std::size_t g = 0; g < count.size(); ++g)
    bins.group_offset[g + 1] = bins.group_offset[g] + count[g];
  bins.group_owner.resize(owners);
  std::vector<std::uint32_t> next(bins.group_offset.begin(), bins.group_offset.end() - 1);
  for (std::uint32_t b = 0; b < owners; ++b) bins.group_owner[next[group[b]]++] = b;
  for (std::size_t g = 0; g < count.size(); ++g)
    std::sort(bins.group_owner.begin() + bins.group_offset[g],
              bins.group_owner.begin() + bins.group_offset[g + 1],
              [&](std::uint32_t a, std::uint32_t b) { return grid.key(a) < grid.key(b); });
}

}  // namespace

void owner_block_keys(const Particles& particles, StencilSource stencil,
                      const GridGeometry& geometry, std::vector<std::uint64_t>& keys) {
  keys.resize(particles.size());
  if (stencil.shape == ShapeFunction::linear)
    owner_keys<LinearShape>(particles, geometry, nullptr, keys);
  else
    owner_keys<GimpShape>(particles, geometry, stencil.half_width, keys);  // uGIMP, cpGIMP
}

void bin_particles(const Particles& particles, StencilSource stencil, SparseGrid& grid,
                   ParticleBins& bins, const std::vector<std::uint64_t>& extra_keys,
                   const std::uint8_t* field, std::uint8_t which) {
  owner_block_keys(particles, stencil, grid.geometry(), bins.owner);

  grid.clear();
  number_owner_blocks(bins.owner, grid, field, which);
  const auto owners = static_cast<std::uint32_t>(grid.block_count());
  sort_by_owner(bins, owners);
  order_points_by_id(bins, particles, owners);

  // Blocks the stencils reach, and groups.
  bins.neighbours.resize(owners);
  for (std::uint32_t b = 0; b < owners; ++b) {
    const auto c = SparseGrid::block_coords(grid.key(b));
    for (int o = 0; o < 8; ++o)
      bins.neighbours[b][o] = grid.activate(
          SparseGrid::block_key(c[0] + (o & 1), c[1] + ((o >> 1) & 1), c[2] + (o >> 2)));
  }
  group_owner_blocks(bins, grid, owners);
  for (const auto k : extra_keys) grid.activate(k);
  grid.allocate_nodes();
}

}  // namespace hvi::mpm
