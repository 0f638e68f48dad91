#pragma once
/// @file
/// @brief The contact term that FastMassSpring and BackwardEuler put inside their solves
/// (local_global/contact_projection.hpp describes it: the alternating direction method of
/// multipliers, Boyd et al. 2011, section 3.1.1): contact_weights(), its weight per point, and
/// contact_dual_update(), one point's local step.

#include <Eigen/Core>
#include <algorithm>
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

/// @brief The edge distance rho_i [m] of each point of the solves' contact term, into `rho`
/// (resized to the points; allocates only then): rho_i = L_i / sqrt(2), L_i the longest edge of
/// the surface triangles that hold point i, at the system's current positions (0 for a point on
/// no triangle); every rho_i is 0 without a box or a capsule. The term keeps point i rho_i (plus
/// the thickness) from each box's edges and corners, and max(r + thickness, sqrt(r^2 +
/// rho_i^2 / 2)) from each capsule's axis (r its radius; Collider::push_off_edges()), so that no
/// edge of a surface triangle meets the solid, each triangle's three points having at least the
/// rho of its own longest edge:
/// - a box: two points outside it, each at least rho from its edges, are at least sqrt(2) rho = L
///   apart when the segment between them meets the box (the shortest such segment joins two
///   points on the two faces of an edge, rho from it); nor does a box edge pierce a surface
///   triangle (tests/contact/colliders/test_box_shape.cpp samples both);
/// - a capsule: for any set K and two points P, Q at least D from it, every point m = t P +
///   (1 - t) Q of the segment is at least sqrt(D^2 - |P - Q|^2 / 4) from K (c the point of K
///   nearest m: t |P - c|^2 + (1 - t) |Q - c|^2 = |m - c|^2 + t (1 - t) |P - Q|^2), so with K the
///   axis and |P - Q| <= L the segment stays r from it, outside the rod
///   (tests/contact/colliders/test_colliders.cpp samples it).
/// Per point, one long triangle somewhere in the surface widens the band only about its own
/// points. The end-of-step surface pass (contact/response/surface_contact.hpp), which tests the
/// cloth's edges against a box's edges and a capsule's axis, then finds nothing to push there at
/// the step's end.
template <class System>
void edge_distances(const System& system, Vector<typename System::Scalar>& rho) {
  using Scalar = typename System::Scalar;
  rho.setZero(system.num_points());
  bool thin = false;  // a box or a capsule
  for (const auto& c : system.colliders())
    thin = thin || c.shape() == contact::ColliderShape::Box ||
           c.shape() == contact::ColliderShape::Capsule;
  if (!thin) return;
  const auto& triangles = system.surface();
  const auto& x = system.positions();
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    Scalar longest2 = 0;
    for (int k = 0; k < 3; ++k)
      longest2 = std::max(
          longest2,
          Scalar((x.row(triangles(t, k)) - x.row(triangles(t, (k + 1) % 3))).squaredNorm()));
    const Scalar r = std::sqrt(longest2 / 2);
    for (int k = 0; k < 3; ++k) rho(triangles(t, k)) = std::max(rho(triangles(t, k)), r);
  }
}

/// @brief At the iterate x of one point (3 coordinates [m]), with its scaled dual variable u [m]
/// and its start-of-step position x_start: z = P(x + u), P the colliders' position response
/// (ColliderSet::project; begin_step(dt) called), then u <- x + u - z. Writes the point the term
/// pulls x towards, target = z - u, and returns true when the point touches a collider; otherwise
/// (P moved nothing) u = 0, target = x, and returns false. `clearance2` [m^2]: the square of
/// ColliderSet::clearance(x_start) less `edge_distance` when positive, else 0; a z closer than
/// that to x_start is not projected (P would not move it). `edge_distance` [m]: P also keeps
/// the point out of the band about each box's edges and each capsule's axis (the point's
/// edge_distances()). `shift` [m] (3 values, or null for none): moved first, z = P(x + u +
/// shift): the point's self-contact correction (self_contact_term.hpp), so that P is the
/// colliders' projection after self-contact's.
template <class Scalar>
bool contact_dual_update(const contact::ColliderSet<Scalar>& colliders, const Scalar* x_start,
                         const Scalar* x, Scalar* u, Scalar dt, Scalar* target,
                         Scalar clearance2 = 0, Scalar edge_distance = 0,
                         const Scalar* shift = nullptr) {
  const Scalar moved[3] = {x[0] + u[0], x[1] + u[1], x[2] + u[2]};
  Scalar z[3] = {moved[0], moved[1], moved[2]};
  if (shift)
    for (int c = 0; c < 3; ++c) z[c] += shift[c];
  const Scalar d[3] = {z[0] - x_start[0], z[1] - x_start[1], z[2] - x_start[2]};
  if (!(d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < clearance2))
    colliders.project(x_start, z, dt, edge_distance);
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
