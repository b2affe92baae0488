#pragma once
// A symmetric 3x3 tensor as six doubles in the XDMF "Tensor6" order: xx, xy, xz, yy, yz, zz.
// What the laws need of it; mpm/types.hpp re-exports it beside its own helpers.

namespace hvi::materials {

namespace sym {
inline constexpr int xx = 0, xy = 1, xz = 2, yy = 3, yz = 4, zz = 5;
}

inline double trace_sym(const double* s) {
  return s[sym::xx] + s[sym::yy] + s[sym::zz];
}

}  // namespace hvi::materials
