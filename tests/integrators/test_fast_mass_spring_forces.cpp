// integrators/fast_mass_spring.hpp with the system's force terms: constant forces exactly (the
// centre of mass follows implicit Euler's closed form), linear drag folded into Q exactly (the
// converged step equals Newton backward Euler's), other terms at the step's start (a closed form
// for one free point).
#include <doctest/doctest.h>

#include <cmath>
#include <massspring/forces/gravity.hpp>
#include <massspring/forces/linear_drag.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <random>

#include "support/small_systems.hpp"

namespace {

using massspring::FastMassSpring;
using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Pts = massspring::Points<double>;

// The cloth of support/small_systems.hpp with the generator's default shear.
System cloth(unsigned seed = 2) {
  return massspring::test::perturbed_cloth<System>(seed, massspring::ClothOptions{}.shear);
}

// A user's term: a linear tether to the origin, F = -c x (not constant: it depends on x).
struct Tether {
  double c = 3;
  void add_force(const massspring::ForceContext<double>& ctx, Pts& f) const { f -= c * ctx.x; }
};

}  // namespace

TEST_CASE("FastMassSpring: Gravity and ConstantForce are exact: the centre of mass is a particle") {
  // Springs are internal forces and each global solve keeps sum_i m_i x_i exact (the springs' part
  // of Q has zero column sums), so after any number of iterations the centre of mass of a free
  // system moves as one particle of mass M = sum_i m_i under F = M g + n f, by implicit Euler:
  // v' = v + h F / M, x' = x + h v'.
  Pts rest(5, 3);
  rest << 0, 0, 0, 0.3, 0.05, 0, 0.55, -0.1, 0.1, 0.9, 0, 0.05, 1.2, 0.1, 0;
  massspring::Edges springs(5, 2);
  springs << 0, 1, 1, 2, 2, 3, 3, 4, 0, 2;
  Eigen::VectorXd masses(5);
  masses << 1, 2, 3, 2, 0.5;
  System s(rest, springs, masses, Eigen::VectorXd::Constant(5, 400.0));
  s.set_rest_lengths(s.rest_lengths() * 0.8);  // stretched: the springs pull from the start
  Pts v(5, 3);
  v << 0.1, 0, 0, 0, 0.2, 0, -0.1, 0, 0.3, 0, 0, 0, 0.5, -0.2, 0;
  s.set_velocities(v);
  const Eigen::RowVector3d g(0, -9.8, 0.5), f(0.3, 0.1, -0.2);
  s.add_force(massspring::Gravity<double>(g.transpose()));
  s.add_force(massspring::ConstantForce<double>(f.transpose()));
  const double h = 1.0 / 30, total = masses.sum();
  const auto centre = [&](const Pts& p) -> Eigen::RowVector3d {
    return (masses.transpose() * p) / total;
  };
  Eigen::RowVector3d x = centre(s.positions()), u = centre(s.velocities());
  const Eigen::RowVector3d a = g + 5 * f / total;
  FastMassSpring<System> solver;
  solver.options.iterations = 3;  // far from converged: the oracle holds at every iteration
  solver.precompute(s, h);
  for (int step = 0; step < 20; ++step) {
    REQUIRE(solver.step(s).ok());
    u += h * a;
    x += h * u;
    CAPTURE(step);
    CHECK((centre(s.positions()) - x).norm() <= 1e-12 * (1 + x.norm()));
    CHECK((centre(s.velocities()) - u).norm() <= 1e-11 * (1 + u.norm()));
  }
}

TEST_CASE("FastMassSpring: linear drag is folded into Q exactly (converged = Newton's step)") {
  System a = cloth(), b = cloth();
  for (System* s : {&a, &b}) {
    s->add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
    s->add_force(massspring::LinearDrag<double>(0.02));
  }
  FastMassSpring<System> lg;
  lg.options.iterations = 20000;
  lg.options.tolerance = 0;
  const double h = 1.0 / 30;
  lg.precompute(a, h);
  massspring::BackwardEuler<System> be;
  be.options.tolerance = 1e-13;
  be.precompute(b, h);
  double previous = INFINITY;
  for (int step = 0; step < 3; ++step) {
    const auto r = lg.step(a);
    REQUIRE(r.ok());
    REQUIRE(be.step(b).converged);
    // Both minimise the incremental potential with beta/(2h)|x - x^t|^2; to rounding.
    CHECK((a.positions() - b.positions()).cwiseAbs().maxCoeff() < 1e-12);
    previous = r.energy;
  }
  CHECK(std::isfinite(previous));
}

TEST_CASE("FastMassSpring: with drag the energy still never increases over iterations") {
  System s = cloth(5);
  s.add_force(massspring::LinearDrag<double>(0.5));
  s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  FastMassSpring<System> lg;
  lg.options.tolerance = 0;
  lg.precompute(s, 1.0 / 30);
  double last = INFINITY;
  for (int iterations = 1; iterations <= 30; ++iterations) {
    System t = s;
    lg.options.iterations = iterations;
    const auto r = lg.step(t);
    REQUIRE(r.ok());
    // E after k + 1 iterations <= E after k (relative slack for rounding of ~|E| eps).
    CHECK(r.energy <= last + 1e-12 * std::abs(last));
    last = r.energy;
  }
}

TEST_CASE("FastMassSpring: other terms act at the step's start (closed form, one free point)") {
  // One point, no springs: the step minimises m/(2h^2)|x - y|^2 - x . F(x^t) with y = x + h v, so
  // x' = x + h v + h^2/m F(x^t), v' = (x' - x)/h: symplectic Euler's position update.
  Pts x(1, 3);
  x << 0.3, -0.2, 0.5;
  System s(x, massspring::Edges(0, 2), 2.0, 0.0);
  Pts v(1, 3);
  v << 0.1, 0.4, -0.3;
  s.set_velocities(v);
  s.add_force(Tether{});
  FastMassSpring<System> lg;
  lg.options.iterations = 3;
  const double h = 0.05;
  lg.precompute(s, h);
  REQUIRE(lg.step(s).ok());
  const Pts expect = x + h * v + h * h / 2.0 * (-3 * x);
  CHECK((s.positions() - expect).cwiseAbs().maxCoeff() < 1e-15);
  CHECK((s.velocities() - (expect - x) / h).cwiseAbs().maxCoeff() < 1e-13);
}

TEST_CASE("FastMassSpring: adding a drag term makes the next step factorize again") {
  System s = cloth();
  FastMassSpring<System> lg;
  lg.precompute(s, 1.0 / 30);
  CHECK_FALSE(lg.step(s).refactorized);
  s.add_force(massspring::LinearDrag<double>(0.1));
  CHECK(lg.step(s).refactorized);
  CHECK_FALSE(lg.step(s).refactorized);
}
