#pragma once
// An oracle for tests of contact with thin parts (a capsule's axis, a cloth's edges), written
// without the library's distance code: the least distance between two segments.

#include <Eigen/Core>
#include <algorithm>

namespace massspring::test {

// The least distance between the segments [p, q] and [a, b], by ternary search on the convex
// function t -> distance from p + t (q - p) to [a, b] (the distance to a convex set along a line
// is convex); the point of [a, b] nearest a point is its clamped projection.
inline double segment_segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                                       const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double ab2 = ab.squaredNorm();
  const auto f = [&](double t) {
    const Eigen::Vector3d m = p + t * (q - p);
    const double s = ab2 > 0 ? std::clamp((m - a).dot(ab) / ab2, 0.0, 1.0) : 0.0;
    return (m - (a + s * ab)).norm();
  };
  double lo = 0, hi = 1;
  for (int k = 0; k < 200; ++k) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2))
      hi = m2;
    else
      lo = m1;
  }
  return std::min({f(0), f(1), f((lo + hi) / 2)});
}

}  // namespace massspring::test
