#pragma once
// The largest principal value of a symmetric 3x3 tensor (Tensor6 order xx xy xz yy yz zz), by the
// closed-form trigonometric solution of the characteristic cubic (Smith 1961).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "mpm/types.hpp"

namespace hvi::mpm {

inline double max_principal(const double* s) {
  const double p1 = s[sym::xy] * s[sym::xy] + s[sym::xz] * s[sym::xz] + s[sym::yz] * s[sym::yz];
  const double q = trace_sym(s) / 3.0;
  if (p1 <= 1e-30 * (q * q + 1e-300)) return std::max({s[sym::xx], s[sym::yy], s[sym::zz]});
  const double a = s[sym::xx] - q, b = s[sym::yy] - q, c = s[sym::zz] - q;
  const double p2 = a * a + b * b + c * c + 2.0 * p1;
  const double p = std::sqrt(p2 / 6.0);
  // det((S - q I) / p) / 2
  const double B[6] = {a / p, s[sym::xy] / p, s[sym::xz] / p, b / p, s[sym::yz] / p, c / p};
  const double det = B[0] * (B[3] * B[5] - B[4] * B[4]) - B[1] * (B[1] * B[5] - B[4] * B[2]) +
                     B[2] * (B[1] * B[4] - B[3] * B[2]);
  const double r = std::clamp(0.5 * det, -1.0, 1.0);
  const double phi = std::acos(r) / 3.0;
  return q + 2.0 * p * std::cos(phi);
}

}  // namespace hvi::mpm
