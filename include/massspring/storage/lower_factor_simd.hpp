#pragma once
/// @file
/// @brief The AVX2 + FMA rows of detail::LowerFactor's substitutions (storage/lower_factor.hpp),
/// and detail::Row3, a row of three values in one vector register, which a right-hand-side row
/// source may use to give its rows to the AVX2 forward substitution (LowerFactor::forward_rows).
/// Compiled only where detail/simd.hpp defines MASSSPRING_HAVE_SIMD_PATH.

#include <cstddef>

#include "massspring/detail/simd.hpp"

namespace massspring::detail {

#ifdef MASSSPRING_HAVE_SIMD_PATH
// The AVX2 + FMA rows: the same sums as LowerFactor::forward_row and backward_row, over four
// accumulator sets (entries 4k, 4k + 1, 4k + 2, 4k + 3; the last count % 4 entries go to the
// first), each holding a row of w (three values) in one register whose fourth lane is zero (256
// bits for double, 128 for float), each product added by one fused multiply-add. Four sets
// instead of the baseline's two: a fused multiply-add's latency is four of its issue slots.
// - The forward substitution loads a row with one masked load. The back substitution reads rows
//   it has just stored, and a load of a row stored as two narrower stores waits for the stores to
//   reach the cache, so there a row is loaded as its first two values and its third.
// - A row is stored as its first two values and its third, never the fourth lane (the next
//   row's first value).
// Row3<Scalar>'s functions take and return vector registers; they are always inlined into the
// AVX2 functions below, so GCC's note that such a signature's ABI depends on -mavx is moot.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
#define MASSSPRING_ROW3 MASSSPRING_TARGET_AVX2 __attribute__((always_inline)) static inline

template <class Scalar>
struct Row3;

template <>
struct Row3<double> {
  using V = __m256d;
  MASSSPRING_ROW3 V zero() { return _mm256_setzero_pd(); }
  MASSSPRING_ROW3 V load(const double* p) {
    return _mm256_insertf128_pd(_mm256_castpd128_pd256(_mm_loadu_pd(p)), _mm_load_sd(p + 2), 1);
  }
  MASSSPRING_ROW3 V load_masked(const double* p) {
    return _mm256_maskload_pd(p, _mm256_setr_epi64x(-1, -1, -1, 0));
  }
  MASSSPRING_ROW3 V load_aligned(const double* p) { return _mm256_load_pd(p); }  // 32-byte aligned
  MASSSPRING_ROW3 V add(V a, V b) { return _mm256_add_pd(a, b); }
  MASSSPRING_ROW3 V sub(V a, V b) { return _mm256_sub_pd(a, b); }
  MASSSPRING_ROW3 void store(double* p, V v) {
    _mm_storeu_pd(p, _mm256_castpd256_pd128(v));
    _mm_store_sd(p + 2, _mm256_extractf128_pd(v, 1));
  }
  MASSSPRING_ROW3 V sub_product(const double* l, V x, V acc) {  // acc - l x
    return _mm256_fnmadd_pd(_mm256_broadcast_sd(l), x, acc);
  }
  MASSSPRING_ROW3 V add_product(const double* l, V x, V acc) {  // acc + l x
    return _mm256_fmadd_pd(_mm256_broadcast_sd(l), x, acc);
  }
  MASSSPRING_ROW3 V finish(V s, V t, V u, V v, double inv) {  // ((s - t) + (u - v)) inv
    return _mm256_mul_pd(_mm256_add_pd(_mm256_sub_pd(s, t), _mm256_sub_pd(u, v)),
                         _mm256_set1_pd(inv));
  }
};

template <>
struct Row3<float> {
  using V = __m128;
  MASSSPRING_ROW3 V zero() { return _mm_setzero_ps(); }
  MASSSPRING_ROW3 V load(const float* p) {  // (x, y) through __m64 (may alias), then z
    return _mm_movelh_ps(_mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(p)),
                         _mm_load_ss(p + 2));
  }
  MASSSPRING_ROW3 V load_masked(const float* p) {
    return _mm_maskload_ps(p, _mm_setr_epi32(-1, -1, -1, 0));
  }
  MASSSPRING_ROW3 V load_aligned(const float* p) { return _mm_load_ps(p); }  // 16-byte aligned
  MASSSPRING_ROW3 V add(V a, V b) { return _mm_add_ps(a, b); }
  MASSSPRING_ROW3 V sub(V a, V b) { return _mm_sub_ps(a, b); }
  MASSSPRING_ROW3 void store(float* p, V v) {
    _mm_storel_pi(reinterpret_cast<__m64*>(p), v);
    _mm_store_ss(p + 2, _mm_movehl_ps(v, v));
  }
  MASSSPRING_ROW3 V sub_product(const float* l, V x, V acc) {
    return _mm_fnmadd_ps(_mm_broadcast_ss(l), x, acc);
  }
  MASSSPRING_ROW3 V add_product(const float* l, V x, V acc) {
    return _mm_fmadd_ps(_mm_broadcast_ss(l), x, acc);
  }
  MASSSPRING_ROW3 V finish(V s, V t, V u, V v, float inv) {
    return _mm_mul_ps(_mm_add_ps(_mm_sub_ps(s, t), _mm_sub_ps(u, v)), _mm_set1_ps(inv));
  }
};
#undef MASSSPRING_ROW3

// The forward substitution's rows order[begin .. end) (order null: the rows themselves) of a
// LowerFactor f.
template <class Factor, class Index, class Scalar>
MASSSPRING_TARGET_AVX2 void forward_rows_avx2(const Factor& f, const Index* order, Index begin,
                                              Index end, Scalar* w) {
  using R = Row3<Scalar>;
  for (Index q = begin; q < end; ++q) {
    const Index i = order ? order[q] : q;
    const Index* idx = f.row_inner + f.row_outer[i];
    const Scalar* l = f.row_value + f.row_outer[i];
    Index count = f.row_outer[i + 1] - f.row_outer[i];
    auto s = R::load(w + 3 * i), t = R::zero(), u = R::zero(), v = R::zero();
    for (; count >= 4; count -= 4, idx += 4, l += 4) {
      s = R::sub_product(l, R::load_masked(w + 3 * idx[0]), s);
      t = R::add_product(l + 1, R::load_masked(w + 3 * idx[1]), t);
      u = R::sub_product(l + 2, R::load_masked(w + 3 * idx[2]), u);
      v = R::add_product(l + 3, R::load_masked(w + 3 * idx[3]), v);
    }
    for (; count > 0; --count, ++idx, ++l) s = R::sub_product(l, R::load_masked(w + 3 * idx[0]), s);
    R::store(w + 3 * i, R::finish(s, t, u, v, f.inv_diag[i]));
  }
}

// The back substitution's rows order[end - 1] down to order[begin] of a LowerFactor f.
template <class Factor, class Index, class Scalar>
MASSSPRING_TARGET_AVX2 void backward_rows_avx2(const Factor& f, const Index* order, Index begin,
                                               Index end, Scalar* w) {
  using R = Row3<Scalar>;
  for (Index q = end - 1; q >= begin; --q) {
    const Index j = order ? order[q] : q;
    Index count = f.outer[j + 1] - 1 - f.outer[j];
    const Index* idx = f.inner + f.outer[j + 1] - 1;  // the diagonal is at outer[j]
    const Scalar* l = f.value + f.outer[j + 1] - 1;
    auto s = R::load(w + 3 * j), t = R::zero(), u = R::zero(), v = R::zero();
    for (; count >= 4; count -= 4, idx -= 4, l -= 4) {
      s = R::sub_product(l, R::load(w + 3 * idx[0]), s);
      t = R::add_product(l - 1, R::load(w + 3 * idx[-1]), t);
      u = R::sub_product(l - 2, R::load(w + 3 * idx[-2]), u);
      v = R::add_product(l - 3, R::load(w + 3 * idx[-3]), v);
    }
    for (; count > 0; --count, --idx, --l) s = R::sub_product(l, R::load(w + 3 * idx[0]), s);
    R::store(w + 3 * j, R::finish(s, t, u, v, f.inv_diag[j]));
  }
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif

}  // namespace massspring::detail
