// The far field spread over ranks (fem/far_field.hpp): the slabs, each node's owner, the batches a
// rank evaluates, and the plastic state brought to rank 0.
#include "fem/far_field_impl.hpp"

#include <numeric>

namespace hvi::fem {

void FarField::spread(FarFieldRanks ranks) {
  if (ranks.size < 1 || ranks.rank < 0 || ranks.rank >= ranks.size || !ranks.all_gather ||
      !ranks.gather_to_root)
    throw std::invalid_argument("far field: spread over ranks without a rank and collectives");
  impl_->ranks = std::move(ranks);
  impl_->partition();
}

std::size_t FarField::owned_node_count() const {
  const auto& I = *impl_;
  if (!I.ranks) return I.mass.size();
  return static_cast<std::size_t>(
      std::count(I.node_owner.begin(), I.node_owner.end(), I.ranks->rank));
}

// Slabs along x of equal estimated cost: the batches sorted by their lanes' mean centre x (then
// by index), and cut where the running cost passes k / size of the whole. A node goes to the
// lowest slab touching it; a batch is evaluated where it touches an owned node, and reported by
// the lowest such rank.
void FarField::Impl::partition() {
  const unsigned batches = matrix_free.n_cell_batches();
  const int size = ranks->size, me = ranks->rank;
  std::vector<double> centre(batches, 0.0), cost(batches, 0.0);
  std::vector<std::vector<std::size_t>> nodes(batches);
  std::vector<types::global_dof_index> dofs(fe->n_dofs_per_cell());
  for (unsigned b = 0; b < batches; ++b) {
    const unsigned lanes = matrix_free.n_active_entries_per_cell_batch(b);
    for (unsigned lane = 0; lane < lanes; ++lane) {
      const auto cell = matrix_free.get_cell_iterator(b, lane);
      centre[b] += cell->center()[0] / lanes;
      if (!lane_removed[W * b + lane])
        cost[b] += !lane_layer.empty() && lane_is_plastic(b, lane) ? ranks->plastic_cost : 1.0;
      cell->get_dof_indices(dofs);
      for (const auto d : dofs)
        if (d % 3 == 0) nodes[b].push_back(d / 3);
    }
  }
  std::vector<unsigned> order(batches);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](unsigned a, unsigned b) { return centre[a] < centre[b]; });
  const double total = std::accumulate(cost.begin(), cost.end(), 0.0);
  std::vector<int> slab(batches, 0);
  double before = 0.0;
  for (const unsigned b : order) {
    const double middle = before + 0.5 * cost[b];
    slab[b] = std::min(size - 1, static_cast<int>(middle / std::max(total, 1e-300) * size));
    before += cost[b];
  }
  node_owner.assign(mass.size(), size);
  for (unsigned b = 0; b < batches; ++b)
    for (const auto a : nodes[b]) node_owner[a] = std::min(node_owner[a], slab[b]);
  batch_reporter.assign(batches, size);
  std::vector<std::uint8_t> evaluated(batches, 0);
  for (unsigned b = 0; b < batches; ++b)
    for (const auto a : nodes[b]) {
      batch_reporter[b] = std::min(batch_reporter[b], node_owner[a]);
      evaluated[b] = evaluated[b] || node_owner[a] == me;
    }
  colours = all_colours;
  for (auto& colour : colours) std::erase_if(colour, [&](unsigned b) { return !evaluated[b]; });
}

void FarField::gather_state_to_root() {
  auto& I = *impl_;
  if (!I.ranks || !I.any_plastic()) return;
  const std::size_t block = static_cast<std::size_t>(I.n_q) * Impl::W * I.state_size;
  const auto slot = [&](unsigned b) {
    return I.plastic.begin() + static_cast<std::ptrdiff_t>(I.plastic_slot[b] * block);
  };
  // Rank 0's own batches are current where they are: it sends and copies only the others'.
  const int me = I.ranks->rank;
  std::vector<double> mine;
  for (unsigned b = 0; b < I.batch_reporter.size() && me != 0; ++b)
    if (I.plastic_slot[b] >= 0 && I.batch_reporter[b] == me)
      mine.insert(mine.end(), slot(b), slot(b) + static_cast<std::ptrdiff_t>(block));
  const auto all = I.ranks->gather_to_root(mine);
  if (me != 0) return;
  std::vector<std::size_t> at(all.size(), 0);
  for (unsigned b = 0; b < I.batch_reporter.size(); ++b) {
    if (I.plastic_slot[b] < 0 || I.batch_reporter[b] == 0) continue;
    const auto r = static_cast<std::size_t>(I.batch_reporter[b]);
    std::copy_n(all[r].begin() + static_cast<std::ptrdiff_t>(at[r]), block, slot(b));
    at[r] += block;
  }
}

}  // namespace hvi::fem
