#pragma once
// A sum of doubles that does not depend on the order of its terms: each term is added exactly to a
// fixed-point accumulator spanning every finite double (2^-1074 to 2^1024, in 32-bit limbs), and
// the exact total is rounded to a double once, at the end. Two accumulators add exactly too, so the
// energies of a run come out bitwise the same for any thread count, any order of the particle
// arrays and (summed per process, then over processes) any number of processes.
//
// A term is m 2^e, m a 53-bit integer; it lands in the limbs covering bits e .. e + 52. Limbs are
// 64-bit signed integers holding 32-bit digits, so about 2^30 terms can be added before the carries
// must be passed up (done then, and before reading).
#include <array>
#include <cstdint>

namespace hvi::mpm {

class ExactSum {
 public:
  ExactSum& operator+=(double x);
  ExactSum& operator+=(const ExactSum& other);
  // The exact total rounded to a double (to nearest, ties decided by the leading 65 bits); a NaN or
  // infinite term makes it their (order-free) sum.
  double value() const;

 private:
  static constexpr int limb_bits = 32;
  static constexpr int lowest_exponent = -1074;  // of the smallest subnormal's bit
  static constexpr int limb_count = (1024 - lowest_exponent) / limb_bits + 3;
  void carry();
  std::array<std::int64_t, limb_count> limb_{};
  std::int64_t pending_ = 0;  // terms added since the last carry
  double special_ = 0.0;      // the sum of the non-finite terms
};

}  // namespace hvi::mpm
