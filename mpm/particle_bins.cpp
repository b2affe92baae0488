#include "mpm/particle_bins.hpp"

#include <cmath>

namespace hvi::mpm {

std::size_t ParticleBins::bytes() const {
  std::size_t b = key.capacity() * sizeof(std::uint64_t) + order.capacity() * sizeof(std::uint32_t) +
                  offset.capacity() * sizeof(std::uint32_t) +
                  neighbours.capacity() * sizeof(neighbours[0]);
  for (const auto& c : colour) b += c.capacity() * sizeof(std::uint32_t);
  return b;
}

namespace {

// Key of the block owning the lowest stencil node of each particle.
template <class Shape>
void owner_keys(const Particles& particles, const GridGeometry& g, const std::vector<double>* half_width,
                std::vector<std::uint64_t>& key) {
  const double inv_h = 1.0 / g.cell_size;
  const auto n = static_cast<std::int64_t>(particles.size());
  const double* x = particles.position.data();
  const double* hw = half_width ? half_width->data() : nullptr;
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    int base[3];
    for (int d = 0; d < 3; ++d)
      base[d] = Shape::lowest((x[3 * p + d] - g.origin[d]) * inv_h, hw ? hw[3 * p + d] * inv_h : 0.0);
    key[p] = SparseGrid::key_of_node(base[0], base[1], base[2]);
  }
}

}  // namespace

void bin_particles(const Particles& particles, StencilSource stencil, SparseGrid& grid,
                   ParticleBins& bins, const std::vector<std::uint64_t>& extra_keys,
                   const std::uint8_t* field, std::uint8_t which) {
  const std::size_t n = particles.size();
  bins.key.resize(n);
  if (stencil.shape == ShapeFunction::linear)
    owner_keys<LinearShape>(particles, grid.geometry(), nullptr, bins.key);
  else
    owner_keys<GimpShape>(particles, grid.geometry(), stencil.half_width, bins.key);  // uGIMP, cpGIMP

  // Owner blocks in order of first appearance. Particles are stored mostly in block order, so
  // consecutive particles usually share a key and skip the hash lookup.
  grid.clear();
  constexpr std::uint32_t unbinned = SparseGrid::none;
  std::vector<std::uint32_t> owner(n, unbinned);
  std::vector<std::uint32_t> count;
  std::uint64_t last_key = ~std::uint64_t{0};
  std::uint32_t last_block = 0;
  std::size_t binned = 0;
  for (std::size_t p = 0; p < n; ++p) {
    if (field && field[p] != which) continue;
    ++binned;
    if (bins.key[p] != last_key) {
      last_key = bins.key[p];
      last_block = grid.activate(last_key);
      if (last_block == count.size()) count.push_back(0);
    }
    owner[p] = last_block;
    ++count[last_block];
  }
  const auto owners = static_cast<std::uint32_t>(count.size());

  // Counting sort, stable in particle order.
  bins.offset.assign(owners + 1, 0);
  for (std::uint32_t b = 0; b < owners; ++b) bins.offset[b + 1] = bins.offset[b] + count[b];
  bins.order.resize(binned);
  {
    std::vector<std::uint32_t> next(bins.offset.begin(), bins.offset.end() - 1);
    for (std::size_t p = 0; p < n; ++p)
      if (owner[p] != unbinned) bins.order[next[owner[p]]++] = static_cast<std::uint32_t>(p);
  }

  // Blocks the stencils reach, and colours.
  bins.neighbours.resize(owners);
  for (auto& c : bins.colour) c.clear();
  for (std::uint32_t b = 0; b < owners; ++b) {
    const auto c = SparseGrid::block_coords(grid.key(b));
    for (int o = 0; o < 8; ++o)
      bins.neighbours[b][o] =
          grid.activate(SparseGrid::block_key(c[0] + (o & 1), c[1] + ((o >> 1) & 1), c[2] + (o >> 2)));
    bins.colour[(c[0] & 1) | ((c[1] & 1) << 1) | ((c[2] & 1) << 2)].push_back(b);
  }
  for (const auto k : extra_keys) grid.activate(k);
  grid.allocate_nodes();
}

}  // namespace hvi::mpm
