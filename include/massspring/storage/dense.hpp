#pragma once
/// @file
/// @brief storage_traits<Dense, Scalar>: dense matrices, Eigen::LLT, an n x 3 solve without
/// allocation.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <vector>

#include "massspring/storage/tags.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Dense Cholesky factorization Q = L L^T of a symmetric positive definite matrix, solving
/// for #rows by 3 right-hand sides.
template <class Scalar_>
class DenseCholesky {
 public:
  using Scalar = Scalar_;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// @brief Factorizes Q (only its lower triangle is read). Allocates; call it once per change of
  /// Q.
  /// @return false when Q is not numerically positive definite.
  bool compute(const Matrix& q) {
    llt_.compute(q);
    work_.resize(q.rows(), 3);
    perm_ = Eigen::VectorXi::LinSpaced(q.rows(), 0, int(q.rows()) - 1);
    ok_ = llt_.info() == Eigen::Success;
    return ok_;
  }

  /// @brief True after a successful compute().
  [[nodiscard]] bool ok() const { return ok_; }
  /// @brief Order of the factorized matrix.
  [[nodiscard]] Eigen::Index rows() const { return work_.rows(); }
  /// @brief Stored entries of the factor L (the lower triangle, diagonal included).
  [[nodiscard]] Eigen::Index factor_nonzeros() const { return rows() * (rows() + 1) / 2; }

  /// @brief The identity: a dense factor is not reordered (the interface of SparseCholesky).
  [[nodiscard]] const Eigen::VectorXi& permutation() const { return perm_; }
  /// @brief Bytes the factor takes (the whole n x n matrix).
  [[nodiscard]] std::size_t factor_bytes() const {
    return std::size_t(rows()) * std::size_t(rows()) * sizeof(Scalar);
  }

  /// @brief w = Q^-1 w for a #rows by 3 row-major array (w[3 r + c]). No allocation.
  void solve_in_place(Scalar* w) {
    Eigen::Map<Points<Scalar>> rows3(w, rows(), 3);
    solve(rows3, rows3);
  }

  /// @brief x = Q^-1 b for a #rows by 3 right-hand side. No allocation; b and x may be the same.
  /// One forward and one back substitution per column.
  void solve(const Eigen::Ref<const Points<Scalar>>& b, Eigen::Ref<Points<Scalar>> x) {
    work_ = b;
    for (Eigen::Index c = 0; c < 3; ++c) {
      auto column = work_.col(c);
      llt_.matrixL().solveInPlace(column);
      llt_.matrixU().solveInPlace(column);
    }
    x = work_;
  }

 private:
  Eigen::LLT<Matrix, Eigen::Lower> llt_;
  Eigen::Matrix<Scalar, Eigen::Dynamic, 3> work_;  // column-major: each column is contiguous
  Eigen::VectorXi perm_;
  bool ok_ = false;
};

template <class Scalar_>
struct storage_traits<Dense, Scalar_> {
  using Scalar = Scalar_;
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Cholesky = DenseCholesky<Scalar>;
  using Triplet = Eigen::Triplet<Scalar, int>;

  /// @brief rows x cols matrix whose entries are the sums of the triplets at each position.
  static Matrix from_triplets(Eigen::Index rows, Eigen::Index cols,
                              const std::vector<Triplet>& triplets) {
    Matrix result = Matrix::Zero(rows, cols);
    for (const Triplet& t : triplets) result(t.row(), t.col()) += t.value();
    return result;
  }
};

}  // namespace massspring
