#pragma once
/// @file
/// @brief The closest points of two segments in 3D, and their squared distance.
///
/// The segments are A(s) = a0 + s (a1 - a0) and B(t) = b0 + t (b1 - b0), s, t in [0, 1]. The
/// squared distance |A(s) - B(t)|^2 is a convex quadratic on the unit square, so its minimum lies
/// either on the square's boundary (an endpoint of one segment against the other segment) or at
/// the interior critical point of the two lines. This routine evaluates candidates and keeps the
/// nearest, instead of branching on the sign of a determinant as Ericson, "Real-Time Collision
/// Detection" (2005), section 5.1.9, does:
/// - the four endpoint-segment pairs, each by clamped projection (exact for parallel, collinear
///   and zero-length segments, where the lines have no unique critical point);
/// - when the lines are not parallel (n = (a1 - a0) x (b1 - b0) != 0), the lines' critical point
///   s* = ((b0 - a0) x (b1 - b0)) . n / |n|^2, clamped to [0, 1], then polished by one clamped
///   projection each way: t = proj_B(A(s*)), s = proj_A(B(t)). The polish keeps the pair on the
///   valley of the distance, so an s* spoiled by rounding (nearly parallel segments) costs a
///   distance error of the order of the rounding of the coordinates, not of 1 / |n|.
/// Every candidate is a true pair of points of the two segments, so the result is never below the
/// true distance by more than the rounding of one point evaluation.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "massspring/contact/distance/point_segment.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The closest pair of points of two segments.
template <class Scalar>
struct EdgeEdgeDistance {
  /// @brief Parameter of the closest point a0 + s (a1 - a0) on the first segment, in [0, 1].
  Scalar s = 0;
  /// @brief Parameter of the closest point b0 + t (b1 - b0) on the second segment, in [0, 1].
  Scalar t = 0;
  /// @brief |a0 + s (a1 - a0) - b0 - t (b1 - b0)|^2 [m^2] (NaN when an input is NaN).
  Scalar squared_distance = 0;
};

/// @brief Closest points of the segments [a0, a1] and [b0, b1] (all 3-vectors [m]). Robust for
/// parallel, collinear and zero-length segments; when several pairs are closest (parallel
/// overlapping segments), one of them is returned. No allocation.
template <class Scalar>
EdgeEdgeDistance<Scalar> edge_edge_distance(const Vector3<Scalar>& a0, const Vector3<Scalar>& a1,
                                            const Vector3<Scalar>& b0, const Vector3<Scalar>& b1) {
  const Vector3<Scalar> da = a1 - a0, db = b1 - b0;
  EdgeEdgeDistance<Scalar> best;
  const auto squared = [&](Scalar s, Scalar t) {
    return ((a0 + s * da) - (b0 + t * db)).squaredNorm();
  };
  const auto keep_if_nearer = [&](Scalar s, Scalar t) {
    const Scalar q = squared(s, t);
    if (q < best.squared_distance) best = {s, t, q};
  };
  // The first candidate is kept unconditionally, so a NaN input yields a NaN distance.
  best.t = segment_parameter(a0, b0, b1);
  best.squared_distance = squared(Scalar(0), best.t);
  keep_if_nearer(Scalar(1), segment_parameter(a1, b0, b1));
  keep_if_nearer(segment_parameter(b0, a0, a1), Scalar(0));
  keep_if_nearer(segment_parameter(b1, a0, a1), Scalar(1));
  const Vector3<Scalar> n = da.cross(db);
  const Scalar nn = n.squaredNorm();
  if (nn > 0) {
    Scalar s = (b0 - a0).cross(db).dot(n) / nn;
    s = s < 0 ? Scalar(0) : (s > 1 ? Scalar(1) : s);
    const Vector3<Scalar> on_a = a0 + s * da;
    const Scalar t = segment_parameter(on_a, b0, b1);
    const Vector3<Scalar> on_b = b0 + t * db;
    keep_if_nearer(segment_parameter(on_b, a0, a1), t);
  }
  return best;
}

}  // namespace massspring::contact
