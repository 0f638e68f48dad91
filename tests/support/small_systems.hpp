#pragma once
// Small systems the integrator tests share: a 1-D oscillator, a circular orbit, a perturbed cloth.
#include <Eigen/Core>
#include <massspring/forces/gravitational_attraction.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <random>

namespace massspring::test {

/// A one-dimensional oscillator: point 1 (mass m) on a spring (k, rest length L) from point 0,
/// pinned at the origin, moving along x. Its force -k u (u = x_1 - L) is linear, so each Euler
/// scheme is a 2x2 linear recurrence on (u, w) that the tests iterate independently.
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

/// Sun (pinned, mass 1) at the origin, planet (mass 1) on a circle of radius 1 with G M = 1:
/// speed 1, period 2 pi. Pinning the sun keeps it fixed, as FOSSSim's AccuracyTests does.
template <class System>
System orbit() {
  using Scalar = typename System::Scalar;
  Points<Scalar> x = Points<Scalar>::Zero(2, 3);
  x(1, 0) = 1;
  System s(x, Edges(0, 2), Scalar(1), Scalar(0));
  s.pin(0);
  Points<Scalar> v = Points<Scalar>::Zero(2, 3);
  v(1, 1) = 1;
  s.set_velocities(v);
  s.add_force(GravitationalAttraction<Scalar>({{0, 1, Scalar(1)}}));
  return s;
}

/// A 6 x 5 cloth (0.5 m x 0.4 m, k = 80 N/m, top corners pinned, Voronoi masses), its free points
/// moved by up to 2 cm at random so that springs are both stretched and compressed.
template <class System>
System perturbed_cloth(unsigned seed = 1, ClothShear shear = ClothShear::Both) {
  ClothOptions o;
  o.columns = 6;
  o.rows = 5;
  o.width = 0.5;
  o.height = 0.4;
  o.stiffness = 80;
  o.shear = shear;
  System s = make_system<System>(make_cloth(o));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  Points<typename System::Scalar> x = s.positions();
  for (int i = 0; i < x.rows(); ++i)
    if (!s.is_pinned(i)) x.row(i) += Eigen::RowVector3d(u(rng), u(rng), u(rng));
  s.set_positions(x);
  return s;
}

}  // namespace massspring::test
