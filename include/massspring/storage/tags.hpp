#pragma once
/// @file
/// @brief Storage policies: empty tags that choose the matrix and Cholesky types of a system.
///
/// `MassSpringSystem<Scalar, Dense>` keeps its matrices as dense Eigen matrices and factorizes with
/// `Eigen::LLT`; `MassSpringSystem<Scalar, Sparse>` keeps them as `Eigen::SparseMatrix` and
/// factorizes with `Eigen::SimplicialLLT` (AMD ordering). Dense is for small systems (a few hundred
/// points) and as an independent check of Sparse; Sparse is the default choice.

namespace massspring {

/// @brief Dense storage: `Eigen::Matrix` and `Eigen::LLT`. Memory and factorization grow as n^2,
/// n^3.
struct Dense {};
/// @brief Sparse storage: `Eigen::SparseMatrix` and `Eigen::SimplicialLLT` with AMD ordering.
struct Sparse {};

/// @brief Traits of a storage policy; specialised per tag in storage/dense.hpp and
/// storage/sparse.hpp.
///
/// Each specialisation provides
/// - `Matrix`: the matrix type;
/// - `Cholesky`: a factorization of Q with the members storage/cholesky_concept.hpp lists
///   (compute, permutation, solve_in_place, factor_nonzeros), and `solve(b, x)` for #rows by 3
///   right-hand sides without allocation;
/// - `static Matrix from_triplets(rows, cols, triplets)`: duplicates are summed.
template <class Storage, class Scalar>
struct storage_traits;

/// @brief True for the storage tags this library knows.
template <class Storage>
inline constexpr bool is_storage_v = false;
template <>
inline constexpr bool is_storage_v<Dense> = true;
template <>
inline constexpr bool is_storage_v<Sparse> = true;

}  // namespace massspring
