#pragma once
/// @file
/// @brief storage_traits<Sparse, Scalar>: Eigen::SparseMatrix, Eigen::SimplicialLLT with a
/// fill-reducing ordering (AMD by default), and a fused n x 3 solve without allocation.

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

#include "massspring/storage/tags.hpp"
#include "massspring/types.hpp"

namespace massspring {

namespace detail {

/// @brief A column-compressed lower factor L (diagonal first in each column) with its inverse
/// diagonal, and forward and back substitution for three right-hand sides stored row-major
/// (w[3 r + c]), in place: one walk of L forward and one back for all three columns.
template <class Scalar, class Index>
struct LowerFactor {
  Index n = 0;
  const Index* outer = nullptr;
  const Index* inner = nullptr;
  const Scalar* value = nullptr;
  const Scalar* inv_diag = nullptr;  // 1 / L(j, j)

  /// @brief Column j of the forward substitution L z = w: z_j = w_j / L(j, j), then
  /// w_i -= L(i, j) z_j below the diagonal. Columns must be done in order 0, 1, ..., n - 1; row j
  /// of w must be complete (every addition to it done) when column j is.
  void forward_column(Index j, Scalar* w) const {
    const Scalar inv = inv_diag[j];
    const Scalar z0 = w[3 * j] *= inv;
    const Scalar z1 = w[3 * j + 1] *= inv;
    const Scalar z2 = w[3 * j + 2] *= inv;
    for (Index p = outer[j] + 1; p < outer[j + 1]; ++p) {
      Scalar* wi = w + 3 * inner[p];
      const Scalar lij = value[p];
      wi[0] -= lij * z0;
      wi[1] -= lij * z1;
      wi[2] -= lij * z2;
    }
  }

  /// @brief The back substitution L^T u = z in place; column j of L is row j of L^T (a gather from
  /// the rows below).
  void backward(Scalar* w) const {
    for (Index j = n - 1; j >= 0; --j) {
      Scalar s0 = w[3 * j], s1 = w[3 * j + 1], s2 = w[3 * j + 2];
      for (Index p = outer[j] + 1; p < outer[j + 1]; ++p) {
        const Scalar* wi = w + 3 * inner[p];
        const Scalar lij = value[p];
        s0 -= lij * wi[0];
        s1 -= lij * wi[1];
        s2 -= lij * wi[2];
      }
      const Scalar inv = inv_diag[j];
      w[3 * j] = s0 * inv;
      w[3 * j + 1] = s1 * inv;
      w[3 * j + 2] = s2 * inv;
    }
  }

  /// @brief w = (L L^T)^-1 w.
  void solve(Scalar* w) const {
    for (Index j = 0; j < n; ++j) forward_column(j, w);
    backward(w);
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
/// @tparam Ordering_ an Eigen ordering (Eigen::AMDOrdering<int>, Eigen::COLAMDOrdering<int>,
/// Eigen::NaturalOrdering<int>, Eigen::MetisOrdering<int>)
template <class Scalar_, class Ordering_ = Eigen::AMDOrdering<int>>
class SparseCholesky {
 public:
  using Scalar = Scalar_;
  using Ordering = Ordering_;
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;
  using Factorization = Eigen::SimplicialLLT<Matrix, Eigen::Lower, Ordering>;

  /// @brief Symbolic analysis (ordering, pattern) and numeric factorisation of Q (lower triangle
  /// read). Allocates; call it once per change of Q.
  /// @return false when Q is not numerically positive definite.
  bool compute(const Matrix& q) {
    llt_.compute(q);
    work_.resize(q.rows(), 3);
    ok_ = llt_.info() == Eigen::Success;
    if (ok_) {
      const auto& p = llt_.permutationP();
      perm_ =
          p.size() > 0 ? p.indices() : Eigen::VectorXi::LinSpaced(q.rows(), 0, int(q.rows()) - 1);
      const Matrix& l = factor();
      inv_diag_.resize(l.cols());
      for (Eigen::Index j = 0; j < l.cols(); ++j)
        inv_diag_(j) = Scalar(1) / l.valuePtr()[l.outerIndexPtr()[j]];
      ok_ = inv_diag_.allFinite();
    }
    return ok_;
  }

  /// @brief True after a successful compute().
  [[nodiscard]] bool ok() const { return ok_; }
  /// @brief Order of the factorised matrix.
  [[nodiscard]] Eigen::Index rows() const { return work_.rows(); }
  /// @brief Stored entries of the factor L (diagonal included).
  [[nodiscard]] Eigen::Index factor_nonzeros() const { return factor().nonZeros(); }
  /// @brief Bytes the factor takes (values, row indices, column starts, inverse diagonal).
  [[nodiscard]] std::size_t factor_bytes() const {
    return std::size_t(factor_nonzeros()) * (sizeof(Scalar) + sizeof(int)) +
           std::size_t(rows() + 1) * sizeof(int) + std::size_t(rows()) * sizeof(Scalar);
  }
  /// @brief The factor L of P Q P^T (column-compressed, lower, diagonal first in each column).
  [[nodiscard]] const Matrix& factor() const { return llt_.matrixL().nestedExpression(); }
  /// @brief The underlying Eigen factorisation.
  [[nodiscard]] const Factorization& factorization() const { return llt_; }
  /// @brief Row i of Q's unknowns is row permutation()[i] of the factor's order.
  [[nodiscard]] const Eigen::VectorXi& permutation() const { return perm_; }

  /// @brief w = (P Q P^T)^-1 w for a #rows by 3 row-major array in the factor's order
  /// (w[3 r + c], r = permutation()[i] for Q's row i). No allocation, no permutation.
  void solve_in_place(Scalar* w) const { lower().solve(w); }

  /// @brief L and its inverse diagonal, for substitutions fused with other work (see
  /// detail::LowerFactor). Valid until the next compute().
  [[nodiscard]] detail::LowerFactor<Scalar, int> lower() const {
    const Matrix& l = factor();
    return {int(l.cols()), l.outerIndexPtr(), l.innerIndexPtr(), l.valuePtr(), inv_diag_.data()};
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
  Vector<Scalar> inv_diag_;
  Points<Scalar> work_;
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
