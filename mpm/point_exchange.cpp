#include "mpm/point_exchange.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "mpm/grid.hpp"

namespace hvi::mpm {

namespace {

// The fields a point carries, by name: ranks that declared the same fields in another order (a
// checkpoint's, a creator's) read each other's points alike.
struct Layout {
  std::vector<const RealField*> reals;
  std::vector<const IntField*> ints;
  std::size_t per_point = 0;  // doubles
  double signature = 0.0;     // a hash of the names and sizes, the first double of a message
};

Layout layout(const Particles& P) {
  Layout l;
  for (const auto& f : P.real_fields())
    if (!f.scratch) l.reals.push_back(&f);
  for (const auto& f : P.int_fields()) l.ints.push_back(&f);
  std::sort(l.reals.begin(), l.reals.end(), [](auto a, auto b) { return a->name < b->name; });
  std::sort(l.ints.begin(), l.ints.end(), [](auto a, auto b) { return a->name < b->name; });
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
  auto mix = [&](const std::string& text) {
    for (const char c : text) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  };
  for (const auto* f : l.reals) {
    l.per_point += static_cast<std::size_t>(components(f->kind));
    mix(f->name + "/" + std::to_string(components(f->kind)) + ";");
  }
  for (const auto* f : l.ints) mix(f->name + ";");
  l.per_point += l.ints.size();
  l.signature = std::bit_cast<double>(hash);
  return l;
}

}  // namespace

std::vector<double> pack_points(const Particles& P, std::span<const std::uint32_t> which) {
  if (which.empty()) return {};
  const Layout l = layout(P);
  const std::size_t per = l.per_point;
  std::vector<double> out(1 + per * which.size());
  out[0] = l.signature;
  std::size_t offset = 1;  // of the field within a point's record, after the signature
  for (const auto* f : l.reals) {
    const auto nc = static_cast<std::size_t>(components(f->kind));
    const double* data = f->data->data();
    for (std::size_t k = 0; k < which.size(); ++k)
      std::copy_n(data + nc * which[k], nc, &out[k * per + offset]);
    offset += nc;
  }
  for (const auto* f : l.ints) {
    for (std::size_t k = 0; k < which.size(); ++k)
      out[k * per + offset] = std::bit_cast<double>((*f->data)[which[k]]);
    offset += 1;
  }
  return out;
}

void append_points(Particles& P, std::span<const double> packed) {
  if (packed.empty()) return;
  const Layout l = layout(P);
  const std::size_t per = l.per_point;
  if (std::bit_cast<std::uint64_t>(packed[0]) != std::bit_cast<std::uint64_t>(l.signature) ||
      (packed.size() - 1) % per != 0)
    throw std::logic_error("received points whose fields differ from this rank's");
  const std::size_t n = (packed.size() - 1) / per, first = P.size();
  P.resize(first + n);
  std::size_t offset = 1;
  for (const auto* f : l.reals) {
    const auto nc = static_cast<std::size_t>(components(f->kind));
    double* data = f->data->data();
    for (std::size_t k = 0; k < n; ++k)
      std::copy_n(&packed[k * per + offset], nc, data + nc * (first + k));
    offset += nc;
  }
  for (const auto* f : l.ints) {
    for (std::size_t k = 0; k < n; ++k)
      (*f->data)[first + k] = std::bit_cast<std::int64_t>(packed[k * per + offset]);
    offset += 1;
  }
}

std::vector<GroupLoad> global_loads(Communicator& comm, const std::vector<GroupLoad>& mine) {
  std::vector<double> out;
  out.reserve(2 * mine.size());
  for (const auto& g : mine) {
    out.push_back(std::bit_cast<double>(g.key));
    out.push_back(std::bit_cast<double>(g.points));
  }
  std::vector<GroupLoad> all;
  for (const auto& from : comm.all_gather(out))
    for (std::size_t k = 0; k + 1 < from.size(); k += 2)
      all.push_back(
          {std::bit_cast<std::uint64_t>(from[k]), std::bit_cast<std::uint64_t>(from[k + 1])});
  std::sort(all.begin(), all.end(), [](auto& a, auto& b) { return a.key < b.key; });
  std::vector<GroupLoad> merged;
  for (const auto& g : all)
    if (!merged.empty() && merged.back().key == g.key)
      merged.back().points += g.points;
    else
      merged.push_back(g);
  return merged;
}

void add_over_ranks(Communicator& comm, std::span<ExactSum> sums) {
  static_assert(std::is_trivially_copyable_v<ExactSum>);
  constexpr std::size_t per = (sizeof(ExactSum) + sizeof(double) - 1) / sizeof(double);
  std::vector<double> mine(per * sums.size(), 0.0);
  for (std::size_t k = 0; k < sums.size(); ++k)
    std::memcpy(&mine[k * per], &sums[k], sizeof(ExactSum));
  const auto all = comm.all_gather(mine);
  for (auto& s : sums) s = ExactSum{};
  for (const auto& from : all)  // integer limbs: exact in any order
    for (std::size_t k = 0; k < sums.size(); ++k) {
      ExactSum part;
      std::memcpy(static_cast<void*>(&part), &from[k * per], sizeof(ExactSum));
      sums[k] += part;
    }
}

std::uint64_t group_of_block(std::uint64_t block_key) {
  const auto c = SparseGrid::block_coords(block_key);
  return SparseGrid::block_key(c[0] / 2, c[1] / 2, c[2] / 2);
}

}  // namespace hvi::mpm
