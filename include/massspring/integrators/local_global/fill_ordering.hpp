#pragma once
/// @file
/// @brief factorize_in_order(): Q's Cholesky factorization in the elimination order
/// FastMassSpringOptions::ordering asks for (FillOrdering): the Cholesky type's own, geometric
/// nested dissection of the rest positions, or (Auto) whichever of the two gives the factor fewer
/// nonzeros, both counted symbolically before factorizing.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "massspring/integrators/local_global/options.hpp"
#include "massspring/storage/cholesky_concept.hpp"
#include "massspring/storage/nested_dissection.hpp"

namespace massspring::local_global {

/// @brief Factorizes q (Q over the unknowns) with llt; row r of q belongs to the point
/// free[r], whose rest position (a row of rest_positions [m]) places it for nested dissection.
/// A Cholesky type without compute(matrix, order) always uses its own order. Returns llt's result
/// (false: q is not numerically positive definite). Allocates.
template <class Cholesky, class Matrix, class RestPositions>
bool factorize_in_order(Cholesky& llt, const Matrix& q, FillOrdering ordering,
                        const RestPositions& rest_positions, const std::vector<int>& free) {
  if constexpr (cholesky_has_ordered_compute<Cholesky, Matrix>::value) {
    if (ordering != FillOrdering::Solver) {
      const Eigen::Index nr = q.rows();
      Eigen::Matrix<double, Eigen::Dynamic, 3> xyz(nr, 3);
      for (Eigen::Index r = 0; r < nr; ++r)
        xyz.row(r) = rest_positions.row(free[std::size_t(r)]).template cast<double>();
      const Graph graph = graph_of(q);
      std::size_t dissected = 0;  // nnz(L) in that order
      std::vector<int> order = nested_dissection(xyz, graph, {}, &dissected);
      if (ordering == FillOrdering::Auto) {
        std::vector<int> own = Cholesky::ordering_of(q);
        if (cholesky_nonzeros(graph, own) <= dissected) order.swap(own);
      }
      return llt.compute(q, order);
    }
  }
  (void)ordering;
  (void)rest_positions;
  (void)free;
  return llt.compute(q);
}

}  // namespace massspring::local_global
