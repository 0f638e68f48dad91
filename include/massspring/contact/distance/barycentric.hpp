#pragma once
/// @file
/// @brief Barycentric coordinates in a triangle: of a point's projection on the triangle's plane
/// (plane_barycentric()), and of a point on the triangle, clamped to it (clamped_barycentric()).
/// Ericson, "Real-Time Collision Detection" (2005), section 3.4 (Cramer's rule on the normal
/// equations of p - a = s (b - a) + t (c - a)).

#include <Eigen/Core>
#include <algorithm>
#include <array>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The coordinates (1 - s - t, s, t) on (a, b, c) of p's projection on the triangle's
/// plane, not clamped: all three are positive exactly when the projection is inside the triangle.
/// (1, 0, 0) for a degenerate triangle (zero area).
template <class Scalar>
std::array<Scalar, 3> plane_barycentric(const Vector3<Scalar>& p, const Vector3<Scalar>& a,
                                        const Vector3<Scalar>& b, const Vector3<Scalar>& c) {
  const Vector3<Scalar> u = b - a, v = c - a, w = p - a;
  const Scalar uu = u.dot(u), uv = u.dot(v), vv = v.dot(v), wu = w.dot(u), wv = w.dot(v);
  const Scalar den = uu * vv - uv * uv;
  if (!(den > 0)) return {1, 0, 0};
  const Scalar s = (vv * wu - uv * wv) / den, t = (uu * wv - uv * wu) / den;
  return {1 - s - t, s, t};
}

/// @brief plane_barycentric() with s clamped to [0, 1] and then t to [0, 1 - s]: the
/// coordinates of a point on the triangle (e.g. closest_point_on_triangle()'s) that rounding left
/// just outside it.
template <class Scalar>
std::array<Scalar, 3> clamped_barycentric(const Vector3<Scalar>& p, const Vector3<Scalar>& a,
                                          const Vector3<Scalar>& b, const Vector3<Scalar>& c) {
  const std::array<Scalar, 3> plane = plane_barycentric(p, a, b, c);
  const Scalar s = std::clamp(plane[1], Scalar(0), Scalar(1));
  const Scalar t = std::clamp(plane[2], Scalar(0), Scalar(1) - s);
  return {1 - s - t, s, t};
}

}  // namespace massspring::contact
