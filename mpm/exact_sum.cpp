#include "mpm/exact_sum.hpp"

#include <algorithm>
#include <cmath>

namespace hvi::mpm {

ExactSum& ExactSum::operator+=(double x) {
  if (!std::isfinite(x)) {
    special_ += x;  // inf, -inf and NaN sum the same in any order
    return *this;
  }
  if (x == 0.0) return *this;
  // x = m 2^(e - 53), |m| < 2^53 an integer.
  int e = 0;
  const double f = std::frexp(x, &e);
  auto m = static_cast<std::int64_t>(std::ldexp(f, 53));
  int shift = e - 53 - lowest_exponent;
  if (shift < 0) {  // a subnormal: the bits below 2^-1074 are zero
    m /= std::int64_t{1} << -shift;
    shift = 0;
  }
  const std::int64_t sign = m < 0 ? -1 : 1;
  const unsigned __int128 v = static_cast<unsigned __int128>(m < 0 ? -m : m) << (shift % limb_bits);
  const int first = shift / limb_bits;
  for (int k = 0; k < 3; ++k)
    limb_[static_cast<std::size_t>(first + k)] +=
        sign * static_cast<std::int64_t>((v >> (limb_bits * k)) & 0xffffffffu);
  if (++pending_ >= (std::int64_t{1} << 30)) carry();
  return *this;
}

ExactSum& ExactSum::operator+=(const ExactSum& other) {
  for (std::size_t k = 0; k < limb_.size(); ++k) limb_[k] += other.limb_[k];
  special_ += other.special_;
  pending_ += other.pending_ + 1;
  if (pending_ >= (std::int64_t{1} << 30)) carry();
  return *this;
}

// Every limb but the last into [0, 2^32), the rest passed up: one representation per total.
void ExactSum::carry() {
  for (std::size_t k = 0; k + 1 < limb_.size(); ++k) {
    const std::int64_t up = limb_[k] >> limb_bits;  // floor division by 2^32
    limb_[k] -= up * (std::int64_t{1} << limb_bits);
    limb_[k + 1] += up;
  }
  pending_ = 0;
}

double ExactSum::value() const {
  if (special_ != 0.0 || std::isnan(special_)) return special_;
  ExactSum s = *this;
  s.carry();
  const bool negative = s.limb_.back() < 0;
  if (negative) {
    for (auto& l : s.limb_) l = -l;
    s.carry();
  }
  int top = limb_count - 1;
  while (top >= 0 && s.limb_[static_cast<std::size_t>(top)] == 0) --top;
  if (top < 0) return 0.0;
  // The three leading limbs (96 bits, at least 65 of them significant) as one integer.
  unsigned __int128 lead = 0;
  for (int k = top; k > top - 3; --k)
    lead = (lead << limb_bits) |
           (k >= 0 ? static_cast<unsigned __int128>(s.limb_[static_cast<std::size_t>(k)]) : 0u);
  const double magnitude =
      std::ldexp(static_cast<double>(lead), limb_bits * (top - 2) + lowest_exponent);
  return negative ? -magnitude : magnitude;
}

}  // namespace hvi::mpm
