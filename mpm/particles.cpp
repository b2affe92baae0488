#include "mpm/particles.hpp"

#include <cstdint>
#include <stdexcept>

namespace hvi::mpm {

int components(FieldKind kind) {
  switch (kind) {
    case FieldKind::scalar: return 1;
    case FieldKind::vector: return 3;
    case FieldKind::tensor: return 9;
    case FieldKind::sym_tensor: return 6;
  }
  return 1;
}

Particles::Particles() { register_core_fields(); }

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
    if (f.kind != kind) throw std::logic_error("particle field '" + name + "' declared twice with different kinds");
    return *f.data;
  }
  extra_storage_.push_back(std::make_unique<std::vector<double>>(size() * components(kind), initial));
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
  if (order.size() != size()) throw std::logic_error("Particles::reorder: order has the wrong size");
  for (auto& f : real_fields_)
    if (!f.scratch) permute(*f.data, components(f.kind), order);
  for (auto& f : int_fields_) permute(*f.data, 1, order);
}

namespace {
template <class T>
void compact(std::vector<T>& v, int nc, std::span<const std::uint8_t> flag) {
  std::size_t out = 0;
  for (std::size_t p = 0; p < flag.size(); ++p) {
    if (flag[p]) continue;
    if (out != p)
      for (int c = 0; c < nc; ++c) v[out * nc + c] = v[p * nc + c];
    ++out;
  }
  v.resize(out * nc);
}
}  // namespace

void Particles::erase_flagged(std::span<const std::uint8_t> flag) {
  // Field by field in parallel: each is its own array, moved the same way whatever the thread.
  const auto reals = static_cast<std::int64_t>(real_fields_.size());
  const auto fields = reals + static_cast<std::int64_t>(int_fields_.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t i = 0; i < fields; ++i) {
    if (i < reals)
      compact(*real_fields_[i].data, components(real_fields_[i].kind), flag);
    else
      compact(*int_fields_[i - reals].data, 1, flag);
  }
}

std::size_t Particles::bytes() const {
  std::size_t b = 0;
  for (const auto& f : real_fields_) b += f.data->capacity() * sizeof(double);
  for (const auto& f : int_fields_) b += f.data->capacity() * sizeof(std::int64_t);
  return b;
}

}  // namespace hvi::mpm
