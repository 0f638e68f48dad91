#pragma once
/// @file
/// @brief The contact term that FastMassSpring and BackwardEuler put inside their solves
/// (local_global/contact_projection.hpp describes it: the alternating direction method of
/// multipliers, Boyd et al. 2011, section 3.1.1): contact_weights(), its weight per point, and
/// contact_dual_update(), one point's local step.

#include <Eigen/Core>
#include <cmath>

#include "massspring/contact/colliders/collider_set.hpp"
#include "massspring/types.hpp"

namespace massspring::detail {

/// @brief The contact term's weight of each point, w_i = alpha sqrt(m_i (m_i + h2 k_i)) [kg]
/// (h2 = dt^2 [s^2], k_i the summed stiffness of point i's springs [N/m]), into `w` (resized to
/// the points). It is the geometric mean of the smallest and largest curvature the step's
/// objective can have at the point, times dt^2 (its inertia alone, and with its springs): the
/// sqrt(lambda_min lambda_max) penalty of Ghadimi et al. 2015 ("Optimal parameter selection for
/// the alternating direction method of multipliers (ADMM): quadratic problems", IEEE Transactions
/// on Automatic Control 60(3)), which balances ADMM's two residuals. A lone point gets alpha m_i;
/// a cloth point at a large step many times its mass. Allocates only when `w` is resized.
template <class System, class Scalar>
void contact_weights(const System& system, Scalar alpha, Scalar h2, Vector<Scalar>& w) {
  w.setZero(system.num_points());
  const auto& springs = system.springs();
  for (Eigen::Index e = 0; e < springs.rows(); ++e)
    for (int end = 0; end < 2; ++end) w(springs(e, end)) += system.stiffness()(e);
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    const Scalar m = system.masses()(i);
    w(i) = alpha * std::sqrt(m * (m + h2 * w(i)));
  }
}

/// @brief At the iterate x of one point (3 coordinates [m]), with its scaled dual variable u [m]
/// and its start-of-step position x_start: z = P(x + u), P the colliders' position response
/// (ColliderSet::project; begin_step(dt) called), then u <- x + u - z. Writes the point the term
/// pulls x towards, target = z - u, and returns true when the point touches a collider; otherwise
/// (P moved nothing) u = 0, target = x, and returns false. `clearance2` [m^2]: the square of
/// ColliderSet::clearance(x_start) when positive, else 0; a z closer than that to x_start is
/// not projected (P would not move it).
template <class Scalar>
bool contact_dual_update(const contact::ColliderSet<Scalar>& colliders, const Scalar* x_start,
                         const Scalar* x, Scalar* u, Scalar dt, Scalar* target,
                         Scalar clearance2 = 0) {
  Scalar z[3] = {x[0] + u[0], x[1] + u[1], x[2] + u[2]};
  const Scalar moved[3] = {z[0], z[1], z[2]};
  const Scalar d[3] = {z[0] - x_start[0], z[1] - x_start[1], z[2] - x_start[2]};
  if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < clearance2)) colliders.project(x_start, z, dt);
  if (z[0] == moved[0] && z[1] == moved[1] && z[2] == moved[2]) {
    for (int c = 0; c < 3; ++c) {
      u[c] = 0;
      target[c] = x[c];
    }
    return false;
  }
  for (int c = 0; c < 3; ++c) {
    u[c] = moved[c] - z[c];
    target[c] = z[c] - u[c];
  }
  return true;
}

}  // namespace massspring::detail
