#pragma once
/// @file
/// @brief detail::LowerFactor and detail::LowerFactorRows: forward and back substitution with a
/// sparse Cholesky factor L for three right-hand sides at once, in place, allocation-free, with
/// an AVX2 + FMA version chosen at run time (storage/lower_factor_simd.hpp).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "massspring/detail/simd.hpp"
#include "massspring/storage/lower_factor_simd.hpp"

namespace massspring {
namespace detail {

/// @brief A lower factor L (column j's diagonal first in the column-compressed arrays) with its
/// inverse diagonal and a row-compressed copy of its strict lower part, and forward and back
/// substitution for three right-hand sides stored row-major (w[3 r + c]), in place: one walk of L
/// forward and one back for all three columns.
///
/// Both substitutions are gathers (a row's sum over the rows already solved, held in registers):
/// the forward one walks the row copy upward, the back one walks the columns downward, each
/// column from its last entry to its first, so that every array is read in one direction only and
/// the hardware prefetcher follows it. Each sum is split over two sets of accumulators (four in the
/// AVX2 rows), so that the additions do not form one chain of dependent latencies
/// (docs/performance.md compares it with a column-oriented substitution).
///
/// forward_row() and backward_row() are the baseline (SSE2) rows. forward_rows(), backward_rows()
/// and everything built on them take the AVX2 + FMA rows instead when `simd` is set: the same
/// sums, rounded once per product and split four ways instead of two.
template <class Scalar, class Index>
struct LowerFactor {
  Index n = 0;
  const Index* outer = nullptr;  // column starts (n + 1), diagonal first in each column
  const Index* inner = nullptr;
  const Scalar* value = nullptr;
  const Scalar* inv_diag = nullptr;   // 1 / L(j, j)
  const Index* row_outer = nullptr;   // row starts (n + 1) of the strict lower part
  const Index* row_inner = nullptr;   // its column indices, ascending in each row
  const Scalar* row_value = nullptr;  // its values
  /// Parallel schedule (see LowerFactorRows::plan_threads): parts 0 .. parts - 1 are the rows
  /// schedule[part_start[t] .. part_start[t + 1]), each a union of whole subtrees of L's
  /// elimination tree, ascending; schedule[part_start[parts] .. n) are the rows above them (the
  /// top, ascending). parts == 0: no schedule.
  const Index* schedule = nullptr;
  const Index* part_start = nullptr;
  int parts = 0;
  /// Substitute with the AVX2 + FMA rows (LowerFactorRows::view() sets it when the CPU has
  /// both). Their results differ from the SSE2 rows' in the last bits: each product is added
  /// with one rounding (a fused multiply-add) instead of two.
  bool simd = false;

  /// @brief forward_row(order[q]) for q = begin .. end - 1 (order null: q itself).
  void forward_rows(const Index* order, Index begin, Index end, Scalar* w) const {
#ifdef MASSSPRING_HAVE_SIMD_PATH
    if (simd) return forward_rows_avx2(*this, order, begin, end, w);
#endif
    for (Index q = begin; q < end; ++q) forward_row(order ? order[q] : q, w);
  }

  /// @brief backward_row(order[q]) for q = end - 1 down to begin (order null: q itself).
  void backward_rows(const Index* order, Index begin, Index end, Scalar* w) const {
#ifdef MASSSPRING_HAVE_SIMD_PATH
    if (simd) return backward_rows_avx2(*this, order, begin, end, w);
#endif
    for (Index q = end - 1; q >= begin; --q) backward_row(order ? order[q] : q, w);
  }

  /// @brief Row i of the forward substitution L z = w: z_i = (w_i - sum_{j<i} L(i, j) z_j) /
  /// L(i, i). Rows must be done in order 0, 1, ..., n - 1; row i of w must be complete (every
  /// addition to it done) when it is; rows below i are not touched.
  void forward_row(Index i, Scalar* w) const {
    const Index first = row_outer[i];
    solve_row<1>(i, row_inner + first, row_value + first, row_outer[i + 1] - first, w);
  }

  /// @brief The forward substitution L z = w in place.
  void forward(Scalar* w) const { forward_rows(nullptr, 0, n, w); }

  /// @brief Row j of the back substitution L^T u = z: u_j = (z_j - sum_{i>j} L(i, j) u_i) /
  /// L(j, j), a gather from the rows below, column j of L read from its last entry up. Rows must
  /// be done in order n - 1, ..., 0 (or any order that finishes every row i with L(i, j) != 0
  /// before j).
  void backward_row(Index j, Scalar* w) const {
    const Index last = outer[j + 1] - 1;  // the diagonal is at outer[j]
    solve_row<-1>(j, inner + last, value + last, last - outer[j], w);
  }

  /// @brief The back substitution L^T u = z in place.
  void backward(Scalar* w) const { backward_rows(nullptr, 0, n, w); }

  /// @brief w = (L L^T)^-1 w.
  void solve(Scalar* w) const {
    forward(w);
    backward(w);
  }

  /// @brief w = (L L^T)^-1 w on `parts` OpenMP threads along the schedule: each thread
  /// substitutes forward its part (a union of subtrees, which needs no other rows), one thread the
  /// top after a barrier, forward then back, and after a second barrier each thread its part
  /// back. The same operations as solve() in the same order within each row: the same result, bit
  /// for bit. Without OpenMP (or without a schedule) it is solve().
  void solve_parallel(Scalar* w) const {
#ifdef _OPENMP
    if (parts < 2) return solve(w);
#pragma omp parallel num_threads(parts)
    {
      const int t = omp_get_thread_num();
      const int threads = omp_get_num_threads();  // fewer than asked: the parts are shared out
      for (int part = t; part < parts; part += threads)
        forward_rows(schedule, part_start[part], part_start[part + 1], w);
#pragma omp barrier
#pragma omp single
      {
        forward_rows(schedule, part_start[parts], n, w);
        backward_rows(schedule, part_start[parts], n, w);
      }  // (an implied barrier)
      for (int part = t; part < parts; part += threads)
        backward_rows(schedule, part_start[part], part_start[part + 1], w);
    }
#else
    solve(w);
#endif
  }

 private:
  // w_r = (w_r - sum_k l[k * Step] w_{idx[k * Step]}) / L(r, r) over k = 0 .. count - 1 (Step +1:
  // the entries read upward, -1: downward), the sum split over two accumulator sets (even and
  // odd k) so that the additions do not form one chain of dependent latencies.
  template <int Step>
  void solve_row(Index r, const Index* idx, const Scalar* l, Index count, Scalar* w) const {
    Scalar s0 = w[3 * r], s1 = w[3 * r + 1], s2 = w[3 * r + 2];
    Scalar t0 = 0, t1 = 0, t2 = 0;
    for (; count >= 2; count -= 2, idx += 2 * Step, l += 2 * Step) {
      const Scalar* wa = w + 3 * idx[0];
      const Scalar* wb = w + 3 * idx[Step];
      const Scalar la = l[0], lb = l[Step];
      s0 -= la * wa[0], s1 -= la * wa[1], s2 -= la * wa[2];
      t0 += lb * wb[0], t1 += lb * wb[1], t2 += lb * wb[2];
    }
    if (count == 1) {
      const Scalar* wa = w + 3 * idx[0];
      const Scalar la = l[0];
      s0 -= la * wa[0], s1 -= la * wa[1], s2 -= la * wa[2];
    }
    const Scalar inv = inv_diag[r];
    w[3 * r] = (s0 - t0) * inv;
    w[3 * r + 1] = (s1 - t1) * inv;
    w[3 * r + 2] = (s2 - t2) * inv;
  }
};

/// @brief What LowerFactor needs beyond the column-compressed factor: the inverse diagonal and the
/// row-compressed strict lower part (a second copy of the off-diagonal entries, built once).
template <class Scalar>
struct LowerFactorRows {
  std::vector<Scalar> inv_diag;
  std::vector<int> outer, inner;
  std::vector<Scalar> value;

  /// @brief From L's column-compressed arrays (diagonal first in each column). Allocates.
  /// @return false when a diagonal entry is missing, not first, or its inverse is not finite.
  bool build(int n, const int* col_outer, const int* col_inner, const Scalar* col_value) {
    inv_diag.assign(std::size_t(n), Scalar(0));
    outer.assign(std::size_t(n) + 1, 0);
    for (int j = 0; j < n; ++j) {
      const int first = col_outer[j];
      if (first >= col_outer[j + 1] || col_inner[first] != j) return false;
      inv_diag[std::size_t(j)] = Scalar(1) / col_value[first];
      if (!std::isfinite(double(inv_diag[std::size_t(j)]))) return false;
      for (int p = first + 1; p < col_outer[j + 1]; ++p) ++outer[std::size_t(col_inner[p]) + 1];
    }
    for (int i = 0; i < n; ++i) outer[std::size_t(i) + 1] += outer[std::size_t(i)];
    inner.resize(std::size_t(outer[std::size_t(n)]));
    value.resize(inner.size());
    std::vector<int> next(outer.begin(), outer.end() - 1);
    for (int j = 0; j < n; ++j)  // columns in order: each row's column indices come out ascending
      for (int p = col_outer[j] + 1; p < col_outer[j + 1]; ++p) {
        const auto q = std::size_t(next[std::size_t(col_inner[p])]++);
        inner[q] = j;
        value[q] = col_value[p];
      }
    return true;
  }

  std::vector<int> schedule, part_start;  // see LowerFactor::schedule; empty: none

  /// False: view() never selects the AVX2 rows (for comparisons; default true).
  bool simd = true;

  /// @brief Splits the rows over `parts` threads (>= 2) along the elimination tree of L (column
  /// j's parent is the row of its first off-diagonal entry): the tree is opened from its roots,
  /// always at the subtree of most entries, the open subtrees are dealt to the parts
  /// largest-first, each to the part with the fewest entries so far (LPT), and of these splits the
  /// one whose top plus largest part has the fewest entries is kept. Cost O(n) per split tried,
  /// at most 256 tried (opening a chain node is not a try); allocates. Call after build() with
  /// the same arrays.
  void plan_threads(int parts, int n, const int* col_outer, const int* col_inner) {
    schedule.clear();
    part_start.clear();
    if (parts < 2 || n < 2) return;
    const auto un = std::size_t(n);
    std::vector<int> parent(un, -1);
    std::vector<double> work(un), subtree(un);
    for (int j = 0; j < n; ++j) {
      if (col_outer[j + 1] - col_outer[j] > 1) parent[std::size_t(j)] = col_inner[col_outer[j] + 1];
      work[std::size_t(j)] = subtree[std::size_t(j)] = double(col_outer[j + 1] - col_outer[j]);
    }
    for (int j = 0; j < n; ++j)  // a parent's index is above its children's
      if (parent[std::size_t(j)] >= 0)
        subtree[std::size_t(parent[std::size_t(j)])] += subtree[std::size_t(j)];
    std::vector<std::vector<int>> children(un);
    std::vector<int> open;  // roots of the open subtrees
    for (int j = 0; j < n; ++j)
      (parent[std::size_t(j)] >= 0 ? children[std::size_t(parent[std::size_t(j)])] : open)
          .push_back(j);
    // label: -1 top, else the part; decided for the open subtrees' roots by the best split.
    std::vector<int> label(un, -2), best_label;
    double top = 0, best = 0;
    const auto by_size = [&](int a, int b) {
      return subtree[std::size_t(a)] > subtree[std::size_t(b)];
    };
    // Opening a chain (one child) changes nothing to deal out: only splits with at least `parts`
    // open subtrees are evaluated, at most 256 of them.
    for (int tried = 0; tried < 256 && !open.empty();) {
      std::sort(open.begin(), open.end(), by_size);
      if (int(open.size()) >= parts) {
        ++tried;
        std::vector<double> load(std::size_t(parts), 0.0);
        std::vector<int> assign(open.size());
        for (std::size_t r = 0; r < open.size(); ++r) {
          const auto least = std::size_t(std::min_element(load.begin(), load.end()) - load.begin());
          load[least] += subtree[std::size_t(open[r])];
          assign[r] = int(least);
        }
        const double makespan = top + *std::max_element(load.begin(), load.end());
        if (best_label.empty() || makespan < best) {
          best = makespan;
          best_label = label;
          for (std::size_t r = 0; r < open.size(); ++r)
            best_label[std::size_t(open[r])] = assign[r];
        }
      }
      const int widest = open.front();  // open the subtree of most entries
      if (children[std::size_t(widest)].empty()) break;
      open.erase(open.begin());
      label[std::size_t(widest)] = -1;
      top += work[std::size_t(widest)];
      for (const int c : children[std::size_t(widest)]) open.push_back(c);
    }
    if (best_label.empty()) {  // a single chain: nothing to share, all in the top
      best_label.assign(un, -1);
    }
    for (int j = n - 1; j >= 0; --j)  // the rest of each subtree takes its root's label
      if (best_label[std::size_t(j)] == -2)
        best_label[std::size_t(j)] = best_label[std::size_t(parent[std::size_t(j)])];
    part_start.assign(std::size_t(parts) + 2, 0);
    for (int j = 0; j < n; ++j) {
      const int l = best_label[std::size_t(j)];
      ++part_start[std::size_t(l < 0 ? parts : l) + 1];
    }
    for (int t = 0; t <= parts; ++t) part_start[std::size_t(t) + 1] += part_start[std::size_t(t)];
    schedule.resize(std::size_t(n));
    std::vector<int> next(part_start.begin(), part_start.end() - 1);
    for (int j = 0; j < n; ++j) {
      const int l = best_label[std::size_t(j)];
      schedule[std::size_t(next[std::size_t(l < 0 ? parts : l)]++)] = j;
    }
  }

  /// @brief Bytes held (inverse diagonal, the row copy and the schedule).
  [[nodiscard]] std::size_t bytes() const {
    return inv_diag.size() * sizeof(Scalar) +
           (outer.size() + inner.size() + schedule.size() + part_start.size()) * sizeof(int) +
           value.size() * sizeof(Scalar);
  }

  /// @brief The view over these and the column-compressed arrays.
  [[nodiscard]] LowerFactor<Scalar, int> view(int n, const int* col_outer, const int* col_inner,
                                              const Scalar* col_value) const {
    LowerFactor<Scalar, int> v{
        n,           col_outer, col_inner, col_value, inv_diag.data(), outer.data(), inner.data(),
        value.data()};
#ifdef MASSSPRING_HAVE_SIMD_PATH
    v.simd = simd && cpu_has_avx2_fma();
#endif
    if (!part_start.empty()) {
      v.schedule = schedule.data();
      v.part_start = part_start.data();
      v.parts = int(part_start.size()) - 2;
    }
    return v;
  }
};

}  // namespace detail
}  // namespace massspring
