#pragma once
/// @file
/// @brief The box collider's geometry: Collider::box() and the signed distance of a point from an
/// oriented box (contact/distance/point_box.hpp). Included by the headers that make box
/// colliders; contact/colliders/collider.hpp reaches it through a table of pointers box() sets.

#include <Eigen/Core>

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
    static constexpr typename C::Geometry kGeometry{&BoxShape::phi, nullptr, nullptr};
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

  /// @brief phi and the outward normal n at the local point p (the box's half extents: axis()).
  static Scalar phi(const C& self, const V3& p, V3& n) {
    return point_box_distance<Scalar>(p, self.axis_, n);
  }
};

}  // namespace massspring::contact
