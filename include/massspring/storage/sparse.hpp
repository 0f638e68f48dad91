#pragma once
/// @file
/// @brief storage_traits<Sparse, Scalar>: Eigen::SparseMatrix, Eigen::SimplicialLLT with AMD
/// ordering, and a fused n x 3 solve without allocation.

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

#include "massspring/storage/tags.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Sparse Cholesky factorisation P Q P^T = L L^T (Eigen::SimplicialLLT, AMD ordering),
/// solving for #rows by 3 right-hand sides.
///
/// Eigen's own `SimplicialLLT::solve` walks the factor once per column of the right-hand side and
/// allocates (the in-place permutation keeps a mask). solve() here walks L once forward and once
/// backward for all three columns together, on a row-major work array, and allocates nothing.
template <class Scalar_>
class SparseCholesky {
 public:
  using Scalar = Scalar_;
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;
  using Factorization = Eigen::SimplicialLLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>>;

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
    }
    return ok_;
  }

  /// @brief True after a successful compute().
  [[nodiscard]] bool ok() const { return ok_; }
  /// @brief Order of the factorised matrix.
  [[nodiscard]] Eigen::Index rows() const { return work_.rows(); }
  /// @brief Stored entries of the factor L (diagonal included).
  [[nodiscard]] Eigen::Index factor_nonzeros() const { return factor().nonZeros(); }
  /// @brief The factor L of P Q P^T (column-compressed, lower, diagonal first in each column).
  [[nodiscard]] const Matrix& factor() const { return llt_.matrixL().nestedExpression(); }
  /// @brief The underlying Eigen factorisation.
  [[nodiscard]] const Factorization& factorization() const { return llt_; }

  /// @brief x = Q^-1 b for a #rows by 3 right-hand side. No allocation; b and x may be the same.
  void solve(const Eigen::Ref<const Points<Scalar>>& b, Eigen::Ref<Points<Scalar>> x) {
    const Matrix& l = factor();
    const int n = int(l.cols());
    const int* outer = l.outerIndexPtr();
    const int* inner = l.innerIndexPtr();
    const Scalar* value = l.valuePtr();
    Scalar* w = work_.data();
    const int* perm = perm_.data();
    for (int i = 0; i < n; ++i) {
      const int r = perm[i];
      w[3 * r] = b(i, 0);
      w[3 * r + 1] = b(i, 1);
      w[3 * r + 2] = b(i, 2);
    }
    // Forward: L z = w, column by column; the diagonal is the first entry of each column.
    for (int j = 0; j < n; ++j) {
      const Scalar inv = Scalar(1) / value[outer[j]];
      const Scalar z0 = w[3 * j] *= inv;
      const Scalar z1 = w[3 * j + 1] *= inv;
      const Scalar z2 = w[3 * j + 2] *= inv;
      for (int p = outer[j] + 1; p < outer[j + 1]; ++p) {
        Scalar* wi = w + 3 * inner[p];
        const Scalar lij = value[p];
        wi[0] -= lij * z0;
        wi[1] -= lij * z1;
        wi[2] -= lij * z2;
      }
    }
    // Backward: L^T u = z, each column of L is a row of L^T.
    for (int j = n - 1; j >= 0; --j) {
      Scalar s0 = w[3 * j], s1 = w[3 * j + 1], s2 = w[3 * j + 2];
      for (int p = outer[j] + 1; p < outer[j + 1]; ++p) {
        const Scalar* wi = w + 3 * inner[p];
        const Scalar lij = value[p];
        s0 -= lij * wi[0];
        s1 -= lij * wi[1];
        s2 -= lij * wi[2];
      }
      const Scalar inv = Scalar(1) / value[outer[j]];
      w[3 * j] = s0 * inv;
      w[3 * j + 1] = s1 * inv;
      w[3 * j + 2] = s2 * inv;
    }
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
