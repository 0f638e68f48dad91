// integrators/detail/commit_step.hpp: StepReport::contact_work, the energy the end-of-step
// collision response adds. Oracle: symplectic Euler's step of one point over a plane collider in
// closed form (v_end = v0 + h F(x0) / m, x_end = x0 + h v_end; the plane's inelastic,
// frictionless response puts the point on the plane at rest), and the energies before and after
// the response computed here by hand: a point that only stops loses its kinetic energy; a point
// that a spring pulls into the plane is pushed back against the spring, which gains more
// potential energy than the point loses kinetic energy. And the energy bound's contact limit
// (energy_bound.hpp): a response that adds more than S / 2 + S_c refuses the step (a rising
// plane pressing a point against a spring), S and S_c computed here by hand from the start state.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <massspring/contact/colliders/colliders.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/symplectic_euler.hpp>

namespace commit_step_test {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using V3 = Eigen::Vector3d;

// Point 1 (mass m) at height 0.05 m above the plane y = 0, moving at v0, and point 0 pinned at
// `anchor`, joined by a spring of stiffness k and rest length l0.
System over_plane(const V3& anchor, double l0, double m, double k, const V3& v0,
                  bool plane = true) {
  massspring::Points<double> x(2, 3);
  x.row(0) = anchor.transpose();
  x.row(1) << 0, 0.05, 0;
  massspring::Edges springs(1, 2);
  springs << 0, 1;
  System s(x, springs, m, k);
  s.set_rest_lengths(Eigen::VectorXd::Constant(1, l0));
  s.pin(0);
  s.velocities().row(1) = v0.transpose();
  if (plane) s.add_collider(massspring::contact::Collider<double>::plane(V3::Zero(), V3(0, 1, 0)));
  return s;
}

double spring_energy(double k, double l, double l0) { return 0.5 * k * (l - l0) * (l - l0); }

// A point at rest at y = 0.1 on a spring at rest (k = 10^4 N/m, l0 = 0.1 m) from a pin at
// y = 0.2, each of mass 1 kg, no force; the plane y = 0 rises at V m/s. One backward Euler step
// of 1 s, the contact term off (so that only the end-of-step response sees the plane), with
// the energy bound at `growth`: the solve leaves everything at rest (E = 0), and the plane's
// response puts the point on the plane at y = V, moving at V, the spring V - 0.1 shorter.
System under_rising_plane(double V) {
  massspring::Points<double> x(2, 3);
  x << 0, 0.2, 0, 0, 0.1, 0;
  massspring::Edges springs(1, 2);
  springs << 0, 1;
  System s(x, springs, 1.0, 1e4);
  s.pin(0);
  s.add_collider(massspring::contact::Collider<double>::plane(V3::Zero(), V3(0, 1, 0))
                     .set_velocity(V3(0, V, 0)));
  return s;
}
massspring::StepReport step_under_rising_plane(System& s, double growth) {
  massspring::BackwardEuler<System> solver;
  solver.options.contact_weight = 0;
  solver.options.energy_growth = growth;
  solver.precompute(s, 1.0);
  return solver.step(s);
}
// The response's work in closed form: the spring's energy at length 0.2 - V plus the point's
// kinetic energy, m V^2 / 2 (E before it: 0).
double rising_plane_work(double V) { return spring_energy(1e4, 0.2 - V, 0.1) + 0.5 * V * V; }
// The contact limit S / 2 + S_c (energy_bound.hpp) of the start state: S = k l0^2 / 2 (at rest,
// no force: E = K = 0), S_c = 2 M V^2 with M = 2 kg.
double rising_plane_limit(double V) { return 0.5 * (0.5 * 1e4 * 0.01) + 2 * 2 * V * V; }

}  // namespace commit_step_test

using namespace commit_step_test;

TEST_CASE("contact_work: a point stopped by a plane loses its kinetic energy, m |v|^2 / 2") {
  // No spring force (stiffness 0): the proposed end is 0.25 m below the plane at 3 m/s.
  const double m = 2, h = 0.1;
  System s = over_plane(V3(0, 1, 0), 0.95, m, 0.0, V3(0, -3, 0));
  massspring::SymplecticEuler<System> solver;
  solver.precompute(s, h);
  const massspring::StepReport r = solver.step(s);
  REQUIRE(r.ok());
  CHECK(std::abs(s.positions()(1, 1)) <= 1e-12);
  CHECK(s.velocities().row(1).norm() <= 1e-12);
  CHECK(r.contact_work == doctest::Approx(-0.5 * m * 9).epsilon(1e-12));
}

TEST_CASE("contact_work: a plane that pushes a point back against a spring adds energy") {
  // The spring (k = 100 N/m, l0 = 0.5 m) from the pin at y = -1 holds 1.05 m, pulling the point
  // down with 55 N: v_end = -2.75 m/s, x_end = 0.05 - 0.275 = -0.225 m (length 0.775 m). The
  // response puts it at y = 0 at rest (length 1 m).
  const double m = 2, k = 100, l0 = 0.5, h = 0.1;
  System s = over_plane(V3(0, -1, 0), l0, m, k, V3::Zero());
  massspring::SymplecticEuler<System> solver;
  solver.precompute(s, h);
  const massspring::StepReport r = solver.step(s);
  REQUIRE(r.ok());
  const double proposed = spring_energy(k, 0.775, l0) + 0.5 * m * 2.75 * 2.75;  // 11.34375 J
  const double after = spring_energy(k, 1.0, l0);                               // 12.5 J
  CHECK(std::abs(s.positions()(1, 1)) <= 1e-12);
  CHECK(r.contact_work == doctest::Approx(after - proposed).epsilon(1e-9));
  CHECK(r.contact_work > 1);
}

TEST_CASE("contact_work: 0 without a collision response") {
  const double h = 0.1;
  System s = over_plane(V3(0, -1, 0), 0.5, 2, 100, V3::Zero(), false);
  massspring::SymplecticEuler<System> solver;
  solver.precompute(s, h);
  const massspring::StepReport r = solver.step(s);
  REQUIRE(r.ok());
  CHECK(s.positions()(1, 1) == doctest::Approx(-0.225));  // fell through where the plane was
  CHECK(r.contact_work == 0);
}

TEST_CASE("contact_work above S / 2 + S_c: the step is refused as a blow-up, the state kept") {
  // V = 0.19 m/s: the spring is pressed to 1 cm, 40.5 J, against a limit of 25.1 J.
  const double V = 0.19;
  REQUIRE(rising_plane_work(V) > 1.5 * rising_plane_limit(V));
  System s = under_rising_plane(V);
  const massspring::Points<double> before = s.positions();
  const massspring::StepReport r = step_under_rising_plane(s, 100);
  CHECK(r.blew_up);
  CHECK_FALSE(r.ok());
  CHECK(r.finite);
  CHECK(r.contact_resolved);
  CHECK(r.contact_work == doctest::Approx(rising_plane_work(V)).epsilon(1e-9));
  CHECK(s.positions() == before);
  CHECK(s.velocities().isZero(0));

  // With the energy bound off (growth 0) the same step is committed.
  System off = under_rising_plane(V);
  const massspring::StepReport r0 = step_under_rising_plane(off, 0);
  CHECK(r0.ok());
  CHECK(off.positions()(1, 1) == doctest::Approx(V).epsilon(1e-12));
  CHECK(r0.contact_work == doctest::Approx(rising_plane_work(V)).epsilon(1e-9));
}

TEST_CASE("contact_work below S / 2 + S_c: the step is committed") {
  // V = 0.16 m/s: 18 J against a limit of 25.1 J.
  const double V = 0.16;
  REQUIRE(rising_plane_work(V) < 0.8 * rising_plane_limit(V));
  System s = under_rising_plane(V);
  const massspring::StepReport r = step_under_rising_plane(s, 100);
  CHECK(r.ok());
  CHECK(s.positions()(1, 1) == doctest::Approx(V).epsilon(1e-12));
  CHECK(r.contact_work == doctest::Approx(rising_plane_work(V)).epsilon(1e-9));
}
