#pragma once
/// @file
/// @brief ContactZone: the region of space, over one step, outside which a collider
/// (contact/colliders/collider.hpp) cannot touch a point's path: its quick rejection, far(), and
/// the distance from a path's start that keeps the path outside, clearance().
///
/// The zone is a half-space for a plane (world normal n, offset o: the points with n . x - o <= 0
/// may touch), and for the other shapes the ball about the collider's end-of-step reference point
/// c of radius reach + motion: `reach` holds the shape, its thickness and a margin of
/// sqrt(epsilon) of the scale (far above any rounding, so that the zone only filters), `motion`
/// bounds how far a point of the shape moves over the step. Collider::refresh() sets it.

#include <Eigen/Core>
#include <cmath>

#include "massspring/contact/colliders/collider_contact.hpp"
#include "massspring/contact/distance/point_segment.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief A collider's contact zone over a step (see the file comment).
template <class Scalar>
struct ContactZone {
  using V3 = Vector3<Scalar>;

  ColliderShape shape = ColliderShape::Plane;
  V3 normal = V3::Zero();  // a plane's world normal
  V3 centre = V3::Zero();  // c: the reference point at the step's end [m]
  Scalar offset = 0;       // a plane's: n . x - offset > 0 is outside [m]
  Scalar reach = 0;        // the ball's radius without the motion [m]
  Scalar motion = 0;       // how far a point of the shape moves over the step [m]

  /// @brief True when no point of the path x_start -> x_end can be in contact: outside the zone
  /// grown by slop [m] (a plane: the end alone; a mesh: the whole path; a solid: the end, then the
  /// whole path, as a point may cross the solid within one step).
  template <class A, class B>
  [[nodiscard]] bool far(const A& x_start, const B& x_end, Scalar slop) const {
    switch (shape) {
      case ColliderShape::Plane:
        return normal.dot(x_end) - offset > slop;
      case ColliderShape::Mesh: {
        const auto d = point_segment_distance<Scalar>(centre, x_start, x_end);
        return d.distance > reach + motion + slop;
      }
      default: {
        // The end, then the bound |x_end - c| - |x_end - x_start| on the path's distance from
        // c, then that distance.
        const Scalar r = reach + slop;
        const Scalar end2 = (x_end - centre).squaredNorm();
        if (!(end2 > r * r)) return false;
        if (std::sqrt(end2) - (x_end - x_start).norm() > r + motion) return true;
        const auto d = point_segment_distance<Scalar>(centre, x_start, x_end);
        return d.distance > r + motion;
      }
    }
  }

  /// @brief A distance [m] from x_start such that no path x_start -> x_end shorter than it enters
  /// the zone (far() with slop 0 holds, and the collider's contact() finds nothing): the plane's
  /// offset of x_start, or x_start's distance from the ball (every point of the path lies within
  /// |x_end - x_start| of x_start). Not positive: no such distance. The zone's margin is far above
  /// this bound's rounding.
  [[nodiscard]] Scalar clearance(const V3& x_start) const {
    if (shape == ColliderShape::Plane) return normal.dot(x_start) - offset;
    return (x_start - centre).norm() - reach - motion;
  }
};

}  // namespace massspring::contact
