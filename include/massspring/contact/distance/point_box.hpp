#pragma once
/// @file
/// @brief Signed distance from a point to an axis-aligned box centred at the origin, with the
/// outward normal: the box collider's distance, in its local frame (contact/colliders/collider.hpp).

#include <Eigen/Core>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Signed distance [m] from p to the box [-h, h] (h: half extents > 0), and its outward
/// normal n: outside, the distance to the nearest surface point, n towards p; inside, minus the
/// distance to the nearest face, n that face's normal. A component of p that is exactly 0 lies
/// within that face's span (it has no sign).
template <class Scalar>
Scalar point_box_distance(const Vector3<Scalar>& p, const Vector3<Scalar>& h, Vector3<Scalar>& n) {
  using V3 = Vector3<Scalar>;
  const V3 q = p.cwiseAbs() - h;
  const V3 outside = q.cwiseMax(V3::Zero());
  const Scalar out = outside.norm();
  if (out > 0) {
    n = outside.cwiseProduct(p.cwiseSign()) / out;
    return out;
  }
  Eigen::Index k = 0;
  const Scalar inside = q.maxCoeff(&k);
  n = V3::Zero();
  n(k) = p(k) < 0 ? Scalar(-1) : Scalar(1);
  return inside;
}

}  // namespace massspring::contact
