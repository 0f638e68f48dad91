#pragma once
/// @file
/// @brief CholmodCholesky: Q factorized by SuiteSparse's CHOLMOD (supernodal, with its choice of
/// fill-reducing ordering, METIS included), then solved by massspring's own fused n x 3
/// substitution. Optional: needs libcholmod (target massspring::cholmod, which defines
/// MASSSPRING_HAS_CHOLMOD); the core never includes this header.
///
/// Use it as FastMassSpring's second template argument:
///   massspring::FastMassSpring<System, massspring::CholmodCholesky<double>> solver;
///
/// CHOLMOD factorizes in double whatever the Scalar (SuiteSparse 5 has no single precision); the
/// factor is converted to a simplicial L L^T and copied into Scalar arrays, so that every iteration
/// runs the same allocation-free substitution as SparseCholesky.

#include <cholmod.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <string>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/storage/sparse.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief The fill-reducing ordering CHOLMOD uses.
enum class CholmodOrdering {
  Default,  ///< CHOLMOD's own choice: AMD, and METIS when AMD's fill is high; the best kept
  AMD,      ///< approximate minimum degree only
  METIS,    ///< METIS nested dissection only
  NESDIS,   ///< CHOLMOD's nested dissection (METIS plus constrained minimum degree)
  Natural,  ///< no reordering (not even a postorder of the elimination tree)
};

/// @brief Sparse Cholesky by CHOLMOD, solved by massspring's fused substitution (see the file).
template <class Scalar_>
class CholmodCholesky {
 public:
  using Scalar = Scalar_;
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;

  /// @brief The ordering of the next compute() (default: CHOLMOD's own choice).
  CholmodOrdering ordering = CholmodOrdering::Default;

  /// @brief Starts CHOLMOD with its printing off: a failure is compute()'s return value, not a
  /// line on stderr.
  CholmodCholesky() {
    cholmod_start(&common_);
    common_.print = 0;
  }
  ~CholmodCholesky() {
    free_factor();
    cholmod_finish(&common_);
  }
  CholmodCholesky(const CholmodCholesky&) = delete;
  CholmodCholesky& operator=(const CholmodCholesky&) = delete;

  /// @brief Orders, factorizes (supernodal) and converts the factor of Q (lower triangle read).
  /// Allocates. @return false when Q is not numerically positive definite.
  bool compute(const Matrix& q) {
    free_factor();
    ok_ = false;
    const auto n = std::size_t(q.rows());
    // The lower triangle of Q as a CHOLMOD matrix (double, stype -1).
    Eigen::SparseMatrix<double, Eigen::ColMajor, int> lower =
        q.template cast<double>().template triangularView<Eigen::Lower>();
    lower.makeCompressed();
    cholmod_sparse a{};
    a.nrow = a.ncol = n;
    a.nzmax = std::size_t(lower.nonZeros());
    a.p = lower.outerIndexPtr();
    a.i = lower.innerIndexPtr();
    a.x = lower.valuePtr();
    a.stype = -1;
    a.itype = CHOLMOD_INT;
    a.xtype = CHOLMOD_REAL;
    a.dtype = CHOLMOD_DOUBLE;
    a.sorted = 1;
    a.packed = 1;
    configure();
    factor_ = cholmod_analyze(&a, &common_);
    if (factor_ == nullptr) return false;
    cholmod_factorize(&a, factor_, &common_);
    if (common_.status != CHOLMOD_OK || factor_->minor < n) return false;
    analysed_ordering_ = factor_->ordering;
    // Simplicial, L L^T, packed: column j holds its diagonal first.
    if (!cholmod_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, factor_, &common_)) return false;
    const int* p = static_cast<const int*>(factor_->p);
    const int* i = static_cast<const int*>(factor_->i);
    const double* x = static_cast<const double*>(factor_->x);
    const int* perm = static_cast<const int*>(factor_->Perm);
    outer_.assign(p, p + n + 1);
    inner_.assign(i, i + p[n]);
    value_.resize(std::size_t(p[n]));
    for (std::size_t k = 0; k < std::size_t(p[n]); ++k) value_[k] = Scalar(x[k]);
    // false when a column does not hold its diagonal first
    if (!rows_.build(int(n), outer_.data(), inner_.data(), value_.data())) return false;
    perm_.resize(Eigen::Index(n));
    for (std::size_t k = 0; k < n; ++k) perm_(perm[k]) = int(k);
    work_.resize(Eigen::Index(n), 3);
    free_factor();  // the copy above is all the solve needs
    ok_ = true;
    return true;
  }

  /// @brief True after a successful compute().
  [[nodiscard]] bool ok() const { return ok_; }
  /// @brief Order of the factorized matrix.
  [[nodiscard]] Eigen::Index rows() const { return work_.rows(); }
  /// @brief Stored entries of the factor L (diagonal included).
  [[nodiscard]] Eigen::Index factor_nonzeros() const { return Eigen::Index(inner_.size()); }
  /// @brief Bytes the factor takes: the column-compressed L (values, row indices, column starts)
  /// plus the inverse diagonal and the row-compressed copy the substitutions read.
  [[nodiscard]] std::size_t factor_bytes() const {
    return inner_.size() * (sizeof(Scalar) + sizeof(int)) + outer_.size() * sizeof(int) +
           rows_.bytes();
  }
  /// @brief Row i of Q's unknowns is row permutation()[i] of the factor's order.
  [[nodiscard]] const Eigen::VectorXi& permutation() const { return perm_; }
  /// @brief The ordering CHOLMOD chose (CHOLMOD_AMD, CHOLMOD_METIS, ...; see cholmod.h).
  [[nodiscard]] int chosen_ordering() const { return analysed_ordering_; }

  /// @brief Allow the AVX2 + FMA substitution (default true; see SparseCholesky::set_simd).
  void set_simd(bool allowed) { rows_.simd = allowed; }
  /// @brief True when solves use the AVX2 + FMA substitution.
  [[nodiscard]] bool simd() const { return lower().simd; }
  /// @brief L and its inverse diagonal (see detail::LowerFactor).
  [[nodiscard]] detail::LowerFactor<Scalar, int> lower() const {
    return rows_.view(int(rows()), outer_.data(), inner_.data(), value_.data());
  }
  /// @brief w = (P Q P^T)^-1 w, w row-major #rows x 3 in the factor's order. No allocation.
  void solve_in_place(Scalar* w) const { lower().solve(w); }
  /// @brief x = Q^-1 b for a #rows by 3 right-hand side. No allocation; b and x may be the same.
  void solve(const Eigen::Ref<const Points<Scalar>>& b, Eigen::Ref<Points<Scalar>> x) {
    const int n = int(rows());
    Scalar* w = work_.data();
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) w[3 * perm_(i) + c] = b(i, c);
    solve_in_place(w);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) x(i, c) = w[3 * perm_(i) + c];
  }

 private:
  void configure() {
    common_.supernodal = CHOLMOD_SUPERNODAL;
    common_.final_ll = 1;
    switch (ordering) {
      case CholmodOrdering::Default:
        common_.nmethods = 0;  // CHOLMOD's default strategy
        common_.postorder = 1;
        break;
      case CholmodOrdering::AMD:
        set_method(CHOLMOD_AMD);
        break;
      case CholmodOrdering::METIS:
        set_method(CHOLMOD_METIS);
        break;
      case CholmodOrdering::NESDIS:
        set_method(CHOLMOD_NESDIS);
        break;
      case CholmodOrdering::Natural:
        set_method(CHOLMOD_NATURAL);
        common_.postorder = 0;  // a postorder of the elimination tree would reorder the rows
        break;
    }
  }
  void set_method(int method) {
    common_.nmethods = 1;
    common_.method[0].ordering = method;
    common_.postorder = 1;
  }
  void free_factor() {
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    factor_ = nullptr;
  }

  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
  int analysed_ordering_ = -1;
  std::vector<int> outer_, inner_;
  std::vector<Scalar> value_;
  detail::LowerFactorRows<Scalar> rows_;
  Eigen::VectorXi perm_;
  Points<Scalar> work_;
  bool ok_ = false;
};

}  // namespace massspring
