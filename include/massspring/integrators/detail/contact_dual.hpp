#pragma once
/// @file
/// @brief contact_dual_update(): one point's local step of the contact term that FastMassSpring
/// and BackwardEuler put inside their solves (local_global/contact_projection.hpp describes the
/// term: the alternating direction method of multipliers, Boyd et al. 2011, section 3.1.1).

#include "massspring/contact/colliders/collider_set.hpp"

namespace massspring::detail {

/// @brief At the iterate x of one point (3 coordinates [m]), with its scaled dual variable u [m]
/// and its start-of-step position x_start: z = P(x + u), P the colliders' position response
/// (ColliderSet::project; begin_step(dt) called), then u <- x + u - z. Writes the point the term
/// pulls x towards, target = z - u, and returns true when the point touches a collider; otherwise
/// (P moved nothing) u = 0, target = x, and returns false.
template <class Scalar>
bool contact_dual_update(const contact::ColliderSet<Scalar>& colliders, const Scalar* x_start,
                         const Scalar* x, Scalar* u, Scalar dt, Scalar* target) {
  Scalar z[3] = {x[0] + u[0], x[1] + u[1], x[2] + u[2]};
  const Scalar moved[3] = {z[0], z[1], z[2]};
  colliders.project(x_start, z, dt);
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
