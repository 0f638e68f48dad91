#pragma once
/// @file
/// @brief storage_traits<Sparse, Scalar>: Eigen::SparseMatrix, Eigen::SimplicialLLT with a
/// fill-reducing ordering (AMD by default), and a fused n x 3 solve without allocation.

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "massspring/error.hpp"
#include "massspring/storage/nested_dissection.hpp"
#include "massspring/storage/tags.hpp"
#include "massspring/system/detail/validate.hpp"
#include "massspring/types.hpp"

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
/// the hardware prefetcher follows it. Each sum is split over two sets of accumulators, so that the
/// additions do not form one chain of dependent latencies. On the 2.6 GHz EPYC of the project's
/// measurements this halves the solve of a 256 x 256 cloth against a column-oriented (scatter)
/// forward substitution and a back substitution reading each column upward (see
/// docs/performance.md).
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

  /// @brief Row i of the forward substitution L z = w: z_i = (w_i - sum_{j<i} L(i, j) z_j) /
  /// L(i, i). Rows must be done in order 0, 1, ..., n - 1; row i of w must be complete (every
  /// addition to it done) when it is; rows below i are not touched.
  void forward_row(Index i, Scalar* w) const {
    const Index first = row_outer[i];
    solve_row<1>(i, row_inner + first, row_value + first, row_outer[i + 1] - first, w);
  }

  /// @brief The forward substitution L z = w in place.
  void forward(Scalar* w) const {
    for (Index i = 0; i < n; ++i) forward_row(i, w);
  }

  /// @brief Row j of the back substitution L^T u = z: u_j = (z_j - sum_{i>j} L(i, j) u_i) /
  /// L(j, j), a gather from the rows below, column j of L read from its last entry up. Rows must
  /// be done in order n - 1, ..., 0 (or any order that finishes every row i with L(i, j) != 0
  /// before j).
  void backward_row(Index j, Scalar* w) const {
    const Index last = outer[j + 1] - 1;  // the diagonal is at outer[j]
    solve_row<-1>(j, inner + last, value + last, last - outer[j], w);
  }

  /// @brief The back substitution L^T u = z in place.
  void backward(Scalar* w) const {
    for (Index j = n - 1; j >= 0; --j) backward_row(j, w);
  }

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
        for (Index q = part_start[part]; q < part_start[part + 1]; ++q) forward_row(schedule[q], w);
#pragma omp barrier
#pragma omp single
      {
        for (Index q = part_start[parts]; q < n; ++q) forward_row(schedule[q], w);
        for (Index q = n - 1; q >= part_start[parts]; --q) backward_row(schedule[q], w);
      }  // (an implied barrier)
      for (int part = t; part < parts; part += threads)
        for (Index q = part_start[part + 1] - 1; q >= part_start[part]; --q)
          backward_row(schedule[q], w);
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
    if (!part_start.empty()) {
      v.schedule = schedule.data();
      v.part_start = part_start.data();
      v.parts = int(part_start.size()) - 2;
    }
    return v;
  }
};

}  // namespace detail

/// @brief Sparse Cholesky factorisation P Q P^T = L L^T (Eigen::SimplicialLLT with a fill-reducing
/// ordering, AMD by default), solving for #rows by 3 right-hand sides.
///
/// Eigen's own `SimplicialLLT::solve` walks the factor once per column of the right-hand side and
/// allocates (the in-place permutation keeps a mask). Here the three columns are solved together in
/// one walk of L forward and one back, on a row-major array, allocating nothing:
/// - solve(b, x) permutes b into the factor's order, substitutes and permutes back;
/// - solve_in_place(w) substitutes only, for a w that is already in the factor's order (row
///   `permutation()[i]` of w is row i of Q's unknowns): the floor of a local-global iteration that
///   keeps its iterate in that order.
///
/// The elimination order is the Ordering's (Eigen's AMD by default) or one given to compute()
/// (e.g. nested_dissection(), storage/nested_dissection.hpp); either way Q is permuted here and
/// Eigen's SimplicialLLT factorises the result in its natural order.
///
/// @tparam Ordering_ an Eigen ordering (Eigen::AMDOrdering<int>, Eigen::COLAMDOrdering<int>,
/// Eigen::NaturalOrdering<int>, Eigen::MetisOrdering<int>)
template <class Scalar_, class Ordering_ = Eigen::AMDOrdering<int>>
class SparseCholesky {
 public:
  using Scalar = Scalar_;
  using Ordering = Ordering_;
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;
  /// @brief The factorisation of P Q P^T (already permuted: natural order).
  using Factorization = Eigen::SimplicialLLT<Matrix, Eigen::Lower, Eigen::NaturalOrdering<int>>;

  /// @brief The elimination order the Ordering gives Q (order[k]: Q's row eliminated k-th), as
  /// Eigen's SimplicialLLT computes it (on the full symmetric pattern of Q's lower triangle).
  [[nodiscard]] static std::vector<int> ordering_of(const Matrix& q) {
    const int n = int(q.rows());
    std::vector<int> order(static_cast<std::size_t>(n));
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    {
      Matrix full;
      full = q.template selfadjointView<Eigen::Lower>();
      Ordering()(full, inverse);
    }
    for (int k = 0; k < n; ++k)
      order[std::size_t(k)] = inverse.size() > 0 ? inverse.indices()(k) : k;
    return order;
  }

  /// @brief Symbolic analysis (ordering, pattern) and numeric factorisation of Q (lower triangle
  /// read), in the Ordering's order. Allocates; call it once per change of Q.
  /// @return false when Q is not numerically positive definite.
  bool compute(const Matrix& q) { return compute(q, ordering_of(q)); }

  /// @brief As compute(q), eliminating Q's rows in `order` (order[k]: the row eliminated k-th).
  /// @throws Error when `order` is not a permutation of Q's rows.
  bool compute(const Matrix& q, const std::vector<int>& order) {
    const std::vector<int> position = detail::inverse_order(order, int(q.rows()), "SparseCholesky");
    perm_ = Eigen::Map<const Eigen::VectorXi>(position.data(), Eigen::Index(position.size()));
    {
      Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p(perm_);
      Matrix permuted(q.rows(), q.cols());
      permuted.template selfadjointView<Eigen::Lower>() =
          q.template selfadjointView<Eigen::Lower>().twistedBy(p);
      llt_.compute(permuted);
    }
    work_.resize(q.rows(), 3);
    ok_ = llt_.info() == Eigen::Success;
    if (ok_) {
      const Matrix& l = factor();
      ok_ = rows_.build(int(l.cols()), l.outerIndexPtr(), l.innerIndexPtr(), l.valuePtr());
      if (ok_ && threads_ > 1)
        rows_.plan_threads(threads_, int(l.cols()), l.outerIndexPtr(), l.innerIndexPtr());
    }
    return ok_;
  }

  /// @brief True after a successful compute().
  [[nodiscard]] bool ok() const { return ok_; }
  /// @brief Order of the factorised matrix.
  [[nodiscard]] Eigen::Index rows() const { return work_.rows(); }
  /// @brief Stored entries of the factor L (diagonal included).
  [[nodiscard]] Eigen::Index factor_nonzeros() const { return factor().nonZeros(); }
  /// @brief Bytes the factor takes: Eigen's column-compressed L (values, row indices, column
  /// starts) plus the inverse diagonal and the row-compressed copy the substitutions read.
  [[nodiscard]] std::size_t factor_bytes() const {
    return std::size_t(factor_nonzeros()) * (sizeof(Scalar) + sizeof(int)) +
           std::size_t(rows() + 1) * sizeof(int) + rows_.bytes();
  }
  /// @brief The factor L of P Q P^T (column-compressed, lower, diagonal first in each column).
  [[nodiscard]] const Matrix& factor() const { return llt_.matrixL().nestedExpression(); }
  /// @brief The underlying Eigen factorisation, of P Q P^T (permutation() gives P).
  [[nodiscard]] const Factorization& factorization() const { return llt_; }
  /// @brief Row i of Q's unknowns is row permutation()[i] of the factor's order.
  [[nodiscard]] const Eigen::VectorXi& permutation() const { return perm_; }

  /// @brief w = (P Q P^T)^-1 w for a #rows by 3 row-major array in the factor's order
  /// (w[3 r + c], r = permutation()[i] for Q's row i). No allocation, no permutation.
  void solve_in_place(Scalar* w) const {
    if (threads_ > 1)
      lower().solve_parallel(w);
    else
      lower().solve(w);
  }

  /// @brief Threads the substitutions use (default 1). With t > 1 the rows are split along the
  /// elimination tree into t parts and a top (LowerFactorRows::plan_threads) and solve() runs on
  /// t OpenMP threads, with the same result bit for bit. Worth it only for large factors: see
  /// docs/performance.md for the measured crossover. Takes effect at once (plans the split when
  /// a factor is there) and is kept across compute().
  /// @throws Error for t < 1, or t > 1 when compiled without OpenMP (-fopenmp /
  /// OpenMP::OpenMP_CXX).
  void set_threads(int threads) {
    if (threads < 1)
      throw Error(detail::message("SparseCholesky: threads must be >= 1, got ", threads));
#ifndef _OPENMP
    if (threads > 1)
      throw Error(
          detail::message("SparseCholesky: threads = ", threads,
                          " needs OpenMP; compile with -fopenmp (link OpenMP::OpenMP_CXX)"));
#endif
    threads_ = threads;
    if (ok_) {
      const Matrix& l = factor();
      rows_.plan_threads(threads_, int(l.cols()), l.outerIndexPtr(), l.innerIndexPtr());
    }
  }
  /// @brief Threads the substitutions use (see set_threads()).
  [[nodiscard]] int threads() const { return threads_; }

  /// @brief L and its inverse diagonal, for substitutions fused with other work (see
  /// detail::LowerFactor). Valid until the next compute().
  [[nodiscard]] detail::LowerFactor<Scalar, int> lower() const {
    const Matrix& l = factor();
    return rows_.view(int(l.cols()), l.outerIndexPtr(), l.innerIndexPtr(), l.valuePtr());
  }

  /// @brief x = Q^-1 b for a #rows by 3 right-hand side. No allocation; b and x may be the same.
  void solve(const Eigen::Ref<const Points<Scalar>>& b, Eigen::Ref<Points<Scalar>> x) {
    const int n = int(rows());
    Scalar* w = work_.data();
    const int* perm = perm_.data();
    for (int i = 0; i < n; ++i) {
      const int r = perm[i];
      w[3 * r] = b(i, 0);
      w[3 * r + 1] = b(i, 1);
      w[3 * r + 2] = b(i, 2);
    }
    solve_in_place(w);
    for (int i = 0; i < n; ++i) {
      const int r = perm[i];
      x(i, 0) = w[3 * r];
      x(i, 1) = w[3 * r + 1];
      x(i, 2) = w[3 * r + 2];
    }
  }

 private:
  Factorization llt_;
  Eigen::VectorXi perm_;
  detail::LowerFactorRows<Scalar> rows_;
  Points<Scalar> work_;
  int threads_ = 1;
  bool ok_ = false;
};

template <class Scalar_>
struct storage_traits<Sparse, Scalar_> {
  using Scalar = Scalar_;
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;
  using Cholesky = SparseCholesky<Scalar>;
  using Triplet = Eigen::Triplet<Scalar, int>;

  /// @brief rows x cols compressed matrix whose entries are the sums of the triplets at each
  /// position.
  static Matrix from_triplets(Eigen::Index rows, Eigen::Index cols,
                              const std::vector<Triplet>& triplets) {
    Matrix result(rows, cols);
    result.setFromTriplets(triplets.begin(), triplets.end());
    return result;
  }
};

}  // namespace massspring
