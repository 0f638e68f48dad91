#pragma once
/// @file
/// @brief loop_stays_star_shaped(): the contour half of the self-collision tree's skip test
/// (contact/broad_phase/normal_cone_tree.hpp; Schvartzman, Perez and Otaduy 2010,
/// "Star-contours for efficient hierarchical self-collision detection"), over a time step.
///
/// With every point moving linearly, p(t) = (1 - t) p0 + t p1, and a centre c(t) that does too,
/// a . ((p(t) - c(t)) x (q(t) - c(t))) is quadratic in t with the Bernstein coefficients
/// a . (P0 x Q0), a . (P0 x Q1 + P1 x Q0) / 2 and a . (P1 x Q1), where Pk = pk - ck; when all
/// three are positive, so is the quadratic on [0, 1]. Every edge then turns counterclockwise
/// about c(t) by less than a half turn and the loop never meets c(t), so its winding number about
/// c(t) is the same at every t: at t = 0, the number of edges that cross the ray from c0 along
/// the first coordinate axis upwards (from v < 0 to v >= 0; a counterclockwise turn of less than
/// a half turn crosses that line only there). Star-shaped means one turn: a loop that turns
/// counterclockwise twice about c (a fan about a border vertex folded over itself in a spiral)
/// passes the edge test and is not one-to-one. The products are taken in coordinates
/// (u, v) of the plane normal to a, in an orthonormal basis e1, e2 = a x e1, where
/// a . (p x q) = u_p v_q - v_p u_q, so each point's offsets are projected once.

#include <Eigen/Core>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Whether the closed loop of `count` (>= 1) points, rows `loop[0..count)` of x0 and x1
/// (positions at the start and end of the step [m]), seen along the unit axis a, turns strictly
/// counterclockwise about the centre c(t) = (1 - t) c0 + t c1 at every t in [0, 1], once: each
/// of the three Bernstein coefficients of each edge (see the file comment) exceeds 1e-9 of
/// (|P0|_1 + |P1|_1)(|Q0|_1 + |Q1|_1), at least 1e-9 of the product of the lengths, a margin
/// far above the rounding of the products, and the winding number is 1.
template <class Scalar>
bool loop_stays_star_shaped(const Points<Scalar>& x0, const Points<Scalar>& x1,
                            const Vector3<Scalar>& a, const Vector3<Scalar>& c0,
                            const Vector3<Scalar>& c1, const int* loop, int count) {
  using V3 = Vector3<Scalar>;
  int least = 0;
  a.cwiseAbs().minCoeff(&least);
  const V3 e1 = a.cross(V3::Unit(least)).normalized(), e2 = a.cross(e1);
  struct Offsets {
    Scalar u0, v0, u1, v1;
    Scalar length;  // |P0|_1 + |P1|_1
  };
  const auto offsets = [&](int p) {
    const V3 p0 = x0.row(p).transpose() - c0, p1 = x1.row(p).transpose() - c1;
    return Offsets{p0.dot(e1), p0.dot(e2), p1.dot(e1), p1.dot(e2),
                   p0.template lpNorm<1>() + p1.template lpNorm<1>()};
  };
  Offsets p = offsets(loop[count - 1]);
  int turns = 0;
  for (int i = 0; i < count; ++i) {  // the edge p -> q, the closing one first
    const Offsets q = offsets(loop[i]);
    const Scalar scale = Scalar(1e-9) * p.length * q.length;
    const Scalar at0 = p.u0 * q.v0 - p.v0 * q.u0, at1 = p.u1 * q.v1 - p.v1 * q.u1;
    const Scalar mixed = p.u0 * q.v1 - p.v0 * q.u1 + (p.u1 * q.v0 - p.v1 * q.u0);
    if (!(at0 > scale && at1 > scale && mixed > 2 * scale)) return false;
    turns += p.v0 < 0 && q.v0 >= 0;
    p = q;
  }
  return turns == 1;
}

}  // namespace massspring::contact
