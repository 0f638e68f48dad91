#pragma once
/// @file
/// @brief What a factorization of Q must provide to serve a solver (FastMassSpring), written once:
/// detection traits for the required and the optional members, and require_cholesky(), whose
/// static_assert messages say what a user-supplied factorization is missing.
///
/// Required, for a #rows by 3 right-hand side stored row-major (w[3 r + c]) in the factor's
/// order (row permutation()[i] of w is row i of Q's unknowns):
/// - `bool compute(const Matrix& q)`: factorize P Q P^T = L L^T; false when Q is not numerically
///   positive definite;
/// - `const Eigen::VectorXi& permutation() const`;
/// - `void solve_in_place(Scalar* w)`: w = (P Q P^T)^-1 w, allocating nothing;
/// - `Eigen::Index factor_nonzeros() const`.
/// Optional, used when present:
/// - `bool compute(const Matrix& q, const std::vector<int>& order)` and
///   `static std::vector<int> ordering_of(const Matrix& q)`: a given elimination order
///   (FillOrdering::NestedDissection, FillOrdering::Auto);
/// - `void set_threads(int)`, `int threads() const`: substitutions on several threads;
/// - `void set_simd(bool)`: allow the SIMD substitution.
/// SparseCholesky, DenseCholesky and CholmodCholesky provide these.

#include <Eigen/Core>
#include <type_traits>
#include <utility>
#include <vector>

namespace massspring {

template <class C, class Matrix, class = void>
struct cholesky_has_compute : std::false_type {};
template <class C, class Matrix>
struct cholesky_has_compute<
    C, Matrix,
    std::void_t<decltype(bool(std::declval<C&>().compute(std::declval<const Matrix&>())))>>
    : std::true_type {};

template <class C, class = void>
struct cholesky_has_permutation : std::false_type {};
template <class C>
struct cholesky_has_permutation<
    C, std::enable_if_t<std::is_convertible_v<decltype(std::declval<const C&>().permutation()),
                                              const Eigen::VectorXi&>>> : std::true_type {};

template <class C, class Scalar, class = void>
struct cholesky_has_solve_in_place : std::false_type {};
template <class C, class Scalar>
struct cholesky_has_solve_in_place<
    C, Scalar, std::void_t<decltype(std::declval<C&>().solve_in_place(std::declval<Scalar*>()))>>
    : std::true_type {};

template <class C, class = void>
struct cholesky_has_factor_nonzeros : std::false_type {};
template <class C>
struct cholesky_has_factor_nonzeros<
    C, std::void_t<decltype(Eigen::Index(std::declval<const C&>().factor_nonzeros()))>>
    : std::true_type {};

/// @brief Has compute(q, order) (a given elimination order) and ordering_of(q).
template <class C, class Matrix, class = void>
struct cholesky_has_ordered_compute : std::false_type {};
template <class C, class Matrix>
struct cholesky_has_ordered_compute<
    C, Matrix,
    std::void_t<decltype(std::declval<C&>().compute(std::declval<const Matrix&>(),
                                                    std::declval<const std::vector<int>&>())),
                decltype(C::ordering_of(std::declval<const Matrix&>()))>> : std::true_type {};

/// @brief Has set_threads(int) and threads().
template <class C, class = void>
struct cholesky_has_threads : std::false_type {};
template <class C>
struct cholesky_has_threads<C, std::void_t<decltype(std::declval<C&>().set_threads(1)),
                                           decltype(std::declval<const C&>().threads())>>
    : std::true_type {};

/// @brief Has set_simd(bool).
template <class C, class = void>
struct cholesky_has_simd : std::false_type {};
template <class C>
struct cholesky_has_simd<C, std::void_t<decltype(std::declval<C&>().set_simd(true))>>
    : std::true_type {};

/// @brief Fails to compile, saying what is missing, unless C has the required members above.
template <class C, class Matrix, class Scalar>
constexpr bool require_cholesky() {
  static_assert(cholesky_has_compute<C, Matrix>::value,
                "massspring: the Cholesky type needs `bool compute(const Matrix& q)` (factorize "
                "P Q P^T = L L^T; false when Q is not positive definite)");
  static_assert(cholesky_has_permutation<C>::value,
                "massspring: the Cholesky type needs `const Eigen::VectorXi& permutation() const` "
                "(row permutation()[i] of a right-hand side is row i of Q)");
  static_assert(cholesky_has_solve_in_place<C, Scalar>::value,
                "massspring: the Cholesky type needs `void solve_in_place(Scalar* w)` (w = (P Q "
                "P^T)^-1 w for #rows x 3 values, row-major, allocating nothing)");
  static_assert(cholesky_has_factor_nonzeros<C>::value,
                "massspring: the Cholesky type needs `Eigen::Index factor_nonzeros() const`");
  return true;
}

}  // namespace massspring
