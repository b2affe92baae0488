#pragma once
// Short vectors of doubles for the transfer kernels, as GCC/Clang vector extensions: the compiler
// maps them to the widest registers the target has (two SSE registers for four lanes on the
// portable x86-64-v2 build, one AVX register in the x86-64-v3 clones). Every lane computes the
// same operations in the same order on every target, and the project is built without
// floating-point contraction (CMakeLists.txt: no fused multiply-adds), so a clone gives the same
// bits as the portable path, and a lane the same bits as the scalar expression it stands for.
#include <cstring>

namespace hvi::mpm::simd {

typedef double d2 __attribute__((vector_size(16)));
typedef double d4 __attribute__((vector_size(32)));

template <int L>
struct Lanes;
template <>
struct Lanes<2> {
  using type = d2;
};
template <>
struct Lanes<4> {
  using type = d4;
};
template <int L>
using vec = typename Lanes<L>::type;

// Unaligned loads and stores of L consecutive doubles.
template <int L>
inline vec<L> load(const double* p) {
  vec<L> v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <int L>
inline void store(double* p, vec<L> v) {
  std::memcpy(p, &v, sizeof v);
}
template <int L>
inline vec<L> broadcast(double x) {
  return vec<L>{} + x;
}

// The sum of the lanes, always in the order ((l0 + l1) + (l2 + l3)).
inline double sum(d2 v) {
  return v[0] + v[1];
}
inline double sum(d4 v) {
  return (v[0] + v[1]) + (v[2] + v[3]);
}

// The sums of four vectors at once, (sum a, sum b, sum c, sum d), each added in the order of sum().
typedef long long i4 __attribute__((vector_size(32)));
inline d4 sum4(d4 a, d4 b, d4 c, d4 d) {
  const i4 even = {0, 4, 2, 6}, odd = {1, 5, 3, 7}, low = {0, 1, 4, 5}, high = {2, 3, 6, 7};
  const d4 ab =
      __builtin_shuffle(a, b, even) + __builtin_shuffle(a, b, odd);  // a0+a1, b0+b1, a2+a3, b2+b3
  const d4 cd = __builtin_shuffle(c, d, even) + __builtin_shuffle(c, d, odd);
  return __builtin_shuffle(ab, cd, low) + __builtin_shuffle(ab, cd, high);
}

}  // namespace hvi::mpm::simd

// A kernel built twice, for x86-64-v3 (AVX2) and for the build's own target, the loader picking
// the one the processor runs (GCC function multi-versioning); `flatten` inlines what it calls, so
// the whole kernel is compiled for each. Elsewhere the portable build only.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(HVI_NO_CLONES)
#define HVI_SIMD_KERNEL __attribute__((target_clones("arch=x86-64-v3", "default"), flatten))
#else
#define HVI_SIMD_KERNEL __attribute__((flatten))
#endif
