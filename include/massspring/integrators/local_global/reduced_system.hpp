#pragma once
/// @file
/// @brief local_global::ReducedSystem: the global step's linear system of FastMassSpring and the
/// numbering of its unknowns (the model is libigl's min_quad_with_fixed). With exact pins the
/// pinned points' rows and columns are eliminated: Q = A_F^T K A_F + M_F / dt^2 + (beta / dt) I
/// (+ the contact term's weights, W_F) over the free points F, and a spring joining a free point
/// to a pinned one moves k x_pinned to the right-hand side (-Q_FP X_P; PackedSprings::subtract_from
/// adds it). With penalty pins Q covers every point and adds w on the pinned points' diagonal
/// (Q += w C^T C, right-hand side += w C^T X_target).
///
/// Inside a step the iterate lives in the factor's row order (the fill-reducing permutation), as
/// a row-major #rows x 3 array: free points first, in the factor's order, then (exact pins) the
/// pinned points in the system's pinned() order.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "massspring/types.hpp"

namespace massspring::local_global {

template <class Scalar>
struct ReducedSystem {
  int n = 0;                      // points
  int nr = 0;                     // unknowns of Q (free points; every point with penalty pins)
  int nx = 0;                     // iterate rows (nr, then the pinned points with exact pins)
  std::vector<int> free;          // point of each of Q's rows, in the system's order
  std::vector<int> row, point;    // iterate row of each point, point of each iterate row
  std::vector<int> penalty_rows;  // iterate rows of the pinned points (penalty pins)

  /// @brief Numbers the unknowns and assembles Q from triplets (duplicates summed):
  /// A^T K A over the springs, then m_i / dt^2 + drag_diagonal + point_diagonal(i) on each
  /// unknown's diagonal (point_diagonal: the contact term's weights [N/m], one per point, or empty
  /// for none), then `weight` on each pinned point's diagonal (penalty pins). Allocates.
  template <class Traits, class System>
  typename Traits::Matrix assemble(const System& system, bool exact, Scalar inv_dt2,
                                   Scalar drag_diagonal, Scalar weight,
                                   const Vector<Scalar>& point_diagonal) {
    using Triplet = typename Traits::Triplet;
    n = system.num_points();
    const int m = system.num_springs();
    const auto& springs = system.springs();
    const auto& k = system.stiffness();
    const auto& mass = system.masses();
    std::vector<int> reduced(std::size_t(n), -1);  // Q's row of each point; -1 for exact pins
    free.clear();
    for (int i = 0; i < n; ++i)
      if (!(exact && system.is_pinned(i))) {
        reduced[std::size_t(i)] = int(free.size());
        free.push_back(i);
      }
    nr = int(free.size());

    std::vector<Triplet> t;
    t.reserve(std::size_t(4 * m + 2 * n));
    for (int e = 0; e < m; ++e) {
      const int ri = reduced[std::size_t(springs(e, 0))], rj = reduced[std::size_t(springs(e, 1))];
      if (ri >= 0) t.emplace_back(ri, ri, k(e));
      if (rj >= 0) t.emplace_back(rj, rj, k(e));
      if (ri >= 0 && rj >= 0) {
        t.emplace_back(ri, rj, -k(e));
        t.emplace_back(rj, ri, -k(e));
      }
    }
    for (int r = 0; r < nr; ++r) {
      const int i = free[std::size_t(r)];
      t.emplace_back(r, r, mass(i) * inv_dt2 + drag_diagonal);
      if (point_diagonal.size() > 0) t.emplace_back(r, r, point_diagonal(i));
    }
    if (!exact)
      for (int p : system.pinned()) t.emplace_back(p, p, weight);
    return Traits::from_triplets(nr, nr, t);
  }

  /// @brief The iterate's rows from the factor's permutation (Q's row r is factor row perm(r)).
  template <class System>
  void renumber(const System& system, const Eigen::VectorXi& perm, bool exact) {
    const int np = exact ? system.num_pinned() : 0;
    nx = nr + np;
    row.assign(std::size_t(n), 0);
    point.assign(std::size_t(nx), 0);
    for (int r = 0; r < nr; ++r) {
      row[std::size_t(free[std::size_t(r)])] = perm(r);
      point[std::size_t(perm(r))] = free[std::size_t(r)];
    }
    for (int p = 0; p < np; ++p) {
      const int i = system.pinned()[std::size_t(p)];
      row[std::size_t(i)] = nr + p;
      point[std::size_t(nr + p)] = i;
    }
    penalty_rows.clear();
    if (!exact)
      for (int p : system.pinned()) penalty_rows.push_back(row[std::size_t(p)]);
  }
};

}  // namespace massspring::local_global
