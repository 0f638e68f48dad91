// integrators/detail/energy_bound.hpp: every integrator refuses a step whose end state's energy
// passes its start energy + growth (S + S_c), and leaves the state before it. Oracle: forward Euler on a harmonic
// anchor multiplies the energy by exactly (1 + h^2 omega^2) per step, so the step that first
// passes the limit is known in closed form; a term that pumps energy trips every integrator; a
// long free fall, whose energy is conserved or dissipated, never does.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <massspring/error.hpp>
#include <massspring/forces/force_term.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/forward_euler.hpp>
#include <massspring/integrators/local_global/fast_mass_spring.hpp>
#include <massspring/integrators/rk4.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>

namespace energy_bound_test {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Pts = massspring::Points<double>;

// F_i = -kappa x_i, energy kappa |x_i|^2 / 2: a linear spring to the origin [N/m].
struct Anchor {
  double kappa = 1;
  const char* name() const { return "anchor"; }
  void add_force(const massspring::ForceContext<double>& c, Pts& f) const { f -= kappa * c.x; }
  double energy(const massspring::ForceContext<double>& c) const {
    return 0.5 * kappa * c.x.squaredNorm();
  }
  void add_dfdx(const massspring::ForceContext<double>& c,
                massspring::JacobianSink<double>& j) const {
    for (int i = 0; i < int(c.x.rows()); ++i)
      for (int k = 0; k < 3; ++k) j.add(3 * i + k, 3 * i + k, -kappa);
  }
};

// F_i = +c v_i: anti-damping, which adds energy at every step of every integrator.
struct Pump {
  double c = 1;  // [N s/m]
  const char* name() const { return "pump"; }
  static constexpr bool velocity_dependent = true;
  void add_force(const massspring::ForceContext<double>& ctx, Pts& f) const { f += c * ctx.v; }
  void add_dfdv(const massspring::ForceContext<double>& ctx,
                massspring::JacobianSink<double>& j) const {
    for (int i = 0; i < int(ctx.x.rows()); ++i)
      for (int k = 0; k < 3; ++k) j.add(3 * i + k, 3 * i + k, c);
  }
};

// One point of mass m at (1, 0, 0), at rest, on the anchor: omega^2 = kappa / m.
System anchored_point(double m, double kappa) {
  Pts x = Pts::Zero(1, 3);
  x(0, 0) = 1;
  System s(x, massspring::Edges(0, 2), m, 0.0);
  s.add_force(Anchor{kappa});
  return s;
}

// The first step n whose gain passes the limit: the energy after step n is E(0) (1 + q)^n, so
// step n gains E(0) (1 + q)^(n-1) q, and with no springs, one point and no collider
// S = |E(0)| (the bounding box has no diagonal, K(0) = 0) and S_c = 0: the first n with
// (1 + q)^(n-1) > growth / q.
int first_blow_up(double q, double growth) {
  return int(std::floor(std::log(growth / q) / std::log1p(q))) + 2;
}

TEST_CASE("energy bound: forward Euler blows up at the step the closed form gives") {
  const double m = 2, kappa = 50, h = std::sqrt(0.1 * m / kappa);  // h^2 omega^2 = 0.1
  for (double growth : {100.0, 1000.0}) {
    CAPTURE(growth);
    System s = anchored_point(m, kappa);
    massspring::ForwardEuler<System> fe;
    fe.set_energy_growth(growth);
    fe.precompute(s, h);
    const int expected = first_blow_up(0.1, growth);  // 74 for 100, 98 for 1000
    CHECK(expected == (growth == 100 ? 74 : 98));
    Pts last;
    int n = 1;
    for (; n <= expected + 5; ++n) {
      last = s.positions();
      const Pts v = s.velocities();
      const massspring::StepReport r = fe.step(s);
      if (!r.ok()) {
        CHECK(r.blew_up);
        CHECK(r.finite);
        CHECK(s.positions() == last);  // the state before the step, bit for bit
        CHECK(s.velocities() == v);
        break;
      }
    }
    CHECK(n == expected);
  }
}

TEST_CASE(
    "energy bound: growth 0 (the explicit integrators' default) turns it off; symplectic Euler and "
    "RK4 stay within it") {
  const double m = 2, kappa = 50, h = std::sqrt(0.1 * m / kappa);
  System s = anchored_point(m, kappa);
  massspring::ForwardEuler<System> fe;  // the default: no bound
  fe.precompute(s, h);
  for (int n = 0; n < 100; ++n) REQUIRE(fe.step(s).ok());
  CHECK(s.positions().norm() > 10);  // (1.1)^50 times the start amplitude: no check stopped it

  System a = anchored_point(m, kappa), b = anchored_point(m, kappa);
  massspring::SymplecticEuler<System> se;  // h omega = 0.32 < 2: bounded energy
  massspring::RK4<System> rk;
  se.set_energy_growth(100);
  rk.set_energy_growth(100);
  se.precompute(a, h);
  rk.precompute(b, h);
  for (int n = 0; n < 2000; ++n) {
    REQUIRE(se.step(a).ok());
    REQUIRE(rk.step(b).ok());
  }
}

TEST_CASE("energy bound: an energy pump trips every integrator, which keeps the last state") {
  const double h = 1.0 / 30, m = 0.1;
  const auto make = [&] {
    System s = anchored_point(m, 1.0);
    Pts v = Pts::Zero(1, 3);
    v(0, 1) = 1;
    s.set_velocities(v);
    // h c / m = 1/2: an implicit step doubles the velocity, an explicit one multiplies it by 1.5.
    s.add_force(Pump{0.5 * m / h});
    return s;
  };
  const auto run = [&](auto& integrator, const char* who) {
    CAPTURE(who);
    System s = make();
    integrator.precompute(s, h);
    int n = 0;
    for (; n < 2000; ++n) {
      const Pts x = s.positions();
      const massspring::StepReport r = integrator.step(s);
      if (!r.ok()) {
        CHECK(r.blew_up);
        CHECK(r.finite);
        CHECK(s.positions() == x);
        break;
      }
    }
    CHECK(n < 100);
  };
  massspring::FastMassSpring<System> fms;
  run(fms, "FastMassSpring");
  massspring::BackwardEuler<System> be;
  run(be, "BackwardEuler");
  massspring::SymplecticEuler<System> se;
  se.set_energy_growth(100);  // off by default for the explicit integrators
  run(se, "SymplecticEuler");
}

TEST_CASE("energy bound: a 20 s free fall with the defaults never trips it") {
  massspring::ClothOptions o;
  o.columns = o.rows = 8;
  o.pins = massspring::ClothPins::None;
  const auto make = [&] {
    System s = massspring::make_system<System>(massspring::make_cloth(o));
    s.add_force(massspring::Gravity<double>({0, -9.8, 0}));
    return s;
  };
  const double h = 1.0 / 30;
  System a = make(), b = make();
  massspring::FastMassSpring<System> fms;
  massspring::BackwardEuler<System> be;
  fms.precompute(a, h);
  be.precompute(b, h);
  for (int n = 0; n < 600; ++n) {
    REQUIRE(fms.step(a).ok());
    REQUIRE(be.step(b).ok());
  }
  // Fell 0.5 g t^2 = 1960 m, less what the implicit steps' damping of the fall takes.
  CHECK(a.positions().col(1).mean() < -1900);
  CHECK(b.positions().col(1).mean() < -1900);
}

TEST_CASE("energy bound: growth is validated") {
  System s = anchored_point(1, 1);
  massspring::ForwardEuler<System> fe;
  CHECK_THROWS_AS(fe.set_energy_growth(-1), massspring::Error);
  CHECK_THROWS_AS(fe.set_energy_growth(NAN), massspring::Error);
  massspring::FastMassSpring<System> fms;
  fms.options.energy_growth = -1;
  CHECK_THROWS_WITH_AS(fms.precompute(s, 0.01), doctest::Contains("energy_growth"),
                       massspring::Error);
  massspring::BackwardEuler<System> be;
  be.options.energy_growth = INFINITY;
  CHECK_THROWS_WITH_AS(be.precompute(s, 0.01), doctest::Contains("energy_growth"),
                       massspring::Error);
}

}  // namespace energy_bound_test
