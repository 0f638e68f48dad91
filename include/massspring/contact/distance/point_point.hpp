#pragma once
/// @file
/// @brief Distance between two points, with the closest point and the normal.
///
/// FOSSSim's particle-particle test (Theme 2, SimpleCollisionHandler::
/// detectParticleParticle): n = x_2 - x_1, in contact when |n| < r_1 + r_2. 3-vectors throughout
/// (the 2D scenes live in z = 0), so the 3D contact code uses the same functions.

#include <Eigen/Core>
#include <cmath>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The shortest vector from point p to point q, and its length.
template <class Scalar>
struct PointPointDistance {
  /// @brief n = q - p [m]: from p to the closest point of the other primitive (here q itself).
  Vector3<Scalar> n;
  /// @brief |n| [m].
  Scalar distance = 0;
  /// @brief The closest point of the other primitive (q) [m].
  Vector3<Scalar> closest;
  /// @brief n / |n|, or zero when |n| = 0 (no direction).
  [[nodiscard]] Vector3<Scalar> normal() const {
    return distance > 0 ? Vector3<Scalar>(n / distance) : Vector3<Scalar>::Zero();
  }
};

/// @brief Distance from p to q: \f$ n = q - p,\ d = |n| \f$.
/// @param[in] p, q  3-vectors [m]
template <class Scalar>
PointPointDistance<Scalar> point_point_distance(const Vector3<Scalar>& p,
                                                const Vector3<Scalar>& q) {
  PointPointDistance<Scalar> r;
  r.n = q - p;
  r.distance = r.n.norm();
  r.closest = q;
  return r;
}

}  // namespace massspring::contact
