#pragma once
/// @file
/// @brief The box collider's geometry: Collider::box() and the signed distance of a point from an
/// oriented box (contact/distance/point_box.hpp). Included by the headers that make box
/// colliders; contact/colliders/collider.hpp reaches it through a table of pointers box() sets.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "massspring/contact/colliders/collider.hpp"
#include "massspring/contact/colliders/rotation.hpp"
#include "massspring/contact/distance/point_box.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Collider::box() and the box's phi.
template <class Scalar>
struct BoxShape {
  using V3 = Vector3<Scalar>;
  using C = Collider<Scalar>;

  /// @brief Collider::box(): validates the centre, the half extents (each > 0) and the
  /// quaternion (w, x, y, z) (finite, not zero; normalised here).
  static C make(const V3& center, const V3& half_extents, const Eigen::Matrix<Scalar, 4, 1>& wxyz) {
    static constexpr
        typename C::Geometry kGeometry{&BoxShape::phi, nullptr, nullptr, &BoxShape::push_off_edges};
    C::check_finite(center, "box: center");
    C::check_finite(half_extents, "box: half_extents");
    for (int k = 0; k < 3; ++k) C::check_positive(half_extents(k), "box collider: half_extents");
    if (!wxyz.allFinite() || !(wxyz.norm() > 0))
      throw Error("box collider: rotation must be a finite, non-zero quaternion (w, x, y, z)");
    C c(ColliderShape::Box, center);
    c.geometry_ = &kGeometry;
    c.axis_ = half_extents;
    c.rotation_ = quaternion_matrix<Scalar>(wxyz / wxyz.norm());
    c.end_rotation_ = c.rotation_;
    c.previous_rotation_ = c.rotation_;
    c.refresh();
    return c;
  }

  /// @brief Collider::push_off_edges() in the box's frame: p (local, outside the box [-h, h] or
  /// on it; h = axis()) closer than `distance` [m] to the box's twelve edges (the corners
  /// included) moves to that distance from them, `distance` taken at most p_start's distance from
  /// them (p_start the point at the step's start, local to the start pose; 0 inside the box):
  /// - over a face (outside the box along one axis k at most): along that face's normal, to the
  ///   height sqrt(distance^2 - r^2) over it, r the distance within the face to its border (the
  ///   cloth on a table is lifted at the rim, not pushed along the table);
  /// - beside an edge or a corner (outside along two or three axes): radially from the nearest
  ///   edge point e (p's coordinate along the edge clamped to it, the others at +-h by p's signs).
  /// True when p moved.
  static bool push_off_edges(const C& self, V3& p, const V3& p_start, Scalar distance) {
    const V3& h = self.axis_;
    const V3 outside = p.cwiseAbs() - h;
    // Inside by more than rounding: the box's own push (contact()) comes first.
    if (inside(p, outside)) return false;
    // The nearest edge point, for the quick test.
    V3 nearest = V3::Zero();
    const Scalar best = nearest_edge_point(h, p, nearest);
    if (!inside(p_start, V3(p_start.cwiseAbs() - h))) {
      V3 unused = V3::Zero();
      distance = std::min(distance, std::sqrt(nearest_edge_point(h, p_start, unused)));
    } else {
      distance = 0;
    }
    if (!(best < distance * distance)) return false;
    int k = 0, beside = 0;
    for (int a = 0; a < 3; ++a) {
      beside += outside(a) > 0;
      if (outside(a) > outside(k)) k = a;
    }
    if (beside >= 2) {  // the nearest point is e, at a positive distance
      p = nearest + distance * (p - nearest) / std::sqrt(best);
      return true;
    }
    Scalar r = std::numeric_limits<Scalar>::infinity();
    for (int a = 0; a < 3; ++a)
      if (a != k) r = std::min(r, std::max(h(a) - std::abs(p(a)), Scalar(0)));
    const Scalar height = std::sqrt(std::max(distance * distance - r * r, Scalar(0)));
    if (!(outside(k) < height)) return false;
    p(k) = p(k) < 0 ? -(h(k) + height) : h(k) + height;
    return true;
  }

  // p inside the box (`outside` = |p| - h) by more than rounding.
  static bool inside(const V3& p, const V3& outside) {
    return outside.maxCoeff() <
           -16 * std::numeric_limits<Scalar>::epsilon() * (1 + p.cwiseAbs().maxCoeff());
  }
  // The point of the box's edges nearest p (into `nearest`; along the edge of each axis a, p's
  // coordinate clamped to it, the others at +-h by p's signs), and its squared distance [m^2].
  static Scalar nearest_edge_point(const V3& h, const V3& p, V3& nearest) {
    Scalar best = std::numeric_limits<Scalar>::infinity();
    for (int a = 0; a < 3; ++a) {
      V3 e;
      for (int b = 0; b < 3; ++b)
        e(b) = b == a ? std::clamp(p(b), -h(b), h(b)) : (p(b) < 0 ? -h(b) : h(b));
      const Scalar d = (p - e).squaredNorm();
      if (d < best) {
        best = d;
        nearest = e;
      }
    }
    return best;
  }

  /// @brief phi and the outward normal n at the local point p (the box's half extents: axis()).
  static Scalar phi(const C& self, const V3& p, V3& n) {
    return point_box_distance<Scalar>(p, self.axis_, n);
  }
};

}  // namespace massspring::contact
