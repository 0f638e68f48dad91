#pragma once
/// @file
/// @brief LinearSolver<Storage, Scalar>: the general linear solve implicit integrators need for
/// their 3n x 3n systems A dx = b, through the storage policy: Cholesky first, a pivoting fallback
/// when A is indefinite or not symmetric.
///
/// - Dense: Eigen::LLT; when it fails, Eigen::LDLT (symmetric indefinite, pivoting); for a
///   non-symmetric A, Eigen::PartialPivLU.
/// - Sparse: Eigen::SimplicialLLT (AMD ordering, pattern analysed once); when it fails,
///   Eigen::SimplicialLDLT on the same pattern (symmetric indefinite, no pivoting: accepted when no
///   pivot of D is zero), then Eigen::SparseLU (COLAMD ordering), which is also the path for a
///   non-symmetric A.
///
/// factorize(a, symmetric, fallback = false) stops after a failed Cholesky: Newton's method uses
/// that to replace an indefinite A by its definite projection instead of paying for the fallback.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <limits>

#include "massspring/storage/tags.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Which factorization the last factorize() used.
enum class LinearSolverPath {
  None,          ///< nothing factorized yet, or the factorization failed
  Cholesky,      ///< A was symmetric positive definite
  Indefinite,    ///< Cholesky failed: the symmetric indefinite fallback (Dense LDLT, Sparse LDLT)
  IndefiniteLU,  ///< Sparse only: LDLT failed too (a zero pivot), so LU
  General,       ///< A was declared not symmetric: LU
};

namespace detail {
/// @brief x = A^-1 b with the factorization `path` names (NaN when none succeeded): the one
/// dispatch both storages share.
template <class Llt, class Ldlt, class Lu, class B, class X>
void solve_on_path(LinearSolverPath path, const Llt& llt, const Ldlt& ldlt, const Lu& lu,
                   const B& b, X& x) {
  switch (path) {
    case LinearSolverPath::Cholesky:
      x = llt.solve(b);
      break;
    case LinearSolverPath::Indefinite:
      x = ldlt.solve(b);
      break;
    case LinearSolverPath::IndefiniteLU:
    case LinearSolverPath::General:
      x = lu.solve(b);
      break;
    case LinearSolverPath::None:
      x.setConstant(std::numeric_limits<typename X::Scalar>::quiet_NaN());
      break;
  }
}
}  // namespace detail

template <class Storage, class Scalar>
class LinearSolver;

/// @brief Dense: LLT, then LDLT, or PartialPivLU for non-symmetric matrices.
template <class Scalar>
class LinearSolver<Dense, Scalar> {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  /// @brief Prepares for matrices of A's size (allocates the factor storage). The factorizations
  /// are computed once on the identity of that size: Eigen's size constructors leave their info
  /// uninitialised, and copying such an object reads it (UBSan: an invalid ComputationInfo).
  void analyze(const Matrix& a) {
    const Matrix identity = Matrix::Identity(a.rows(), a.rows());
    llt_.compute(identity);
    ldlt_.compute(identity);
    lu_.compute(identity);
  }
  /// @brief Factorizes A. @return false when no factorization succeeded.
  bool factorize(const Matrix& a, bool symmetric, bool fallback = true) {
    path_ = LinearSolverPath::None;
    if (!symmetric) {
      lu_.compute(a);
      const bool ok = lu_.matrixLU().diagonal().array().abs().minCoeff() > 0;
      if (ok) path_ = LinearSolverPath::General;
      return ok;
    }
    llt_.compute(a);
    if (llt_.info() == Eigen::Success) {
      path_ = LinearSolverPath::Cholesky;
      return true;
    }
    if (!fallback) return false;
    ldlt_.compute(a);
    if (ldlt_.info() == Eigen::Success && ldlt_.vectorD().array().abs().minCoeff() > 0) {
      path_ = LinearSolverPath::Indefinite;
      return true;
    }
    return false;
  }
  /// @brief x = A^-1 b after a successful factorize().
  template <class B, class X>
  void solve(const B& b, X& x) const {
    detail::solve_on_path(path_, llt_, ldlt_, lu_, b, x);
  }
  [[nodiscard]] LinearSolverPath path() const { return path_; }

 private:
  Eigen::LLT<Matrix> llt_;
  Eigen::LDLT<Matrix> ldlt_;
  Eigen::PartialPivLU<Matrix> lu_;
  LinearSolverPath path_ = LinearSolverPath::None;
};

/// @brief Sparse: SimplicialLLT (pattern analysed once), SparseLU as the fallback.
template <class Scalar>
class LinearSolver<Sparse, Scalar> {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;

  /// @brief Symbolic analysis of A's pattern; call again when the pattern changes.
  void analyze(const Matrix& a) {
    llt_.analyzePattern(a);
    ldlt_analyzed_ = false;
    lu_analyzed_ = false;
  }
  /// @brief Factorizes A (same pattern as analysed). @return false when nothing succeeded.
  bool factorize(const Matrix& a, bool symmetric, bool fallback = true) {
    path_ = LinearSolverPath::None;
    if (symmetric) {
      llt_.factorize(a);
      if (llt_.info() == Eigen::Success) {
        path_ = LinearSolverPath::Cholesky;
        return true;
      }
      if (!fallback) return false;
      if (!ldlt_analyzed_) {
        ldlt_.analyzePattern(a);
        ldlt_analyzed_ = true;
      }
      ldlt_.factorize(a);
      if (ldlt_.info() == Eigen::Success && ldlt_.vectorD().array().abs().minCoeff() > 0) {
        path_ = LinearSolverPath::Indefinite;
        return true;
      }
    }
    if (!lu_analyzed_) {
      lu_.analyzePattern(a);
      lu_analyzed_ = true;
    }
    lu_.factorize(a);
    if (lu_.info() != Eigen::Success) return false;
    path_ = symmetric ? LinearSolverPath::IndefiniteLU : LinearSolverPath::General;
    return true;
  }
  /// @brief x = A^-1 b after a successful factorize().
  template <class B, class X>
  void solve(const B& b, X& x) const {
    detail::solve_on_path(path_, llt_, ldlt_, lu_, b, x);
  }
  [[nodiscard]] LinearSolverPath path() const { return path_; }

 private:
  Eigen::SimplicialLLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> llt_;
  Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt_;
  Eigen::SparseLU<Matrix, Eigen::COLAMDOrdering<int>> lu_;
  bool ldlt_analyzed_ = false, lu_analyzed_ = false;
  LinearSolverPath path_ = LinearSolverPath::None;
};

}  // namespace massspring
