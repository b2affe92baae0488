#include "mpm/particles.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <utility>

namespace hvi::mpm {

int components(FieldKind kind) {
  switch (kind) {
    case FieldKind::scalar:
      return 1;
    case FieldKind::vector:
      return 3;
    case FieldKind::tensor:
      return 9;
    case FieldKind::sym_tensor:
      return 6;
  }
  return 1;
}

Particles::Particles() {
  register_core_fields();
}

void Particles::register_core_fields() {
  real_fields_ = {
      {"position", FieldKind::vector, "m", false, false, &position},
      {"velocity", FieldKind::vector, "m/s", true, false, &velocity},
      {"mass", FieldKind::scalar, "kg", true, false, &mass},
      {"volume0", FieldKind::scalar, "m^3", false, false, &volume0},
      {"volume", FieldKind::scalar, "m^3", true, false, &volume},
      {"stress", FieldKind::sym_tensor, "Pa", true, false, &stress},
      {"internal_energy", FieldKind::scalar, "J/kg", true, false, &internal_energy},
      {"velocity_gradient", FieldKind::tensor, "1/s", false, true, &velocity_gradient},
      {"grid_velocity", FieldKind::vector, "m/s", false, true, &grid_velocity},
  };
  int_fields_ = {{"id", &id}, {"body", &body}, {"material", &material}};
}

std::vector<double>& Particles::add_field(const std::string& name, FieldKind kind,
                                          const std::string& unit, double initial, bool output) {
  for (auto& f : real_fields_) {
    if (f.name != name) continue;
    if (f.kind != kind)
      throw std::logic_error("particle field '" + name + "' declared twice with different kinds");
    return *f.data;
  }
  extra_storage_.push_back(
      std::make_unique<std::vector<double>>(size() * components(kind), initial));
  real_fields_.push_back({name, kind, unit, output, false, extra_storage_.back().get()});
  return *extra_storage_.back();
}

bool Particles::has_field(const std::string& name) const {
  for (const auto& f : real_fields_)
    if (f.name == name) return true;
  return false;
}

std::vector<double>& Particles::field(const std::string& name) {
  for (auto& f : real_fields_)
    if (f.name == name) return *f.data;
  throw std::logic_error("no particle field '" + name + "'");
}

const std::vector<double>& Particles::field(const std::string& name) const {
  return const_cast<Particles*>(this)->field(name);
}

std::size_t Particles::append(const double x[3], double volume_value, double mass_value,
                              std::int64_t body_index, std::int64_t material_index) {
  const std::size_t p = size();
  resize(p + 1);
  for (int d = 0; d < 3; ++d) position[3 * p + d] = x[d];
  volume0[p] = volume_value;
  volume[p] = volume_value;
  mass[p] = mass_value;
  id[p] = static_cast<std::int64_t>(p);
  body[p] = body_index;
  material[p] = material_index;
  return p;
}

void Particles::resize(std::size_t n) {
  // To exactly n: a vector grown past its capacity would double it, and a growing MPM zone that
  // adds a tenth of its points at a time would then hold up to twice the particles' memory.
  auto grow = [](auto& v, std::size_t size, auto zero) {
    if (size > v.capacity()) v.reserve(size);
    v.resize(size, zero);
  };
  for (auto& f : real_fields_) grow(*f.data, n * components(f.kind), 0.0);
  for (auto& f : int_fields_) grow(*f.data, n, std::int64_t{0});
}

namespace {
template <class T>
void permute(std::vector<T>& v, int nc, std::span<const std::uint32_t> order) {
  std::vector<T> tmp(order.size() * nc);
  for (std::size_t k = 0; k < order.size(); ++k)
    for (int c = 0; c < nc; ++c) tmp[k * nc + c] = v[order[k] * static_cast<std::size_t>(nc) + c];
  v.swap(tmp);
}
}  // namespace

void Particles::reorder(std::span<const std::uint32_t> order) {
  if (order.size() != size())
    throw std::logic_error("Particles::reorder: order has the wrong size");
  // Field by field in parallel, as erase().
  const auto reals = static_cast<std::int64_t>(real_fields_.size());
  const auto fields = reals + static_cast<std::int64_t>(int_fields_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t i = 0; i < fields; ++i) {
    if (i < reals) {
      if (!real_fields_[i].scratch)
        permute(*real_fields_[i].data, components(real_fields_[i].kind), order);
    } else {
      permute(*int_fields_[i - reals].data, 1, order);
    }
  }
}

namespace {

// Moves (from, to) that close the gaps of removed particles group by group. Group g holds
// [b, e) and will hold [B, B + n'), B <= b: its free slots are [B, b) (left by the groups before,
// whose particles there have moved into their own ranges) and its removed particles inside the
// new range; its survivors beyond the new range fill them, in order.
std::vector<std::pair<std::uint32_t, std::uint32_t>> gap_moves(
    std::span<const std::uint32_t> removed, std::span<const std::size_t> group_sizes,
    std::size_t& new_size) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> moves;
  std::size_t b = 0, B = 0, r = 0;  // old and new start of the group; next removed index
  for (const std::size_t n : group_sizes) {
    const std::size_t e = b + n, first_removed = r;
    while (r < removed.size() && removed[r] < e) ++r;
    const std::size_t kept = n - (r - first_removed), E = B + kept;
    std::vector<std::uint32_t> free;  // slots of [B, E) to fill, ascending
    for (std::size_t t = B; t < std::min(b, E); ++t) free.push_back(static_cast<std::uint32_t>(t));
    for (std::size_t k = first_removed; k < r && removed[k] < E; ++k) free.push_back(removed[k]);
    std::size_t next_removed = first_removed, f = 0;
    for (std::size_t from = std::max(b, E); from < e && f < free.size(); ++from) {
      while (next_removed < r && removed[next_removed] < from) ++next_removed;
      if (next_removed < r && removed[next_removed] == from) continue;  // removed: no source
      moves.emplace_back(static_cast<std::uint32_t>(from), free[f++]);
    }
    b = e;
    B = E;
  }
  new_size = B;
  return moves;
}

template <class T>
void apply_moves(std::vector<T>& v, int nc,
                 const std::vector<std::pair<std::uint32_t, std::uint32_t>>& moves,
                 std::size_t new_size) {
  for (const auto& [from, to] : moves)
    for (int c = 0; c < nc; ++c)
      v[to * static_cast<std::size_t>(nc) + c] = v[from * static_cast<std::size_t>(nc) + c];
  v.resize(new_size * nc);
}

}  // namespace

void Particles::erase(std::span<const std::uint32_t> removed,
                      std::span<const std::size_t> group_sizes) {
  if (removed.empty()) return;
  std::size_t new_size = 0;
  const auto moves = gap_moves(removed, group_sizes, new_size);
  // Field by field in parallel: each is its own array, moved the same way whatever the thread.
  const auto reals = static_cast<std::int64_t>(real_fields_.size());
  const auto fields = reals + static_cast<std::int64_t>(int_fields_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t i = 0; i < fields; ++i) {
    if (i < reals)
      apply_moves(*real_fields_[i].data, components(real_fields_[i].kind), moves, new_size);
    else
      apply_moves(*int_fields_[i - reals].data, 1, moves, new_size);
  }
}

std::size_t Particles::bytes() const {
  std::size_t b = 0;
  for (const auto& f : real_fields_) b += f.data->capacity() * sizeof(double);
  for (const auto& f : int_fields_) b += f.data->capacity() * sizeof(std::int64_t);
  return b;
}

}  // namespace hvi::mpm
