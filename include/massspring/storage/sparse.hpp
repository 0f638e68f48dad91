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

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/storage/lower_factor.hpp"
#include "massspring/storage/nested_dissection.hpp"
#include "massspring/storage/tags.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Sparse Cholesky factorization P Q P^T = L L^T (Eigen::SimplicialLLT with a fill-reducing
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
/// Eigen's SimplicialLLT factorizes the result in its natural order.
///
/// @tparam Ordering_ an Eigen ordering (Eigen::AMDOrdering<int>, Eigen::COLAMDOrdering<int>,
/// Eigen::NaturalOrdering<int>, Eigen::MetisOrdering<int>)
template <class Scalar_, class Ordering_ = Eigen::AMDOrdering<int>>
class SparseCholesky {
 public:
  using Scalar = Scalar_;
  using Ordering = Ordering_;
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;
  /// @brief The factorization of P Q P^T (already permuted: natural order).
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

  /// @brief Symbolic analysis (ordering, pattern) and numeric factorization of Q (lower triangle
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
#ifdef _OPENMP  // threads_ > 1 needs OpenMP (set_threads)
      if (ok_ && threads_ > 1)
        rows_.plan_threads(threads_, int(l.cols()), l.outerIndexPtr(), l.innerIndexPtr());
#endif
    }
    return ok_;
  }

  /// @brief True after a successful compute().
  [[nodiscard]] bool ok() const { return ok_; }
  /// @brief Order of the factorized matrix.
  [[nodiscard]] Eigen::Index rows() const { return work_.rows(); }
  /// @brief Stored entries of the factor L (diagonal included).
  [[nodiscard]] Eigen::Index factor_nonzeros() const { return factor().nonZeros(); }
  /// @brief Bytes the factor takes: Eigen's column-compressed L (values, row indices, column
  /// starts) plus the inverse diagonal and the row-compressed copy the substitutions read
  /// (detail::LowerFactorRows).
  [[nodiscard]] std::size_t factor_bytes() const {
    return std::size_t(factor_nonzeros()) * (sizeof(Scalar) + sizeof(int)) +
           std::size_t(rows() + 1) * sizeof(int) + rows_.bytes();
  }
  /// @brief The factor L of P Q P^T (column-compressed, lower, diagonal first in each column).
  [[nodiscard]] const Matrix& factor() const { return llt_.matrixL().nestedExpression(); }
  /// @brief The underlying Eigen factorization, of P Q P^T (permutation() gives P).
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
#ifdef _OPENMP  // without OpenMP, threads is 1 here: nothing to plan
    if (ok_) {
      const Matrix& l = factor();
      rows_.plan_threads(threads_, int(l.cols()), l.outerIndexPtr(), l.innerIndexPtr());
    }
#endif
  }
  /// @brief Threads the substitutions use (see set_threads()).
  [[nodiscard]] int threads() const { return threads_; }

  /// @brief Allow the AVX2 + FMA substitution (default true; used when the CPU has AVX2 and FMA,
  /// see detail::LowerFactor::simd). false: the SSE2 one. Takes effect at once.
  void set_simd(bool allowed) { rows_.simd = allowed; }
  /// @brief True when solves use the AVX2 + FMA substitution (allowed, and the CPU has it).
  [[nodiscard]] bool simd() const { return lower().simd; }

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
