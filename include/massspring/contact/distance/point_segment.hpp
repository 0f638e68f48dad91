#pragma once
/// @file
/// @brief Distance from a point to a segment, with the closest point, its parameter and the
/// normal.
///
/// FOSSSim's particle-edge test (Theme 2, SimpleCollisionHandler::detectParticleEdge,
/// PenaltyForce::addParticleEdgeGradEToTotal): \f$ \alpha = \mathrm{clamp}_{[0,1]}
/// \frac{(x_1 - x_2)\cdot(x_3 - x_2)}{|x_3 - x_2|^2} \f$, closest point
/// \f$ x_\alpha = x_2 + \alpha (x_3 - x_2) \f$, \f$ n = x_\alpha - x_1 \f$.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The shortest vector from a point to a segment [a, b].
template <class Scalar>
struct PointSegmentDistance {
  /// @brief n = closest - p [m].
  Vector3<Scalar> n;
  /// @brief |n| [m].
  Scalar distance = 0;
  /// @brief The closest point a + alpha (b - a) [m].
  Vector3<Scalar> closest;
  /// @brief Its parameter in [0, 1] (0 for a degenerate segment a = b).
  Scalar alpha = 0;
  /// @brief n / |n|, or zero when |n| = 0.
  [[nodiscard]] Vector3<Scalar> normal() const {
    return distance > 0 ? Vector3<Scalar>(n / distance) : Vector3<Scalar>::Zero();
  }
};

/// @brief The parameter of the point of the line through a, b closest to p, clamped to [0, 1]
/// (0 when a = b).
template <class Scalar>
Scalar segment_parameter(const Vector3<Scalar>& p, const Vector3<Scalar>& a,
                         const Vector3<Scalar>& b) {
  const Vector3<Scalar> e = b - a;
  const Scalar ee = e.squaredNorm();
  if (!(ee > 0)) return Scalar(0);
  return std::clamp((p - a).dot(e) / ee, Scalar(0), Scalar(1));
}

/// @brief Distance from p to the segment [a, b] (all 3-vectors [m]).
template <class Scalar>
PointSegmentDistance<Scalar> point_segment_distance(const Vector3<Scalar>& p,
                                                    const Vector3<Scalar>& a,
                                                    const Vector3<Scalar>& b) {
  PointSegmentDistance<Scalar> r;
  r.alpha = segment_parameter(p, a, b);
  r.closest = a + r.alpha * (b - a);
  r.n = r.closest - p;
  r.distance = r.n.norm();
  return r;
}

}  // namespace massspring::contact
