// integrators/detail/commit_step.hpp: StepReport::contact_work, the energy the end-of-step
// collision response adds. Oracle: symplectic Euler's step of one point over a plane collider in
// closed form (v_end = v0 + h F(x0) / m, x_end = x0 + h v_end; the plane's inelastic,
// frictionless response puts the point on the plane at rest), and the energies before and after
// the response computed here by hand: a point that only stops loses its kinetic energy; a point
// that a spring pulls into the plane is pushed back against the spring, which gains more
// potential energy than the point loses kinetic energy.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <massspring/contact/colliders/colliders.hpp>
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
