#pragma once
/// @file
/// @brief The SIMD (AVX2 + FMA) variant of the local step's spring pass (spring_pass.hpp), double
/// only: local_global::SharePass stores each spring's share k_e r_e d_e / |d_e| instead of
/// scattering it, and local_global::ShareRows, a row source for the forward substitution
/// (storage/lower_factor.hpp), assembles each row of the right-hand side rhs0 + A^T K D from the
/// shares as the substitution reaches it. The same results, bit for bit, as the baseline pass.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "massspring/detail/simd.hpp"
#include "massspring/integrators/local_global/spring_pass.hpp"
#include "massspring/storage/lower_factor_simd.hpp"
#include "massspring/types.hpp"

namespace massspring::local_global {

/// @brief A right-hand side assembled from spring shares, row by row (a row source of
/// detail::LowerFactor, see detail::is_row_source): row i is base_i, minus the shares
/// minus_share[minus_begin[i] .. minus_begin[i + 1]) in that order, plus the sum of the
/// consecutive shares plus_begin[i] .. plus_begin[i + 1] - 1 (summed first to last, then added).
/// A share is four Scalars (the fourth never reaches a row), the array aligned to four Scalars.
/// Each spring's share is added to its lower row and subtracted from its higher one: the order
/// of the baseline spring pass, so the same result bit for bit.
template <class Scalar>
struct ShareRows {
  const Scalar* base = nullptr;  // rows * 3, row-major (w[3 r + c])
  const Scalar* shares = nullptr;
  const int* plus_begin = nullptr;   // rows + 1
  const int* minus_begin = nullptr;  // rows + 1
  const int* minus_share = nullptr;

  /// @brief Row i into out[0 .. 2], in the order documented above.
  void row(int i, Scalar* out) const {
    Scalar r0 = base[3 * i], r1 = base[3 * i + 1], r2 = base[3 * i + 2];
    for (int q = minus_begin[i]; q < minus_begin[i + 1]; ++q) {
      const Scalar* s = shares + 4 * std::ptrdiff_t(minus_share[q]);
      r0 -= s[0], r1 -= s[1], r2 -= s[2];
    }
    const int first = plus_begin[i], last = plus_begin[i + 1];
    if (first < last) {
      const Scalar* s = shares + 4 * std::ptrdiff_t(first);
      Scalar a0 = s[0], a1 = s[1], a2 = s[2];
      for (int e = first + 1; e < last; ++e) {
        s += 4;
        a0 += s[0], a1 += s[1], a2 += s[2];
      }
      r0 += a0, r1 += a1, r2 += a2;
    }
    out[0] = r0, out[1] = r1, out[2] = r2;
  }

#ifdef MASSSPRING_HAVE_AVX2_PATH
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // always inlined into an AVX2 function
#endif
  /// @brief row(i) in a detail::Row3 register R (fourth lane 0): the same operations in the
  /// same order.
  template <class R>
  MASSSPRING_TARGET_AVX2 MASSSPRING_ALWAYS_INLINE typename R::V row_simd(int i) const {
    auto r = R::load_masked(base + 3 * i);
    for (int q = minus_begin[i]; q < minus_begin[i + 1]; ++q)
      r = R::sub(r, R::load_aligned(shares + 4 * std::ptrdiff_t(minus_share[q])));
    const int first = plus_begin[i], last = plus_begin[i + 1];
    if (first < last) {
      const Scalar* s = shares + 4 * std::ptrdiff_t(first);
      auto a = R::load_aligned(s);
      for (int e = first + 1; e < last; ++e) a = R::add(a, R::load_aligned(s += 4));
      r = R::add(r, a);
    }
    return r;
  }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif
};

/// @brief The SIMD pass over PackedSprings<double>: each spring's share k r d / |d| stored (four
/// values per spring, from a 32-byte boundary), then read back through rows() in the order the
/// baseline pass adds them. A point's three coordinates are one 256-bit register (fourth lane 0);
/// four springs share one vsqrtpd and one vdivpd; |d|^2 is summed as (x^2 + y^2) + z^2 as in the
/// baseline: the same results, bit for bit. Storing the shares removes every read-modify-write
/// of a row from the pass. Float stays on the baseline pass.
class SharePass {
 public:
  /// @brief True when the SIMD pass is compiled in and the CPU runs it.
  static bool available() { return detail::cpu_has_avx2_fma(); }

  /// @brief The share layout of these springs over `rows` iterate rows; nothing when
  /// !available(). Allocates.
  template <class Scalar>
  void build(const PackedSprings<Scalar>& springs, int rows) {
    shares_.resize(0);
    plus_begin_.clear();
    minus_begin_.clear();
    minus_share_.clear();
    if (!available()) return;
    const int m = springs.count;
    // The padded springs' shares too (never read), and room to start at a 32-byte boundary.
    shares_.setZero(4 * Eigen::Index(springs.ends.size()) + 4);
    plus_begin_.assign(std::size_t(rows) + 1, 0);
    minus_begin_.assign(std::size_t(rows) + 1, 0);
    for (int s = 0; s < m; ++s) {
      ++plus_begin_[std::size_t(springs.ends[std::size_t(s)].a) + 1];
      ++minus_begin_[std::size_t(springs.ends[std::size_t(s)].b) + 1];
    }
    for (std::size_t r = 0; r < std::size_t(rows); ++r) {
      plus_begin_[r + 1] += plus_begin_[r];
      minus_begin_[r + 1] += minus_begin_[r];
    }
    minus_share_.resize(std::size_t(m));
    std::vector<int> next(minus_begin_.begin(), minus_begin_.end() - 1);
    for (int s = 0; s < m; ++s)
      minus_share_[std::size_t(next[std::size_t(springs.ends[std::size_t(s)].b)]++)] = s;
  }

  /// @brief base plus the shares, as a row source (valid while this and base live).
  ShareRows<double> rows(const double* base) {
    ShareRows<double> rhs;
    rhs.base = base;
    rhs.shares = share_start();
    rhs.plus_begin = plus_begin_.data();
    rhs.minus_begin = minus_begin_.data();
    rhs.minus_share = minus_share_.data();
    return rhs;
  }

#ifdef MASSSPRING_HAVE_AVX2_PATH
  /// @brief The pass at the iterate x (one double readable past its last row). With Shares, the
  /// shares are stored (read them through rows()); without, it is PackedSprings::pass<false,
  /// Energy>: each spring of nonzero length has its direction d / |d| recorded (1 / |d| by one
  /// division, then three products), and nothing else written. Returns the springs' energy [J]
  /// when Energy, summed in the baseline's order.
  template <bool Energy, bool Shares = true>
  MASSSPRING_TARGET_AVX2 MASSSPRING_NOINLINE double run(const double* x,
                                                        PackedSprings<double>& springs) {
    const int m = int(springs.ends.size());  // a multiple of 4: the padded springs are inert
    // The arrays in locals: a store through __m256d may alias anything, so members would be
    // read again after every store.
    const Arrays pass{x,
                      springs.ends.data(),
                      springs.kr.data(),
                      springs.rest.data(),
                      springs.stiffness.data(),
                      springs.direction.data(),
                      Shares ? share_start() : nullptr};
    double energy = 0;
    for (int e = 0; e < m; e += 4) springs4<Energy, Shares>(pass, e, energy);
    return energy / 2;
  }
#endif

 private:
  // shares_'s first value on a 32-byte boundary (computed at each use: a copy of the solver has
  // buffers of its own, aligned differently).
  double* share_start() {
    const auto address = reinterpret_cast<std::uintptr_t>(shares_.data());
    return shares_.data() + (32 - address % 32) % 32 / sizeof(double);
  }

#ifdef MASSSPRING_HAVE_AVX2_PATH
  // What run() reads and writes.
  struct Arrays {
    const double* x;  // the iterate, one double readable past its last row
    const SpringEnds* ends;
    const double *kr, *rest, *stiffness;
    double* direction;  // written without shares only
    double* shares;
  };

  // Lane i of v in all four lanes (the permutation needs an immediate: i is one once unrolled).
  MASSSPRING_TARGET_AVX2 MASSSPRING_ALWAYS_INLINE static __m256d broadcast_lane(__m256d v, int i) {
    switch (i) {
      case 0:
        return _mm256_permute4x64_pd(v, 0x00);
      case 1:
        return _mm256_permute4x64_pd(v, 0x55);
      case 2:
        return _mm256_permute4x64_pd(v, 0xAA);
      default:
        return _mm256_permute4x64_pd(v, 0xFF);
    }
  }

  // Springs e .. e + 3.
  template <bool Energy, bool Shares>
  MASSSPRING_TARGET_AVX2 MASSSPRING_ALWAYS_INLINE static void springs4(const Arrays& pass, int e,
                                                                       double& energy) {
    const SpringEnds* sp = pass.ends + e;
    const double* x = pass.x;
    // d = x_a - x_b from two plain 256-bit loads, the fourth lane (the next row's first value, or
    // the padding after the last row) set to 0.
    __m256d d[4];
    MASSSPRING_UNROLL
    for (int i = 0; i < 4; ++i) {
      const SpringEnds& s = sp[i];
      d[i] =
          _mm256_blend_pd(_mm256_sub_pd(_mm256_loadu_pd(x + 3 * s.a), _mm256_loadu_pd(x + 3 * s.b)),
                          _mm256_setzero_pd(), 0x8);
    }
    // hadd(p, q) = (p0 + p1, q0 + q1, p2 + p3, q2 + q3), and p3 = q3 = 0: the squared lengths'
    // x^2 + y^2 in the low halves, z^2 in the high ones.
    const __m256d t0 = _mm256_hadd_pd(_mm256_mul_pd(d[0], d[0]), _mm256_mul_pd(d[1], d[1]));
    const __m256d t1 = _mm256_hadd_pd(_mm256_mul_pd(d[2], d[2]), _mm256_mul_pd(d[3], d[3]));
    const __m256d sq =
        _mm256_add_pd(_mm256_permute2f128_pd(t0, t1, 0x20), _mm256_permute2f128_pd(t0, t1, 0x31));
    const __m256d len = _mm256_sqrt_pd(sq);
    // The clamp of detail::lengths2: f is finite, and unused, where sq is 0 or NaN.
    const __m256d f = _mm256_div_pd(Shares ? _mm256_loadu_pd(pass.kr + e) : _mm256_set1_pd(1.0),
                                    _mm256_max_pd(len, _mm256_set1_pd(0x1p-537)));
    if constexpr (Energy) {
      const __m256d stretch = _mm256_sub_pd(len, _mm256_loadu_pd(pass.rest + e));
      alignas(32) double lane[4];
      _mm256_store_pd(
          lane,
          _mm256_mul_pd(_mm256_mul_pd(_mm256_loadu_pd(pass.stiffness + e), stretch), stretch));
      MASSSPRING_UNROLL
      for (int i = 0; i < 4; ++i) energy += lane[i];  // an inert spring's 0 changes nothing
    }
    const int positive = _mm256_movemask_pd(_mm256_cmp_pd(sq, _mm256_setzero_pd(), _CMP_GT_OQ));
    if constexpr (!Shares) {
      double* dir = pass.direction + 3 * std::ptrdiff_t(e);
      MASSSPRING_UNROLL
      for (int i = 0; i < 4; ++i)
        if (positive >> i & 1) {  // d / |d|; a spring of zero length keeps its direction
          const __m256d u = _mm256_mul_pd(broadcast_lane(f, i), d[i]);
          _mm_storeu_pd(dir + 3 * i, _mm256_castpd256_pd128(u));
          _mm_store_sd(dir + 3 * i + 2, _mm256_extractf128_pd(u, 1));
        }
    } else {
      double* shares = pass.shares + 4 * std::ptrdiff_t(e);
      const __m256i three = _mm256_setr_epi64x(-1, -1, -1, 0);
      MASSSPRING_UNROLL
      for (int i = 0; i < 4; ++i) {
        // k r / |d| times d; fourth lane 0
        __m256d s = _mm256_mul_pd(broadcast_lane(f, i), d[i]);
        if (!(positive >> i & 1))  // zero length (or NaN): k r along the direction kept
          s = _mm256_mul_pd(_mm256_set1_pd(pass.kr[e + i]),
                            _mm256_maskload_pd(pass.direction + 3 * (e + i), three));
        _mm256_store_pd(shares + 4 * i, s);
      }
    }
  }
#endif

  Vector<double> shares_;  // k r d / |d| per sorted spring, four values (from 32 bytes)
  // Row a's run of springs is plus_begin_[a] .. plus_begin_[a + 1] - 1 (sorted by a); the springs
  // whose b is row r are minus_share_[minus_begin_[r] ..], ascending, as the baseline subtracts.
  std::vector<int> plus_begin_, minus_begin_, minus_share_;
};

}  // namespace massspring::local_global
