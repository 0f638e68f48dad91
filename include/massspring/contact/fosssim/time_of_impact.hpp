#pragma once
/// @file
/// @brief Continuous-time detection: the first time in [0, 1] of a step at which two primitives
/// moving on straight lines overlap (distance below the sum of radii) and approach, from
/// FOSSSim's polynomial conditions (Theme 2, ContinuousTimeCollisionHandler::detect* and
/// HybridCollisionHandler::detect*). Positions at time t are x(t) = x + t dx, dx the displacement
/// over the step; every condition is "a polynomial in t is > 0", and the time of impact is the
/// first t where all of a pair's polynomials are (contact/fosssim/polynomial_intervals.hpp).
///
/// - particle-particle (1, 2), s = r1 + r2, y = x2 - x1, dy = dx2 - dx1:
///   distance \f$ s^2 - |y + t\,dy|^2 > 0 \f$ (quadratic), approach
///   \f$ -dy\cdot(y + t\,dy) > 0 \f$ (linear).
/// - particle 1, edge (2, 3), A = x1 - x2, B = x3 - x2 (linear in t), a = A.B, d = |A|^2,
///   g = |B|^2 (quadratics), u = dx1 - dx2, w = dx3 - dx2: distance to the line
///   \f$ a^2 - d g + s^2 g > 0 \f$ (quartic), alpha >= 0: \f$ a > 0 \f$, alpha <= 1:
///   \f$ (x_1 - x_3)\cdot(x_2 - x_3) > 0 \f$ (quadratics), approach of the particle and the edge's
///   closest point \f$ (g u - a w)\cdot(a B - g A) > 0 \f$ (FOSSSim's quintic: the normal
///   relative velocity times g^2).
/// - particle 1, plane (p, m), s = r1: \f$ s^2 |m|^2 - ((p - x_1(t))\cdot m)^2 > 0 \f$,
///   \f$ (dx_1\cdot m)\,((p - x_1(t))\cdot m) > 0 \f$.
/// All vectors are 3-vectors (the 2D scenes live in z = 0).

#include <Eigen/Core>
#include <cmath>

#include "massspring/contact/distance/point_plane.hpp"
#include "massspring/contact/fosssim/polynomial_intervals.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The result of a continuous-time test.
template <class Scalar>
struct TimeOfImpact {
  /// @brief True when the primitives overlap and approach at some t in [0, 1].
  bool hit = false;
  /// @brief The first such t (fraction of the step).
  Scalar time = 0;
  /// @brief The shortest vector from the particle to the other primitive at that time [m].
  Vector3<Scalar> n = Vector3<Scalar>::Zero();
  /// @brief Particle-edge: the closest point's parameter on the edge at that time.
  Scalar alpha = 0;
};

namespace detail {
/// @brief p(t) = a + t b for each coordinate, dotted: (a + t b) . (c + t d).
template <class Scalar>
Polynomial<Scalar> dot_linear(const Vector3<Scalar>& a, const Vector3<Scalar>& b,
                              const Vector3<Scalar>& c, const Vector3<Scalar>& d) {
  return Polynomial<Scalar>::quadratic(a.dot(c), a.dot(d) + b.dot(c), b.dot(d));
}
}  // namespace detail

/// @brief Particles at x1, x2 moving by dx1, dx2 over the step; s = r1 + r2 [m].
template <class Scalar>
TimeOfImpact<Scalar> point_point_time_of_impact(const Vector3<Scalar>& x1,
                                                const Vector3<Scalar>& dx1,
                                                const Vector3<Scalar>& x2,
                                                const Vector3<Scalar>& dx2, Scalar s) {
  using P = Polynomial<Scalar>;
  const Vector3<Scalar> y = x2 - x1, dy = dx2 - dx1;
  const P polys[2] = {P::quadratic(s * s - y.squaredNorm(), -2 * dy.dot(y), -dy.squaredNorm()),
                      P::linear(-dy.dot(y), -dy.squaredNorm())};
  TimeOfImpact<Scalar> r;
  const Scalar t = first_time_all_positive(polys, 2);
  if (!(t <= 1)) return r;
  r.n = y + t * dy;
  r.hit = r.n.squaredNorm() > 0;
  r.time = t;
  return r;
}

/// @brief Particle at x1 (moving by dx1), edge (x2, x3) (moving by dx2, dx3); s = r1 + r_edge.
template <class Scalar>
TimeOfImpact<Scalar> point_edge_time_of_impact(
    const Vector3<Scalar>& x1, const Vector3<Scalar>& dx1, const Vector3<Scalar>& x2,
    const Vector3<Scalar>& dx2, const Vector3<Scalar>& x3, const Vector3<Scalar>& dx3, Scalar s) {
  using P = Polynomial<Scalar>;
  const Vector3<Scalar> A = x1 - x2, dA = dx1 - dx2, B = x3 - x2, dB = dx3 - dx2;
  const P a = detail::dot_linear(A, dA, B, dB);
  const P d = detail::dot_linear(A, dA, A, dA);
  const P g = detail::dot_linear(B, dB, B, dB);
  const P right = a;
  const P left = detail::dot_linear(Vector3<Scalar>(x1 - x3), Vector3<Scalar>(dx1 - dx3),
                                    Vector3<Scalar>(x2 - x3), Vector3<Scalar>(dx2 - dx3));
  const P dist = a * a - d * g + (s * s) * g;
  // approach: (g u - a w) . (a B(t) - g A(t)), u = dA, w = dB; expanded per coordinate
  P vel;
  for (int c = 0; c < 3; ++c) {
    const P first = dA(c) * g - dB(c) * a;
    const P second = a * P::linear(B(c), dB(c)) - g * P::linear(A(c), dA(c));
    vel = vel + first * second;
  }
  const P polys[4] = {dist, right, left, vel};
  TimeOfImpact<Scalar> r;
  const Scalar t = first_time_all_positive(polys, 4);
  if (!(t <= 1)) return r;
  const Vector3<Scalar> At = A + t * dA, Bt = B + t * dB;
  const Scalar gt = Bt.squaredNorm();
  if (!(gt > 0)) return r;
  r.alpha = At.dot(Bt) / gt;
  r.n = r.alpha * Bt - At;  // x2(t) + alpha B(t) - x1(t)
  r.hit = r.n.squaredNorm() > 0;
  r.time = t;
  return r;
}

/// @brief Particle at x1 moving by dx1, and a plane; s = r1 [m].
template <class Scalar>
TimeOfImpact<Scalar> point_plane_time_of_impact(const Vector3<Scalar>& x1,
                                                const Vector3<Scalar>& dx1,
                                                const Plane<Scalar>& plane, Scalar s) {
  using P = Polynomial<Scalar>;
  const Vector3<Scalar>& m = plane.normal;
  const Scalar q = (plane.point - x1).dot(m), dq = dx1.dot(m);  // (p - x(t)).m = q - t dq
  const P polys[2] = {P::quadratic(s * s * m.squaredNorm() - q * q, 2 * q * dq, -dq * dq),
                      P::linear(q * dq, -dq * dq)};
  TimeOfImpact<Scalar> r;
  const Scalar t = first_time_all_positive(polys, 2);
  if (!(t <= 1)) return r;
  r.n = ((q - t * dq) / m.squaredNorm()) * m;
  r.hit = r.n.squaredNorm() > 0;
  r.time = t;
  return r;
}

}  // namespace massspring::contact
