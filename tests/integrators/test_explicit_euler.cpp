// integrators/forward_euler.hpp, symplectic_euler.hpp: the 1-D spring's exact recurrences, first
// order, orbits, pins, allocation, failure handling, validation.
#include <doctest/doctest.h>

#include <cmath>
#include <massspring/diagnostics/energy.hpp>
#include <massspring/forces/gravitational_attraction.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/integrators/forward_euler.hpp>
#include <massspring/integrators/rk4.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>

#include "support/alloc_counter.hpp"
#include "support/small_systems.hpp"

namespace {

using massspring::Dense;
using massspring::Sparse;
using Pts = massspring::Points<double>;
using SystemD = massspring::MassSpringSystem<double, Dense>;
using SystemS = massspring::MassSpringSystem<double, Sparse>;

template <template <class> class Integrator, class Step>
void check_recurrence(Step scheme) {
  const double m = 0.5, k = 8, h = 0.01, w2 = k / m;
  auto s = massspring::test::oscillator<SystemS>(m, k, 1.0, 0.2, 0.1);
  Integrator<SystemS> integrator;
  integrator.precompute(s, h);
  Eigen::Vector2d expect(0.2, 0.1);
  double worst = 0;
  for (int step = 0; step < 500; ++step) {
    REQUIRE(integrator.step(s).ok());
    expect = scheme(expect, h, w2);
    worst = std::max({worst, std::abs(s.positions()(1, 0) - 1.0 - expect(0)),
                      std::abs(s.velocities()(1, 0) - expect(1))});
    CHECK(s.positions()(0, 0) == 0);  // the pin never moves
  }
  // The recurrence is what the scheme computes, up to rounding over 500 steps.
  CHECK(worst < 1e-12);
}

// Error at t = 1 of the oscillator against cos/sin, for step h.
template <template <class> class Integrator>
double oscillator_error(double h) {
  const double m = 1, k = 4, w = 2;
  auto s = massspring::test::oscillator<SystemS>(m, k, 1.0, 0.1);
  Integrator<SystemS> integrator;
  integrator.precompute(s, h);
  const int steps = int(std::lround(1.0 / h));
  for (int i = 0; i < steps; ++i) integrator.step(s);
  return std::abs(s.positions()(1, 0) - 1.0 - 0.1 * std::cos(w * 1.0));
}

}  // namespace

TEST_CASE("ForwardEuler follows its recurrence u' = u + h w, w' = w - h w0^2 u") {
  check_recurrence<massspring::ForwardEuler>(massspring::test::forward_euler_step);
}

TEST_CASE("SymplecticEuler follows its recurrence w' = w - h w0^2 u, u' = u + h w'") {
  check_recurrence<massspring::SymplecticEuler>(massspring::test::symplectic_euler_step);
}

TEST_CASE("Forward and symplectic Euler are first order: halving h halves the error") {
  for (int scheme = 0; scheme < 2; ++scheme) {
    const auto err = [&](double h) {
      return scheme == 0 ? oscillator_error<massspring::ForwardEuler>(h)
                         : oscillator_error<massspring::SymplecticEuler>(h);
    };
    const double e1 = err(1e-3), e2 = err(5e-4), e3 = err(2.5e-4);
    // First order: the ratio tends to 2 as h -> 0 (the next term shifts it by O(h)).
    CHECK(e1 / e2 == doctest::Approx(2).epsilon(0.02));
    CHECK(e2 / e3 == doctest::Approx(2).epsilon(0.01));
  }
}

TEST_CASE("Orbits: forward Euler spirals out, symplectic Euler stays on the circle") {
  const double h = 1e-3;
  const int steps = int(std::lround(2 * M_PI / h));  // one period
  auto a = massspring::test::orbit<SystemS>();
  auto b = massspring::test::orbit<SystemS>();
  massspring::ForwardEuler<SystemS> fe;
  massspring::SymplecticEuler<SystemS> se;
  fe.precompute(a, h);
  se.precompute(b, h);
  double min_b = 1, max_b = 1;
  for (int i = 0; i < steps; ++i) {
    fe.step(a);
    se.step(b);
    const double rb = b.positions().row(1).norm();
    min_b = std::min(min_b, rb);
    max_b = std::max(max_b, rb);
  }
  const double ra = a.positions().row(1).norm();
  // Forward Euler multiplies r^2 by about (1 + h^2) per step: r grows by ~pi h per period.
  CHECK(ra > 1 + 0.5 * M_PI * h);
  // Symplectic Euler's orbit is a slightly perturbed closed curve: r stays within O(h).
  CHECK(max_b - min_b < 2 * h);
  CHECK(b.positions()(1, 0) == doctest::Approx(1).epsilon(4 * h));
}

TEST_CASE("Symplectic Euler keeps the orbit's energy bounded over 1e5 steps") {
  auto s = massspring::test::orbit<SystemS>();
  massspring::SymplecticEuler<SystemS> se;
  const double h = 1e-2;
  se.precompute(s, h);
  const double e0 = massspring::total_energy(s);  // -1/2
  double worst = 0;
  for (int i = 0; i < 100000; ++i) {
    se.step(s);
    worst = std::max(worst, std::abs(massspring::total_energy(s) - e0));
  }
  // A symplectic method's energy error stays O(h) forever (no drift); forward Euler's grows.
  CHECK(worst < 2 * h * std::abs(e0));
}

TEST_CASE("Explicit Euler: pins stay put, Dense equals Sparse, no allocation in step()") {
  massspring::ClothOptions o;
  o.columns = 6;
  o.rows = 5;
  o.stiffness = 50;
  const auto desc = massspring::make_cloth(o);
  auto d = massspring::make_system<SystemD>(desc);
  auto s = massspring::make_system<SystemS>(desc);
  s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  d.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  massspring::SymplecticEuler<SystemD> id;
  massspring::SymplecticEuler<SystemS> is;
  id.precompute(d, 1e-3);
  is.precompute(s, 1e-3);
  const Pts pins0 = s.positions()(s.pinned(), Eigen::all);
  {
    massspring::test::CountAllocations count;
    for (int i = 0; i < 50; ++i) {
      REQUIRE(id.step(d).ok());
      REQUIRE(is.step(s).ok());
    }
    CHECK(count.count() == 0);
  }
  CHECK(s.positions()(s.pinned(), Eigen::all) == pins0);
  CHECK((d.positions() - s.positions()).cwiseAbs().maxCoeff() < 1e-13);
  CHECK((s.positions() - desc.vertices).cwiseAbs().maxCoeff() > 1e-4);  // it did move
}

namespace {

template <template <class> class Integrator>
void check_copying_commit() {
  massspring::ClothOptions o;
  o.columns = 6;
  o.rows = 5;
  o.stiffness = 50;
  auto swapped = massspring::make_system<SystemS>(massspring::make_cloth(o));
  swapped.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  auto copied = swapped;
  Integrator<SystemS> a, b;
  b.set_swap_buffers(false);
  a.precompute(swapped, 1e-3);
  b.precompute(copied, 1e-3);
  const double* x = copied.positions().data();
  const double* v = copied.velocities().data();
  const double* xs = swapped.positions().data();
  massspring::test::CountAllocations count;
  for (int i = 0; i < 50; ++i) {
    REQUIRE(a.step(swapped).ok());
    if (i == 0) CHECK(swapped.positions().data() != xs);  // the default swapped its arrays in
    REQUIRE(b.step(copied).ok());
    // the copying commit keeps the system's arrays where they were, with the same values
    REQUIRE(copied.positions().data() == x);
    REQUIRE(copied.velocities().data() == v);
    REQUIRE(copied.positions() == swapped.positions());
    REQUIRE(copied.velocities() == swapped.velocities());
  }
  CHECK(count.count() == 0);
}

}  // namespace

TEST_CASE("Explicit integrators: set_swap_buffers(false) copies the same state into place") {
  check_copying_commit<massspring::ForwardEuler>();
  check_copying_commit<massspring::SymplecticEuler>();
  check_copying_commit<massspring::RK4>();
}

TEST_CASE("Explicit Euler: a non-finite result is reported and changes nothing") {
  auto s = massspring::test::oscillator<SystemS>(1, 1, 1, 0.1);
  Pts v = Pts::Zero(2, 3);
  v(1, 0) = 1e308;
  s.set_velocities(v);
  massspring::ForwardEuler<SystemS> fe;
  fe.precompute(s, 10.0);
  const Pts x0 = s.positions();
  const auto r = fe.step(s);
  CHECK_FALSE(r.ok());
  CHECK(s.positions() == x0);
  CHECK(s.velocities() == v);
}

TEST_CASE("Explicit Euler: refuses bad dt, step before precompute, a resized system") {
  auto s = massspring::test::oscillator<SystemS>(1, 1, 1, 0.1);
  massspring::ForwardEuler<SystemS> fe;
  CHECK_THROWS_WITH_AS(fe.step(s), "ForwardEuler: step() before precompute()", massspring::Error);
  CHECK_THROWS_WITH_AS(fe.precompute(s, 0.0), "ForwardEuler: dt must be finite and > 0, got 0",
                       massspring::Error);
  CHECK_THROWS_AS(fe.precompute(s, NAN), massspring::Error);
  fe.precompute(s, 0.1);
  auto bigger = massspring::test::oscillator<SystemS>(1, 1, 1, 0.1);
  Pts x = Pts::Zero(3, 3);
  x(1, 0) = 1;
  x(2, 0) = 2;
  SystemS three(x, massspring::Edges(0, 2), 1.0, 1.0);
  CHECK_THROWS_WITH_AS(fe.step(three),
                       "ForwardEuler: the system has 3 points, precompute() saw 2; call "
                       "precompute() again",
                       massspring::Error);
}

TEST_CASE("Every integrator steps a system with no points (nothing to do, not a crash)") {
  const auto check = [](auto integrator) {
    SystemS s(Pts(0, 3), massspring::Edges(0, 2), 1.0, 1.0);
    integrator.precompute(s, 0.1);
    CHECK(integrator.step(s).ok());
    CHECK(s.num_points() == 0);
  };
  check(massspring::ForwardEuler<SystemS>{});
  check(massspring::SymplecticEuler<SystemS>{});
  check(massspring::BackwardEuler<SystemS>{});
  check(massspring::FastMassSpring<SystemS>{});
}
