#pragma once
/// @file
/// @brief Distance from a point to a plane (a half-plane's boundary line in the 2D scenes), with
/// the closest point and the normal.
///
/// FOSSSim's particle-half-plane test (Theme 2, SimpleCollisionHandler::
/// detectParticleHalfplane, PenaltyForce::addParticleHalfplaneGradEToTotal): a plane is a point
/// p and a normal m, not necessarily of unit length;
/// \f$ n = \frac{(p - x)\cdot m}{m\cdot m}\, m \f$ is the shortest vector from x to the plane.
/// Its length is unsigned: FOSSSim's tests treat the boundary as a thick line, from either side.

#include <Eigen/Core>
#include <cmath>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief A plane through `point` with normal `normal` (pointing into the free side; any
/// length > 0). In the 2D scenes a half-plane: z-component 0.
template <class Scalar>
struct Plane {
  Vector3<Scalar> point = Vector3<Scalar>::Zero();
  Vector3<Scalar> normal = Vector3<Scalar>::UnitY();
};

/// @brief The shortest vector from a point to a plane.
template <class Scalar>
struct PointPlaneDistance {
  /// @brief n = closest - x [m].
  Vector3<Scalar> n;
  /// @brief |n| [m] (unsigned).
  Scalar distance = 0;
  /// @brief Signed distance (x - point) . m / |m| [m]: > 0 on the side the normal points to.
  Scalar signed_distance = 0;
  /// @brief The closest point of the plane [m].
  Vector3<Scalar> closest;
  /// @brief n / |n|, or zero when |n| = 0.
  [[nodiscard]] Vector3<Scalar> normal() const {
    return distance > 0 ? Vector3<Scalar>(n / distance) : Vector3<Scalar>::Zero();
  }
};

/// @brief Distance from x to a plane: \f$ n = \frac{(p - x)\cdot m}{m\cdot m} m \f$.
template <class Scalar>
PointPlaneDistance<Scalar> point_plane_distance(const Vector3<Scalar>& x,
                                                const Plane<Scalar>& plane) {
  PointPlaneDistance<Scalar> r;
  const Scalar mm = plane.normal.squaredNorm();
  const Scalar s = (plane.point - x).dot(plane.normal) / mm;
  r.n = s * plane.normal;
  r.distance = r.n.norm();
  r.signed_distance = -s * std::sqrt(mm);
  r.closest = x + r.n;
  return r;
}

}  // namespace massspring::contact
