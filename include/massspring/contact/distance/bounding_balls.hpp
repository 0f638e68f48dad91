#pragma once
/// @file
/// @brief Lower bounds of the distance between two small point sets' convex hulls (a point, an
/// edge, a triangle) from their bounding balls: a cheap test that rejects a pair of elements far
/// apart before their exact distance or continuous detection is computed.
///
/// A set of points x_k with centroid c lies in the ball of centre c and radius
/// r = max_k |x_k - c|, and so does its hull; for two sets, every pair of hull points is at least
/// |c_a - c_b| - r_a - r_b apart.
///
/// Over a straight-line motion x_k(t) = (1 - t) x_k(0) + t x_k(1), t in [0, 1], the centroid
/// moves on a straight line too, and |x_k(t) - c(t)| <= (1 - t) r(0) + t r(1) <= max(r(0), r(1))
/// (the triangle inequality on the interpolated offsets), so the hulls stay at least
/// min_t |c_a(t) - c_b(t)| - max(r_a(0) + r_b(0), r_a(1) + r_b(1)) apart at every t: the distance
/// of the origin to the segment c_a - c_b sweeps, less the larger sum of radii.
///
/// Both bounds are conservative (never above the true distance) and cost a few dozen flops.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "massspring/types.hpp"

namespace massspring::contact {

namespace detail {
// Centroid and radius of points[begin..end).
template <class Scalar, class Points>
void bounding_ball(const Points& points, int begin, int end, Vector3<Scalar>& centre,
                   Scalar& radius) {
  centre.setZero();
  for (int k = begin; k < end; ++k) centre += points[std::size_t(k)];
  centre /= Scalar(end - begin);
  Scalar r2 = 0;
  for (int k = begin; k < end; ++k)
    r2 = std::max(r2, (points[std::size_t(k)] - centre).squaredNorm());
  radius = std::sqrt(r2);
}
}  // namespace detail

/// @brief Whether the hulls of x[0..split) and x[split..4) may come closer than `distance` [m]
/// (false: they are farther apart; see the file comment). split 1: a point and a triangle; 2: two
/// edges.
template <class Scalar>
bool balls_within(const std::array<Vector3<Scalar>, 4>& x, int split, Scalar distance) {
  Vector3<Scalar> ca, cb;
  Scalar ra = 0, rb = 0;
  detail::bounding_ball(x, 0, split, ca, ra);
  detail::bounding_ball(x, split, 4, cb, rb);
  const Scalar reach = ra + rb + distance;
  return (ca - cb).squaredNorm() < reach * reach;
}

/// @brief Whether the hulls of x[0..split) and x[split..4), moving on straight lines from x0 to
/// x1, may come closer than `distance` [m] at some time of the motion (false: never; see the file
/// comment).
template <class Scalar>
bool swept_balls_within(const std::array<Vector3<Scalar>, 4>& x0,
                        const std::array<Vector3<Scalar>, 4>& x1, int split, Scalar distance) {
  Vector3<Scalar> ca0, cb0, ca1, cb1;
  Scalar ra0 = 0, rb0 = 0, ra1 = 0, rb1 = 0;
  detail::bounding_ball(x0, 0, split, ca0, ra0);
  detail::bounding_ball(x0, split, 4, cb0, rb0);
  detail::bounding_ball(x1, 0, split, ca1, ra1);
  detail::bounding_ball(x1, split, 4, cb1, rb1);
  const Scalar reach = std::max(ra0 + rb0, ra1 + rb1) + distance;
  // The closest point to the origin of the segment d(t) = d0 + t (d1 - d0).
  const Vector3<Scalar> d0 = ca0 - cb0, step = (ca1 - cb1) - d0;
  const Scalar len2 = step.squaredNorm();
  const Scalar t = len2 > 0 ? std::clamp(-d0.dot(step) / len2, Scalar(0), Scalar(1)) : Scalar(0);
  return (d0 + t * step).squaredNorm() < reach * reach;
}

}  // namespace massspring::contact
