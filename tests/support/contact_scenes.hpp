#pragma once
// Contact scenes the tests of contact inside a solve share (FastMassSpring's and BackwardEuler's
// contact_weight), at the large step dt = 1/30 s, with their closed forms: a block on an incline,
// a cloth dropped on a (turning) ball over a floor.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <massspring/contact/colliders/colliders.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/system/mass_spring_system.hpp>

namespace massspring::test {

using ContactSystem = MassSpringSystem<double, Sparse>;

constexpr double kContactG = 9.81;
constexpr double kContactDt = 1.0 / 30;

/// Two points of 0.5 kg, 0.1 m apart along z, joined by a spring (k = 100 N/m) at its rest
/// length, on the plane through the origin with normal n = (sin t, cos t, 0), friction mu, under
/// gravity (0, -g, 0).
inline ContactSystem incline_block(double theta, double mu) {
  using V3 = Eigen::Vector3d;
  Points<double> p(2, 3);
  p.row(0) = V3(0, 0, 0).transpose();
  p.row(1) = V3(0, 0, 0.1).transpose();
  Edges e(1, 2);
  e << 0, 1;
  ContactSystem s(p, e, 0.5, 100.0);
  s.add_force(Gravity<double>(V3(0, -kContactG, 0)));
  const V3 n(std::sin(theta), std::cos(theta), 0);
  s.colliders()[s.add_collider(contact::Collider<double>::plane(V3::Zero(), n))].set_friction(mu);
  return s;
}

/// Distance slid downhill (along (cos t, -sin t, 0)) by point 0 of an incline_block after
/// `steps` steps of a solver with precompute() and step().
template <class Solver>
double incline_slide(ContactSystem& s, Solver& solver, double theta, int steps) {
  const Eigen::Vector3d down(std::cos(theta), -std::sin(theta), 0);
  const Eigen::Vector3d start = s.positions().row(0).transpose();
  solver.precompute(s, kContactDt);
  for (int k = 0; k < steps; ++k)
    if (!solver.step(s).ok()) return std::nan("");
  return (s.positions().row(0).transpose() - start).dot(down);
}

/// The largest coordinate change [m] of an incline_block's points from where they start, over
/// `steps` steps of a solver with precompute() and step() (NaN when a step fails): what static
/// friction must keep at 0.
template <class Solver>
double incline_hold(ContactSystem& s, Solver& solver, int steps) {
  const Points<double> x0 = s.positions();
  solver.precompute(s, kContactDt);
  double moved = 0;
  for (int k = 0; k < steps; ++k) {
    if (!solver.step(s).ok()) return std::nan("");
    moved = std::max(moved, (s.positions() - x0).cwiseAbs().maxCoeff());
  }
  return moved;
}

/// Oracle: implicit Euler with Coulomb friction moves a body under constant forces by
/// s_N = a h^2 N (N + 1) / 2 after N steps from rest (x advances by the new velocity, which grows
/// by h a per step), a = g (sin t - mu cos t).
inline double discrete_slide(double theta, double mu, int steps) {
  const double a = kContactG * (std::sin(theta) - mu * std::cos(theta));
  return a * kContactDt * kContactDt * steps * (steps + 1) / 2;
}

/// The 2 m x 2 m cloth of the drape benchmark (1.9 kg, k = 1000 N/m, one diagonal per cell),
/// `n` x `n` points, held flat 5 cm above a ball of radius 0.5 m at the origin (friction `mu`,
/// turning at `omega` rad/s about +y), over a floor at y = -1.
inline ContactSystem cloth_over_ball(int n, double mu, double omega) {
  using V3 = Eigen::Vector3d;
  ClothOptions o;
  o.columns = n;
  o.rows = n;
  o.width = 2;
  o.height = 2;
  o.stiffness = 1000;
  o.mass = 1.9 / (n * n);
  o.shear = ClothShear::One;
  o.pins = ClothPins::None;
  o.plane = ClothPlane::Horizontal;
  o.center = V3(0, 0.55, 0);
  ContactSystem s = make_system<ContactSystem>(make_cloth(o));
  s.add_force(Gravity<double>(V3(0, -kContactG, 0)));
  auto& ball = s.colliders()[s.add_collider(contact::Collider<double>::sphere(V3::Zero(), 0.5))];
  ball.set_friction(mu).set_angular_velocity(V3(0, omega, 0));
  s.colliders()[s.add_collider(contact::Collider<double>::plane(V3(0, -1, 0), V3(0, 1, 0)))]
      .set_friction(mu);
  return s;
}

/// The points of a cloth_over_ball resting on the ball's upper half (within 1 cm of its surface):
/// their velocity against the surface's, omega x x (about +y), on average, relative to the
/// surface's speed; `resting` gets how many there are.
inline double lag_behind_surface(const ContactSystem& s, double omega, int& resting) {
  using V3 = Eigen::Vector3d;
  double difference = 0, surface = 0;
  resting = 0;
  for (int i = 0; i < s.num_points(); ++i) {
    const V3 x = s.positions().row(i).transpose();
    if (!(x.norm() < 0.51 && x.y() > 0.2)) continue;
    const V3 u = V3(0, omega, 0).cross(x);
    difference += (s.velocities().row(i).transpose() - u).norm();
    surface += u.norm();
    ++resting;
  }
  return difference / surface;
}

struct Strain {
  double mean = 0, max = 0;
};
/// |length / rest length - 1| over the springs: mean and max.
inline Strain strain_of(const ContactSystem& s) {
  Strain r;
  for (int e = 0; e < s.num_springs(); ++e) {
    const double length =
        (s.positions().row(s.springs()(e, 0)) - s.positions().row(s.springs()(e, 1))).norm();
    const double strain = std::abs(length / s.rest_lengths()(e) - 1);
    r.mean += strain;
    r.max = std::max(r.max, strain);
  }
  r.mean /= s.num_springs();
  return r;
}

/// The dual variables are the state a contact term carries from step to step: a cloth_over_ball
/// (n x n, mu 0.5, turning at 1 rad/s) run stopped after 10 steps and continued by a new solver
/// from a copy of the system and the duals gives the uninterrupted run's 20 steps bit for bit
/// (positions, velocities, duals); without the duals it does not. `Solver` is FastMassSpring or
/// BackwardEuler, built from `options`.
template <class Solver, class Options>
void check_resume_with_duals(const Options& options, int n) {
  ContactSystem whole = cloth_over_ball(n, 0.5, 1);
  Solver first(options);
  first.precompute(whole, kContactDt);
  for (int k = 0; k < 10; ++k) REQUIRE(first.step(whole).ok());
  const Points<double> duals = first.contact_duals();
  REQUIRE(duals.rows() == whole.num_points());
  CHECK(duals.cwiseAbs().maxCoeff() > 0);  // the cloth rests on the ball: the term acts
  ContactSystem resumed = whole, without = whole;
  for (int k = 0; k < 10; ++k) REQUIRE(first.step(whole).ok());

  Solver second(options), third(options);
  second.precompute(resumed, kContactDt);
  CHECK(second.contact_duals().cwiseAbs().maxCoeff() == 0);  // precompute() starts from 0
  second.set_contact_duals(duals);
  CHECK(second.contact_duals() == duals);
  third.precompute(without, kContactDt);
  for (int k = 0; k < 10; ++k) {
    REQUIRE(second.step(resumed).ok());
    REQUIRE(third.step(without).ok());
  }
  CHECK(resumed.positions() == whole.positions());
  CHECK(resumed.velocities() == whole.velocities());
  CHECK(second.contact_duals() == first.contact_duals());
  CHECK((without.positions() - whole.positions()).cwiseAbs().maxCoeff() > 0);
}

}  // namespace massspring::test
