#pragma once
// The largest principal value of a symmetric 3x3 tensor (Tensor6 order xx xy xz yy yz zz), by the
// closed-form trigonometric solution of the characteristic cubic (Smith 1961).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "materials/tensor.hpp"

namespace hvi::materials {

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

// Whether the largest principal value reaches `limit`: max_principal(s) >= limit, computed only
// when Gershgorin's bound, sigma_1 <= max_i (s_ii + sum_j!=i |s_ij|), does not already rule it out
// (with a margin far above the round-off of either form, so the answer is the same).
inline bool principal_reaches(const double* s, double limit) {
  const double xy = std::fabs(s[sym::xy]), xz = std::fabs(s[sym::xz]), yz = std::fabs(s[sym::yz]);
  const double bound = std::max({s[sym::xx] + xy + xz, s[sym::yy] + xy + yz, s[sym::zz] + xz + yz});
  const double margin = 1e-9 * (std::fabs(bound) + xy + xz + yz + std::fabs(limit));
  if (bound + margin < limit) return false;
  return max_principal(s) >= limit;
}

}  // namespace hvi::materials
