#pragma once
/// @file
/// @brief local_global::PackedSprings: FastMassSpring's springs in the iterate's row order, and
/// the local step's pass over them (Liu et al. 2013, section 4): for each spring e = (a, b),
/// d_e = r_e (x_a - x_b) / |x_a - x_b|, scattered as k_e d_e into row a and -k_e d_e into row b
/// of the right-hand side A^T K D, with the springs' energy sum_e k_e / 2 (|x_a - x_b| - r_e)^2
/// [J] in the same pass when asked for.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <type_traits>
#include <utility>
#include <vector>
#if defined(__SSE2__)
#include <emmintrin.h>  // SSE2
#endif

#include "massspring/detail/simd.hpp"
#include "massspring/types.hpp"

namespace massspring {
namespace detail {

/// For two squared lengths sq and numerators num, lane by lane: len = sqrt(sq) and
/// quotient = num / len, each rounded once as by std::sqrt and by `/`. quotient is finite but
/// meaningless where sq is 0 or NaN (the caller does not use it there). With SSE2 two doubles go
/// through one sqrtpd and one divpd, built from and read back to registers: the divider, the
/// costliest part of a spring, then takes about what one lane did. Floats go lane by lane.
template <class Scalar>
inline void lengths2(const Scalar* sq, const Scalar* num, Scalar* len, Scalar* quotient) {
#if defined(__SSE2__)
  if constexpr (std::is_same_v<Scalar, double>) {
    const __m128d l = _mm_sqrt_pd(_mm_set_pd(sq[1], sq[0]));
    // max(l, clamp) is l for every sq > 0 (sqrt is monotone, and sq >= 2^-1074 gives
    // l >= 2^-537), and the clamp for 0 and NaN (max returns its second operand for NaN).
    const __m128d clamp = _mm_set1_pd(0x1p-537);
    const __m128d q = _mm_div_pd(_mm_set_pd(num[1], num[0]), _mm_max_pd(l, clamp));
    len[0] = _mm_cvtsd_f64(l), len[1] = _mm_cvtsd_f64(_mm_unpackhi_pd(l, l));
    quotient[0] = _mm_cvtsd_f64(q), quotient[1] = _mm_cvtsd_f64(_mm_unpackhi_pd(q, q));
    return;
  }
#endif
  for (int k = 0; k < 2; ++k) {
    len[k] = std::sqrt(sq[k]);
    quotient[k] = sq[k] > 0 ? num[k] / len[k] : Scalar(0);
  }
}

}  // namespace detail

namespace local_global {

/// @brief The two rows of a spring in the iterate (factor order; pinned rows after), a <= b.
struct SpringEnds {
  int a, b;
};

/// @brief The springs of a system sorted by their lower row a, then by the higher row b, with
/// their stiffness k [N/m], rest length r [m], k r [N] and the unit direction each keeps for when
/// its length is zero. Built once per factorization (allocates); the pass allocates nothing.
template <class Scalar>
struct PackedSprings {
  using Buffer = Vector<Scalar>;

  int count = 0;                 // springs
  std::vector<SpringEnds> ends;  // sorted by (a, b)
  std::vector<int> order;        // order[s]: the system's spring index of sorted spring s
  std::vector<bool> flipped;     // the system's (i, j) is (b, a): the direction's sign flips
  Buffer stiffness, rest, kr;    // per sorted spring
  Buffer direction;              // 3 per sorted spring, in the (a, b) orientation
  Buffer run_sum;  // per iterate row: the sum of its run of springs (pass()), 0 for rows with none

  [[nodiscard]] int size() const { return count; }

  /// @brief Packs the system's springs with `row[i]` the iterate row of point i and `rows` the
  /// iterate's row count. A spring's direction starts as its current direction, else (zero
  /// length) its rest direction. Allocates.
  template <class System>
  void build(const System& system, const std::vector<int>& row, int rows) {
    const int m = system.num_springs();
    const auto& springs = system.springs();
    order.resize(std::size_t(m));
    flipped.clear();
    flipped.reserve(std::size_t(m));
    std::iota(order.begin(), order.end(), 0);
    const auto key = [&](int e) {
      const int a = row[std::size_t(springs(e, 0))], b = row[std::size_t(springs(e, 1))];
      return std::pair<int, int>(std::min(a, b), std::max(a, b));
    };
    std::sort(order.begin(), order.end(), [&](int x, int y) { return key(x) < key(y); });
    count = m;
    ends.assign(std::size_t(m), SpringEnds{0, 0});
    stiffness.setZero(m);
    rest.setZero(m);
    kr.setZero(m);
    const auto& k = system.stiffness();
    for (int s = 0; s < m; ++s) {
      const int e = order[std::size_t(s)];
      const int i = row[std::size_t(springs(e, 0))], j = row[std::size_t(springs(e, 1))];
      // Stored as (a, b): d = x_a - x_b, which flips the sign of the spring's direction when
      // i > j; the direction of a zero-length spring is kept in that orientation.
      ends[std::size_t(s)] = {std::min(i, j), std::max(i, j)};
      stiffness(s) = k(e);
      flipped.push_back(i > j);
    }
    run_sum.setZero(3 * Eigen::Index(rows));
    direction.setZero(3 * Eigen::Index(m));
    for (int s = 0; s < m; ++s) {
      const int e = order[std::size_t(s)];
      Vector3<Scalar> u =
          (system.positions().row(springs(e, 0)) - system.positions().row(springs(e, 1)))
              .transpose();
      if (!(u.norm() > 0))
        u = (system.rest_positions().row(springs(e, 0)) -
             system.rest_positions().row(springs(e, 1)))
                .transpose();
      if (u.norm() > 0) u.normalize();
      direction.template segment<3>(3 * s) = flipped[std::size_t(s)] ? Vector3<Scalar>(-u) : u;
    }
  }

  /// @brief The system's current rest lengths (they may change at every step, for free).
  template <class RestLengths>
  void set_rest_lengths(const RestLengths& lengths) {
    for (int s = 0; s < count; ++s) {
      rest(s) = lengths(order[std::size_t(s)]);
      kr(s) = stiffness(s) * rest(s);
    }
  }

  /// @brief rhs -= A^T K A o on the first `free_rows` rows (rhs has no others): for each spring
  /// k_e (o_a - o_b) subtracted from row a and added to row b when b is one of them (a row after
  /// them is an exact pin's: its target is in o, and the spring's k_e o_b is the pin's share of the
  /// right-hand side). Springs between two such rows are skipped. Once per step, for the global
  /// step's displacement form (inertial_term.hpp).
  void subtract_from(const Scalar* o, Scalar* rhs, int free_rows) const {
    const SpringEnds* sp = ends.data();
    const Scalar* k = stiffness.data();
    for (int e = 0; e < count; ++e) {
      const int a = sp[e].a, b = sp[e].b;
      if (a >= free_rows) break;  // sorted by a: the rest join two pinned rows
      const Scalar* oa = o + 3 * a;
      const Scalar* ob = o + 3 * b;
      const Scalar d0 = k[e] * (oa[0] - ob[0]), d1 = k[e] * (oa[1] - ob[1]),
                   d2 = k[e] * (oa[2] - ob[2]);
      Scalar* ra = rhs + 3 * a;
      ra[0] -= d0, ra[1] -= d1, ra[2] -= d2;
      if (b < free_rows) {
        Scalar* rb = rhs + 3 * b;
        rb[0] += d0, rb[1] += d1, rb[2] += d2;
      }
    }
  }

  /// @brief One pass over the springs at the iterate x (`rows` rows of three). With Scatter (the
  /// local step) it adds A^T K D into w (rows of pinned points get garbage: the caller restores
  /// them); with Energy it returns the springs' energy [J]; with neither (after the last
  /// iteration) it records each spring's direction, which a spring of zero length keeps at the
  /// next step.
  ///
  /// Springs go two at a time whatever their rows: the two square roots and the two divisions
  /// k r / |d| share one SSE2 instruction each (detail::lengths2), and no branch depends on where
  /// a row's run of springs ends (about five springs on a cloth, at irregular intervals: a branch
  /// the predictor would most likely miss). Row a's share is summed in registers over its run,
  /// restarted where the run starts by a multiplication with 0 instead of a branch, and stored to
  /// run_sum after every spring, so that the last store holds the run's sum; run_sum is added to
  /// w after the pass. Row a's other additions (as the b of springs of lower rows) all come before
  /// that. Rows that start no run keep run_sum at 0.
  template <bool Scatter, bool Energy>
  MASSSPRING_NOINLINE double pass(const Scalar* x, Scalar* w, int rows) {
    const SpringEnds* sp = ends.data();
    const Scalar* k = stiffness.data();
    const Scalar* r = rest.data();
    const Scalar* krs = kr.data();
    const int m = count;
    Scalar* dir = direction.data();
    Scalar* sums = run_sum.data();
    double energy = 0;
    int previous = -1;
    Scalar acc0 = 0, acc1 = 0, acc2 = 0;  // k_e r_e d_e / |d_e| summed over row a's run so far
    // Springs e and e + 1 (N = 2), or the odd last one (N = 1).
    const auto springs_at = [&](int e, auto lanes) MASSSPRING_LAMBDA_ALWAYS_INLINE {
      constexpr int N = decltype(lanes)::value;
      Scalar d[2][3], sq[2], len[2], f[2], num[2];
      MASSSPRING_UNROLL
      for (int i = 0; i < 2; ++i) {
        const int q = e + (i < N ? i : 0);  // N = 1: the second lane is not used
        const SpringEnds& s = sp[q];
        num[i] = Scatter ? krs[q] : Scalar(1);
        const Scalar* xa = x + 3 * s.a;
        const Scalar* xb = x + 3 * s.b;
        d[i][0] = xa[0] - xb[0], d[i][1] = xa[1] - xb[1], d[i][2] = xa[2] - xb[2];
        sq[i] = d[i][0] * d[i][0] + d[i][1] * d[i][1] + d[i][2] * d[i][2];
      }
      detail::lengths2(sq, num, len, f);  // f = k r / |d| (Scatter) or 1 / |d|
      MASSSPRING_UNROLL
      for (int i = 0; i < N; ++i) {
        const SpringEnds& s = sp[e + i];
        if constexpr (Energy) {
          const Scalar stretch = len[i] - r[e + i];
          energy += double(k[e + i] * stretch * stretch);
        }
        if constexpr (Scatter) {
          Scalar s0, s1, s2;  // k_e r_e times the spring's unit direction
          if (sq[i] > 0) {
            s0 = f[i] * d[i][0], s1 = f[i] * d[i][1], s2 = f[i] * d[i][2];
          } else {
            const Scalar* u = dir + 3 * (e + i);
            s0 = num[i] * u[0], s1 = num[i] * u[1], s2 = num[i] * u[2];
          }
          // acc * 1 + s is acc + s and acc * 0 + s is s, exactly, for finite acc (a NaN or an
          // infinity reaches the next row too, where the substitution would take it anyway).
          const Scalar keep = Scalar(s.a == previous);
          previous = s.a;
          acc0 = acc0 * keep + s0, acc1 = acc1 * keep + s1, acc2 = acc2 * keep + s2;
          Scalar* sa = sums + 3 * s.a;
          sa[0] = acc0, sa[1] = acc1, sa[2] = acc2;
          Scalar* wb = w + 3 * s.b;
          wb[0] -= s0, wb[1] -= s1, wb[2] -= s2;
        } else if (sq[i] > 0) {
          Scalar* u = dir + 3 * (e + i);
          u[0] = d[i][0] * f[i], u[1] = d[i][1] * f[i], u[2] = d[i][2] * f[i];
        }
      }
    };
    int e = 0;
    for (; e + 1 < m; e += 2) springs_at(e, std::integral_constant<int, 2>{});
    if (e < m) springs_at(e, std::integral_constant<int, 1>{});
    if constexpr (Scatter) {
      const Eigen::Index size = 3 * Eigen::Index(rows);
      for (Eigen::Index i = 0; i < size; ++i) w[i] += sums[i];
    }
    return energy / 2;
  }
};

}  // namespace local_global
}  // namespace massspring
