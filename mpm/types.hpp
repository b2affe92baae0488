#pragma once
// Small fixed-size vector and tensor helpers shared by the MPM core. SI units throughout.
#include <array>
#include <cmath>
#include <cstdint>

namespace hvi::mpm {

using Vec3 = std::array<double, 3>;
// A 3x3 tensor, row-major: T[3*i + j] = T_ij.
using Mat3 = std::array<double, 9>;
// A symmetric 3x3 tensor in the XDMF "Tensor6" order: xx, xy, xz, yy, yz, zz.
using Sym6 = std::array<double, 6>;

namespace sym {
inline constexpr int xx = 0, xy = 1, xz = 2, yy = 3, yz = 4, zz = 5;
}

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

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

inline double trace_sym(const double* s) { return s[sym::xx] + s[sym::yy] + s[sym::zz]; }

// Von Mises equivalent stress sqrt(3/2 s:s) of a symmetric stress.
inline double von_mises(const double* s) {
  const double p = trace_sym(s) / 3.0;
  const double dxx = s[sym::xx] - p, dyy = s[sym::yy] - p, dzz = s[sym::zz] - p;
  const double j2 = 0.5 * (dxx * dxx + dyy * dyy + dzz * dzz) +
                    s[sym::xy] * s[sym::xy] + s[sym::xz] * s[sym::xz] + s[sym::yz] * s[sym::yz];
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

// The co-rotational part of the Jaumann rate, W sigma - sigma W, for symmetric sigma.
inline void jaumann_spin_term(const double* W, const double* s, double* out /*Sym6*/) {
  const double S[9] = {s[sym::xx], s[sym::xy], s[sym::xz], s[sym::xy], s[sym::yy],
                       s[sym::yz], s[sym::xz], s[sym::yz], s[sym::zz]};
  double R[9];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double acc = 0.0;
      for (int k = 0; k < 3; ++k) acc += W[3 * i + k] * S[3 * k + j] - S[3 * i + k] * W[3 * k + j];
      R[3 * i + j] = acc;
    }
  out[sym::xx] = R[0];
  out[sym::xy] = R[1];
  out[sym::xz] = R[2];
  out[sym::yy] = R[4];
  out[sym::yz] = R[5];
  out[sym::zz] = R[8];
}

}  // namespace hvi::mpm
