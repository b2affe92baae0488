#include "mpm/io/id_slabs.hpp"

#include <algorithm>
#include <bit>
#include <numeric>

namespace hvi::mpm::io {

IdSlabs::IdSlabs(const Particles& P, Communicator* comm) : comm_(comm) {
  const std::size_t n = P.size();
  const int ranks = comm_ ? comm_->size() : 1;
  std::int64_t largest = -1;
  for (const auto id : P.id) largest = std::max(largest, id);
  // Ids are below 2^53, so a double carries the largest exactly.
  const double m = 1.0 + (comm_ ? comm_->max(static_cast<double>(largest)) : largest);
  const auto ids = static_cast<std::uint64_t>(m);
  sent_.assign(static_cast<std::size_t>(ranks), {});
  for (std::size_t p = 0; p < n; ++p) {
    const auto r = static_cast<std::uint64_t>(P.id[p]) * static_cast<std::uint64_t>(ranks) / ids;
    sent_[r].push_back(static_cast<std::uint32_t>(p));
  }
  std::vector<double> id_values(n);
  for (std::size_t p = 0; p < n; ++p) id_values[p] = std::bit_cast<double>(P.id[p]);
  const std::vector<double> received = route(id_values, 1);
  order_.resize(received.size());
  std::iota(order_.begin(), order_.end(), 0u);
  std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) {
    return std::bit_cast<std::int64_t>(received[a]) < std::bit_cast<std::int64_t>(received[b]);
  });
  rows_ = {0, received.size(), received.size()};
  if (!comm_) return;
  const auto counts = comm_->all_gather({static_cast<double>(received.size())});
  rows_.total = 0;
  for (int r = 0; r < ranks; ++r) {
    const auto c = static_cast<std::size_t>(counts[static_cast<std::size_t>(r)].at(0));
    if (r < comm_->rank()) rows_.first += c;
    rows_.total += c;
  }
}

// The values of this rank's points, each to the rank of its slab; returns what this rank
// received, rank by rank (its own first among them in rank order), not yet in id order.
std::vector<double> IdSlabs::route(const std::vector<double>& field, int columns) const {
  const auto nc = static_cast<std::size_t>(columns);
  std::vector<std::vector<double>> out(sent_.size());
  for (std::size_t r = 0; r < sent_.size(); ++r) {
    out[r].reserve(sent_[r].size() * nc);
    for (const auto p : sent_[r])
      out[r].insert(out[r].end(), field.begin() + p * nc, field.begin() + (p + 1) * nc);
  }
  if (!comm_) return std::move(out[0]);
  std::vector<double> received;
  for (auto& from : comm_->exchange(std::move(out)))
    received.insert(received.end(), from.begin(), from.end());
  return received;
}

std::vector<double> IdSlabs::gather(const std::vector<double>& field, int columns) const {
  const auto nc = static_cast<std::size_t>(columns);
  // On one rank every point is its own slab's, in its own order: no copy to route.
  const std::vector<double> routed = comm_ ? route(field, columns) : std::vector<double>{};
  const std::vector<double>& received = comm_ ? routed : field;
  std::vector<double> rows(order_.size() * nc);
  for (std::size_t k = 0; k < order_.size(); ++k)
    std::copy_n(received.begin() + order_[k] * nc, nc, rows.begin() + k * nc);
  return rows;
}

std::vector<std::int64_t> IdSlabs::gather(const std::vector<std::int64_t>& field) const {
  std::vector<double> values(field.size());
  std::transform(field.begin(), field.end(), values.begin(),
                 [](std::int64_t v) { return std::bit_cast<double>(v); });
  const std::vector<double> rows = gather(values, 1);
  std::vector<std::int64_t> out(rows.size());
  std::transform(rows.begin(), rows.end(), out.begin(),
                 [](double v) { return std::bit_cast<std::int64_t>(v); });
  return out;
}

}  // namespace hvi::mpm::io
