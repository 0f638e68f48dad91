#pragma once
/// @file
/// @brief The point of a triangle closest to a point, and the first crossing of a segment with a
/// triangle: the two queries a triangle-mesh collider makes (contact/colliders/triangle_mesh.hpp);
/// and the squared point-triangle distance the continuous collision detection uses.
///
/// Closest point: Ericson, "Real-Time Collision Detection" (2005), section 5.1.5 (the Voronoi
/// regions of the vertices, edges and face, tested in that order). Crossing: Moller and Trumbore,
/// "Fast, minimum storage ray-triangle intersection" (1997), restricted to the segment's
/// parameter range [0, 1].

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "massspring/contact/distance/point_segment.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The point of triangle (a, b, c) closest to p (all [m]). A degenerate triangle (zero
/// area) is treated as its edges and vertices.
template <class Scalar>
Vector3<Scalar> closest_point_on_triangle(const Vector3<Scalar>& p, const Vector3<Scalar>& a,
                                          const Vector3<Scalar>& b, const Vector3<Scalar>& c) {
  const Vector3<Scalar> ab = b - a, ac = c - a, ap = p - a;
  const Scalar d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;  // vertex region a
  const Vector3<Scalar> bp = p - b;
  const Scalar d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;  // vertex region b
  const Scalar vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;  // edge ab
  const Vector3<Scalar> cp = p - c;
  const Scalar d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;  // vertex region c
  const Scalar vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;  // edge ac
  const Scalar va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);  // edge bc
  const Scalar sum = va + vb + vc;
  if (!(sum > 0)) {  // degenerate: the nearest of the three edges
    Vector3<Scalar> best = a;
    Scalar best_d = (p - a).squaredNorm();
    const Vector3<Scalar>* ends[3][2] = {{&a, &b}, {&b, &c}, {&c, &a}};
    for (const auto& e : ends) {
      const Vector3<Scalar> d = *e[1] - *e[0];
      const Scalar dd = d.squaredNorm();
      Scalar t = dd > 0 ? (p - *e[0]).dot(d) / dd : Scalar(0);
      t = t < 0 ? Scalar(0) : (t > 1 ? Scalar(1) : t);
      const Vector3<Scalar> q = *e[0] + t * d;
      const Scalar qd = (p - q).squaredNorm();
      if (qd < best_d) {
        best_d = qd;
        best = q;
      }
    }
    return best;
  }
  const Scalar v = vb / sum, w = vc / sum;
  return a + v * ab + w * ac;  // face region
}

/// @brief Squared distance from p to triangle (a, b, c) (all [m], result [m^2]): the smaller of
/// |p - closest_point_on_triangle(p, a, b, c)|^2 and the squared distances to the three edges.
/// The edges bound the error of the face region's barycentric division on a sliver (a triangle
/// whose area is small against its edges squared) by the sliver's width. Used by the continuous
/// collision detection (contact/ccd/additive_ccd.hpp), which needs the distance never above the
/// true one by more than rounding.
template <class Scalar>
Scalar point_triangle_squared_distance(const Vector3<Scalar>& p, const Vector3<Scalar>& a,
                                       const Vector3<Scalar>& b, const Vector3<Scalar>& c) {
  Scalar best = (p - closest_point_on_triangle(p, a, b, c)).squaredNorm();
  const Vector3<Scalar>* ends[3][2] = {{&a, &b}, {&b, &c}, {&c, &a}};
  for (const auto& e : ends) {
    const Scalar t = segment_parameter(p, *e[0], *e[1]);
    const Scalar q = (p - (*e[0] + t * (*e[1] - *e[0]))).squaredNorm();
    if (q < best) best = q;
  }
  return best;
}

/// @brief Where the segment p0 -> p1 crosses triangle (a, b, c), as the parameter t in [0, 1]
/// of p0 + t (p1 - p0); false when it does not cross (or lies in the triangle's plane, or the
/// triangle is degenerate). Edges and vertices count as part of the triangle (barycentric
/// coordinates tested with >= 0), so a segment through a shared edge is caught by both triangles.
template <class Scalar>
bool segment_crosses_triangle(const Vector3<Scalar>& p0, const Vector3<Scalar>& p1,
                              const Vector3<Scalar>& a, const Vector3<Scalar>& b,
                              const Vector3<Scalar>& c, Scalar& t) {
  const Vector3<Scalar> d = p1 - p0, e1 = b - a, e2 = c - a;
  const Vector3<Scalar> h = d.cross(e2);
  const Scalar det = e1.dot(h);
  if (det == 0 || !std::isfinite(det)) return false;
  const Scalar inv = Scalar(1) / det;
  const Vector3<Scalar> s = p0 - a;
  const Scalar u = inv * s.dot(h);
  if (u < 0 || u > 1) return false;
  const Vector3<Scalar> q = s.cross(e1);
  const Scalar v = inv * d.dot(q);
  if (v < 0 || u + v > 1) return false;
  t = inv * e2.dot(q);
  return t >= 0 && t <= 1;
}

}  // namespace massspring::contact
