#pragma once
// Small fixed-size vector and tensor helpers shared by the MPM core. SI units throughout.
#include <array>
#include <cmath>
#include <cstdint>

#include "materials/tensor.hpp"

namespace hvi::mpm {

using Vec3 = std::array<double, 3>;
// A 3x3 tensor, row-major: T[3*i + j] = T_ij.
using Mat3 = std::array<double, 9>;
// A symmetric 3x3 tensor in the XDMF "Tensor6" order: xx, xy, xz, yy, yz, zz
// (materials/tensor.hpp, with trace_sym).
using Sym6 = std::array<double, 6>;

namespace sym = materials::sym;
using materials::trace_sym;

inline double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline double norm(const Vec3& a) {
  return std::sqrt(dot(a, a));
}

inline double determinant(const double* F) {
  return F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
         F[2] * (F[3] * F[7] - F[4] * F[6]);
}

// sigma : D for a symmetric sigma (Tensor6 order) and a symmetric D given as a full 3x3 tensor's
// symmetric part; off-diagonal terms count twice.
inline double contract_sym(const double* s, const double* d) {
  return s[sym::xx] * d[sym::xx] + s[sym::yy] * d[sym::yy] + s[sym::zz] * d[sym::zz] +
         2.0 * (s[sym::xy] * d[sym::xy] + s[sym::xz] * d[sym::xz] + s[sym::yz] * d[sym::yz]);
}

// Von Mises equivalent stress sqrt(3/2 s:s) of a symmetric stress.
inline double von_mises(const double* s) {
  const double p = trace_sym(s) / 3.0;
  const double dxx = s[sym::xx] - p, dyy = s[sym::yy] - p, dzz = s[sym::zz] - p;
  const double j2 = 0.5 * (dxx * dxx + dyy * dyy + dzz * dzz) + s[sym::xy] * s[sym::xy] +
                    s[sym::xz] * s[sym::xz] + s[sym::yz] * s[sym::yz];
  return std::sqrt(3.0 * j2);
}

// Symmetric part D and spin W of a velocity gradient L (row-major, L_ij = dv_i/dx_j).
inline void split_velocity_gradient(const double* L, double* D /*Sym6*/, double* W /*Mat3*/) {
  D[sym::xx] = L[0];
  D[sym::yy] = L[4];
  D[sym::zz] = L[8];
  D[sym::xy] = 0.5 * (L[1] + L[3]);
  D[sym::xz] = 0.5 * (L[2] + L[6]);
  D[sym::yz] = 0.5 * (L[5] + L[7]);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) W[3 * i + j] = 0.5 * (L[3 * i + j] - L[3 * j + i]);
}

// The co-rotational part of the Jaumann rate, W sigma - sigma W, for symmetric sigma. With W
// antisymmetric, sigma W = -(W sigma)^T, so the term is A + A^T with A = W sigma, of whose nine
// entries (two products each, W_ii = 0) the six needed are formed; only W_xy, W_xz, W_yz are read.
inline void jaumann_spin_term(const double* W, const double* s, double* out /*Sym6*/) {
  const double wxy = W[1], wxz = W[2], wyz = W[5];
  const double xx = s[sym::xx], xy = s[sym::xy], xz = s[sym::xz], yy = s[sym::yy], yz = s[sym::yz],
               zz = s[sym::zz];
  const double a_xx = wxy * xy + wxz * xz, a_yy = -wxy * xy + wyz * yz, a_zz = -wxz * xz - wyz * yz;
  const double a_xy = wxy * yy + wxz * yz, a_yx = -wxy * xx + wyz * xz;
  const double a_xz = wxy * yz + wxz * zz, a_zx = -wxz * xx - wyz * xy;
  const double a_yz = -wxy * xz + wyz * zz, a_zy = -wxz * xy - wyz * yy;
  out[sym::xx] = 2.0 * a_xx;
  out[sym::yy] = 2.0 * a_yy;
  out[sym::zz] = 2.0 * a_zz;
  out[sym::xy] = a_xy + a_yx;
  out[sym::xz] = a_xz + a_zx;
  out[sym::yz] = a_yz + a_zy;
}

}  // namespace hvi::mpm
