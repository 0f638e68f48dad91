#pragma once
// A one-dimensional oscillator: point 1 (mass m) on a spring (k, rest length L) from point 0,
// pinned at the origin, moving along x. Its force -k u (u = x_1 - L) is linear, so each Euler
// scheme is a 2x2 linear recurrence on (u, w) that the tests iterate independently.
#include <Eigen/Core>
#include <massspring/system/mass_spring_system.hpp>

namespace massspring::test {

template <class System>
System oscillator(double m, double k, double rest, double u0, double w0 = 0) {
  using Scalar = typename System::Scalar;
  Points<Scalar> x = Points<Scalar>::Zero(2, 3);
  x(1, 0) = Scalar(rest);
  Edges e(1, 2);
  e << 0, 1;
  Vector<Scalar> masses(2);
  masses << Scalar(m), Scalar(m);
  System s(x, e, masses, Vector<Scalar>::Constant(1, Scalar(k)));
  s.pin(0);
  Points<Scalar> p = x, v = Points<Scalar>::Zero(2, 3);
  p(1, 0) = Scalar(rest + u0);
  v(1, 0) = Scalar(w0);
  s.set_positions(p);
  s.set_velocities(v);
  return s;
}

/// @brief One step of a scheme's recurrence matrix applied to (u, w).
inline Eigen::Vector2d forward_euler_step(const Eigen::Vector2d& s, double h, double w2) {
  return {s(0) + h * s(1), s(1) - h * w2 * s(0)};
}
inline Eigen::Vector2d symplectic_euler_step(const Eigen::Vector2d& s, double h, double w2) {
  const double w = s(1) - h * w2 * s(0);
  return {s(0) + h * w, w};
}
inline Eigen::Vector2d backward_euler_step(const Eigen::Vector2d& s, double h, double w2) {
  Eigen::Matrix2d a;
  a << 1, -h, h * w2, 1;
  return a.partialPivLu().solve(s);
}

}  // namespace massspring::test
