#pragma once
/// @file
/// @brief Error metrics of the accuracy benchmark (docs/benchmarks.md): trajectory error, the
/// step error of an implicit solver, energy drift.

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/evaluate.hpp"

namespace massspring {

/// @brief The length of the diagonal of the axis-aligned bounding box of `x` [m] (0 when x has
/// no rows).
template <class Derived>
double bounding_box_diagonal(const Eigen::MatrixBase<Derived>& x) {
  if (x.rows() == 0) return 0;
  return double((x.colwise().maxCoeff() - x.colwise().minCoeff()).norm());
}

/// @brief Trajectory error: the RMS distance between corresponding points of x and the
/// reference, divided by `diagonal` (the scene's bounding-box diagonal) [dimensionless].
/// @throws Error when the shapes differ or diagonal is not finite and > 0.
template <class A, class B>
double trajectory_error(const Eigen::MatrixBase<A>& x, const Eigen::MatrixBase<B>& reference,
                        double diagonal) {
  if (x.rows() != reference.rows() || x.cols() != reference.cols())
    throw Error(detail::message("trajectory_error: ", x.rows(), " points against a reference of ",
                                reference.rows()));
  detail::require_number("trajectory_error", "diagonal", diagonal, true);
  if (x.rows() == 0) return 0;
  const double sum =
      (x.template cast<double>() - reference.template cast<double>()).rowwise().squaredNorm().sum();
  return std::sqrt(sum / double(x.rows())) / diagonal;
}

/// @brief The objective that one backward-Euler step minimises, at positions x:
///
///     E(x) = 1/(2 h^2) sum_i m_i |x_i - x^t_i - h v^t_i|^2 + V(x) + sum beta/(2h) |x_i - x^t_i|^2
///
/// (V: the potential energy of every force that has one; the last term for each LinearDrag,
/// whose sum of beta is folded in). Local-global and Newton backward Euler both minimise it (up to
/// the pinned points, which stay at their targets), so step_error() compares their iterates with
/// it. [J]
template <class System>
double incremental_potential(const System& system, const typename System::PointsType& x,
                             const typename System::PointsType& x_start,
                             const typename System::PointsType& v_start, double h) {
  detail::require_number("incremental_potential", "h", h, true);
  double beta = 0;
  for (const auto& term : system.forces())
    if (term->linear_damping) beta += double(term->linear_damping_coefficient());
  double inertia = 0, drag = 0;
  for (int i = 0; i < system.num_points(); ++i) {
    const Eigen::RowVector3d dx = (x.row(i) - x_start.row(i)).template cast<double>();
    const Eigen::RowVector3d d = dx - h * v_start.row(i).template cast<double>();
    inertia += double(system.masses()(i)) * d.squaredNorm();
    drag += dx.squaredNorm();
  }
  return inertia / (2 * h * h) + double(potential_energy(system, x)) + beta / (2 * h) * drag;
}

/// @brief Relative step error of an iterate: (E(x_k) - E*) / (E(x_0) - E*), with E* the
/// objective at the converged solution. 0 at the solution, 1 at the starting iterate; NaN when
/// E(x_0) == E* (nothing to reduce).
inline double step_error(double e_k, double e_0, double e_star) {
  const double range = e_0 - e_star;
  if (range == 0) return std::numeric_limits<double>::quiet_NaN();
  return (e_k - e_star) / range;
}

/// @brief Energy drift: (E(T) - E(0)) / scale, where `scale` is the energy in motion (the
/// benchmark uses the largest kinetic energy of the reference run). Positive: energy gained.
inline double energy_drift(double e_end, double e_start, double scale) {
  detail::require_number("energy_drift", "scale", scale, true);
  return (e_end - e_start) / scale;
}

}  // namespace massspring
