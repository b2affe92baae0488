#pragma once
// The per-point kernels of the transfers (transfers.cpp), on a block's patch (patch.hpp). Each
// walks the point's W x W rows of L lanes; a row is one short vector operation (simd.hpp). With
// weights N = Nx Ny Nz and gradients grad N = (dNx Ny Nz, Nx dNy Nz, Nx Ny dNz) / h:
//   scatter:   m_I += N m_p,  p_I += N m_p v_p,  f_I -= V_p sigma_p grad N_I
//   gather:    dv_p = sum N dv_I,  vg_p = sum N v_I,  L_p = sum v_I (x) grad N_I
//   averages:  s_I += N (V_p a_p, V_p),  abar_p = sum N abar_I
// Lanes accumulate apart and are summed at the end (simd::sum), the same on every target.
#include <cstdint>

#include "mpm/patch.hpp"
#include "mpm/simd.hpp"
#include "mpm/types.hpp"

namespace hvi::mpm::kernels {

// f(row offset in the patch, Ny Nz, dNy Nz / h, Ny dNz / h) for the NY x NZ rows from (y0, z0).
template <int NY, int NZ, int W, class F>
inline void rows(const PatchStencil<W>& st, int y0, int z0, double inv_h, F&& f) {
  const int base = st.base();
  for (int kz = z0; kz < z0 + NZ; ++kz)
    for (int ky = y0; ky < y0 + NY; ++ky)
      f(base + ky * patch::row + kz * patch::layer, st.N[1][ky] * st.N[2][kz],
        st.dN[1][ky] * st.N[2][kz] * inv_h, st.N[1][ky] * st.dN[2][kz] * inv_h);
}

// The same for each row of nonzero weight. A GIMP point reaches 2 or 3 nodes along y and z, so
// the four cases get loops of fixed length, which the compiler unrolls.
template <int W, class F>
inline void for_each_row(const PatchStencil<W>& st, double inv_h, F&& f) {
  const int ny = st.y1 - st.y0 + 1, nz = st.z1 - st.z0 + 1;
  if constexpr (W == 3) {
    if (ny == 3 && nz == 3) return rows<3, 3>(st, 0, 0, inv_h, f);
    if (ny == 2 && nz == 3) return rows<2, 3>(st, st.y0, 0, inv_h, f);
    if (ny == 3 && nz == 2) return rows<3, 2>(st, 0, st.z0, inv_h, f);
    if (ny == 2 && nz == 2) return rows<2, 2>(st, st.y0, st.z0, inv_h, f);
  } else if (ny == 2 && nz == 2) {
    return rows<2, 2>(st, 0, 0, inv_h, f);
  }
  const int base = st.base();
  for (int kz = st.z0; kz <= st.z1; ++kz)
    for (int ky = st.y0; ky <= st.y1; ++ky)
      f(base + ky * patch::row + kz * patch::layer, st.N[1][ky] * st.N[2][kz],
        st.dN[1][ky] * st.N[2][kz] * inv_h, st.N[1][ky] * st.dN[2][kz] * inv_h);
}

// Adds v to the L values at c + r.
template <int L>
inline void add(double* c, int r, simd::vec<L> v) {
  simd::store<L>(c + r, simd::load<L>(c + r) + v);
}

// Components of a scatter patch.
namespace scatter_patch {
constexpr int mass = 0, momentum = 1, force = 4, count = 7;
}

// Mass, momentum and internal force of one point. vs = V_p sigma_p (Sym6).
template <int W, bool Mass, bool Momentum, bool Force>
inline void scatter_point(const PatchStencil<W>& st, double inv_h, double m, const double* v,
                          const double* vs, double* const* c) {
  constexpr int L = PatchStencil<W>::L;
  using V = simd::vec<L>;
  const V nx = simd::load<L>(st.N[0]), dnx = simd::load<L>(st.dN[0]) * inv_h;
  const double mv[3] = {m * v[0], m * v[1], m * v[2]};
  for_each_row(st, inv_h, [&](int r, double nyz, double dy, double dz) {
    const V w = nx * nyz;
    if constexpr (Mass) add<L>(c[scatter_patch::mass], r, w * m);
    if constexpr (Momentum)
      for (int d = 0; d < 3; ++d) add<L>(c[scatter_patch::momentum + d], r, w * mv[d]);
    if constexpr (Force) {
      const V gx = dnx * nyz, gy = nx * dy, gz = nx * dz;
      add<L>(c[scatter_patch::force + 0], r,
             -(vs[sym::xx] * gx + vs[sym::xy] * gy + vs[sym::xz] * gz));
      add<L>(c[scatter_patch::force + 1], r,
             -(vs[sym::xy] * gx + vs[sym::yy] * gy + vs[sym::yz] * gz));
      add<L>(c[scatter_patch::force + 2], r,
             -(vs[sym::xz] * gx + vs[sym::yz] * gy + vs[sym::zz] * gz));
    }
  });
}

// sum_I N_I a_I over the point's nodes of one patch component a.
template <int W>
inline double gather_scalar(const PatchStencil<W>& st, double inv_h, const double* a) {
  constexpr int L = PatchStencil<W>::L;
  using V = simd::vec<L>;
  const V nx = simd::load<L>(st.N[0]);
  V acc{};
  for_each_row(st, inv_h,
               [&](int r, double nyz, double, double) { acc += nx * nyz * simd::load<L>(a + r); });
  return simd::sum(acc);
}

// (s0, s1) += N (x0, x1) on two patch components.
template <int W>
inline void scatter_pair(const PatchStencil<W>& st, double inv_h, double x0, double x1, double* s0,
                         double* s1) {
  constexpr int L = PatchStencil<W>::L;
  using V = simd::vec<L>;
  const V nx = simd::load<L>(st.N[0]);
  for_each_row(st, inv_h, [&](int r, double nyz, double, double) {
    const V w = nx * nyz;
    add<L>(s0, r, w * x0);
    add<L>(s1, r, w * x1);
  });
}

// Components of the velocity gather's patch: the increments dv_I, then the end velocities v_I +
// dv_I.
namespace velocity_patch {
constexpr int increment = 0, end = 3, count = 6;
}

// dv = sum N dv_I and vg = sum N (v_I + dv_I).
template <int W>
inline void gather_velocity_point(const PatchStencil<W>& st, double inv_h, const double* const* c,
                                  double* dv, double* vg) {
  constexpr int L = PatchStencil<W>::L;
  using V = simd::vec<L>;
  const V nx = simd::load<L>(st.N[0]);
  V a_dv[3] = {}, a_vg[3] = {};
  for_each_row(st, inv_h, [&](int r, double nyz, double, double) {
    const V w = nx * nyz;
    for (int d = 0; d < 3; ++d) {
      a_dv[d] += w * simd::load<L>(c[velocity_patch::increment + d] + r);
      a_vg[d] += w * simd::load<L>(c[velocity_patch::end + d] + r);
    }
  });
  if constexpr (L == 4) {
    const V s0 = simd::sum4(a_dv[0], a_dv[1], a_dv[2], a_vg[0]),
            s1 = simd::sum4(a_vg[1], a_vg[2], V{}, V{});
    dv[0] = s0[0], dv[1] = s0[1], dv[2] = s0[2];
    vg[0] = s0[3], vg[1] = s1[0], vg[2] = s1[1];
  } else {
    for (int d = 0; d < 3; ++d) {
      dv[d] = simd::sum(a_dv[d]);
      vg[d] = simd::sum(a_vg[d]);
    }
  }
}

// q_I += N m_p v_p on three patch components.
template <int W>
inline void scatter_vector(const PatchStencil<W>& st, double inv_h, const double* x,
                           double* const* c) {
  constexpr int L = PatchStencil<W>::L;
  using V = simd::vec<L>;
  const V nx = simd::load<L>(st.N[0]);
  for_each_row(st, inv_h, [&](int r, double nyz, double, double) {
    const V w = nx * nyz;
    for (int d = 0; d < 3; ++d) add<L>(c[d], r, w * x[d]);
  });
}

// L_ij = sum_I v_i,I dN_I/dx_j from three velocity components (row-major L).
template <int W>
inline void gather_gradient_point(const PatchStencil<W>& st, double inv_h, const double* const* v,
                                  double* L9) {
  constexpr int L = PatchStencil<W>::L;
  using V = simd::vec<L>;
  const V nx = simd::load<L>(st.N[0]), dnx = simd::load<L>(st.dN[0]) * inv_h;
  V acc[9] = {};
  for_each_row(st, inv_h, [&](int r, double nyz, double dy, double dz) {
    const V g[3] = {dnx * nyz, nx * dy, nx * dz};
    for (int i = 0; i < 3; ++i) {
      const V vi = simd::load<L>(v[i] + r);
      for (int j = 0; j < 3; ++j) acc[3 * i + j] += vi * g[j];
    }
  });
  if constexpr (L == 4) {
    const V s0 = simd::sum4(acc[0], acc[1], acc[2], acc[3]),
            s1 = simd::sum4(acc[4], acc[5], acc[6], acc[7]);
    for (int k = 0; k < 4; ++k) {
      L9[k] = s0[k];
      L9[4 + k] = s1[k];
    }
    L9[8] = simd::sum(acc[8]);
  } else {
    for (int k = 0; k < 9; ++k) L9[k] = simd::sum(acc[k]);
  }
}

// g_I += m_p grad N_I on three patch components (the outward normals of contact).
template <int W>
inline void scatter_mass_gradient(const PatchStencil<W>& st, double inv_h, double m,
                                  double* const* c) {
  constexpr int L = PatchStencil<W>::L;
  using V = simd::vec<L>;
  const V nx = simd::load<L>(st.N[0]), dnx = simd::load<L>(st.dN[0]) * inv_h;
  for_each_row(st, inv_h, [&](int r, double nyz, double dy, double dz) {
    add<L>(c[0], r, dnx * nyz * m);
    add<L>(c[1], r, nx * dy * m);
    add<L>(c[2], r, nx * dz * m);
  });
}

}  // namespace hvi::mpm::kernels
