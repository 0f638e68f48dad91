// integrators/rk4.hpp: the oscillator's exact RK4 recurrence, fourth order on the oscillator and
// on the circular orbit, pins, allocation, failure handling, validation.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/rk4.hpp>

#include "support/alloc_counter.hpp"
#include "support/small_systems.hpp"

namespace {

using massspring::Dense;
using massspring::Sparse;
using SystemD = massspring::MassSpringSystem<double, Dense>;
using SystemS = massspring::MassSpringSystem<double, Sparse>;
using SystemF = massspring::MassSpringSystem<float, Sparse>;

// RK4's amplification matrix on the oscillator (u, w)' = A (u, w), A = [0 1; -w0^2 0]: the
// degree-4 Taylor polynomial of exp(hA), built here from Eigen 2x2 products, independently of
// the integrator's stages.
Eigen::Matrix2d rk4_matrix(double h, double w2) {
  Eigen::Matrix2d a;
  a << 0, 1, -w2, 0;
  const Eigen::Matrix2d ha = h * a;
  const Eigen::Matrix2d ha2 = ha * ha;
  const Eigen::Matrix2d ha3 = ha2 * ha;
  const Eigen::Matrix2d ha4 = ha3 * ha;
  return Eigen::Matrix2d::Identity() + ha + ha2 / 2 + ha3 / 6 + ha4 / 24;
}

// Largest deviation of the oscillator's (u, w) from the RK4 recurrence over `steps` steps,
// relative to the amplitude sqrt(u0^2 + (w0 / w)^2).
template <class System>
double recurrence_deviation(int steps) {
  const double m = 0.5, k = 8, h = 0.01, w2 = k / m, u0 = 0.2, w0 = 0.1;
  auto s = massspring::test::oscillator<System>(m, k, 1.0, u0, w0);
  massspring::RK4<System> rk4;
  rk4.precompute(s, typename System::Scalar(h));
  const Eigen::Matrix2d r = rk4_matrix(h, w2);
  Eigen::Vector2d expect(u0, w0);
  const double amplitude = std::sqrt(u0 * u0 + w0 * w0 / w2);
  double worst = 0;
  for (int step = 0; step < steps; ++step) {
    REQUIRE(rk4.step(s).ok());
    expect = r * expect;
    const double u = double(s.positions()(1, 0)) - 1.0, w = double(s.velocities()(1, 0));
    worst = std::max({worst, std::abs(u - expect(0)) / amplitude,
                      std::abs(w - expect(1)) / (std::sqrt(w2) * amplitude)});
    CHECK(s.positions().row(0).isZero(0));  // the pin never moves
    // Motion stays on the x axis.
    CHECK(s.positions().col(1).isZero(0));
    CHECK(s.positions().col(2).isZero(0));
  }
  return worst;
}

// A float copy of a double system (perturbed_cloth is written for double).
SystemF to_float(const SystemS& d) {
  SystemF f(d.rest_positions().cast<float>(), d.springs(), d.masses().cast<float>(),
            d.stiffness().cast<float>());
  f.pin(d.pinned());
  f.set_positions(d.positions());
  return f;
}

// Error at t = 1 of the oscillator (m = 1, k = 4: w0 = 2) against 0.1 cos(2 t), for step h.
double oscillator_error(double h) {
  auto s = massspring::test::oscillator<SystemS>(1, 4, 1.0, 0.1);
  massspring::RK4<SystemS> rk4;
  rk4.precompute(s, h);
  const int steps = int(std::lround(1.0 / h));
  for (int i = 0; i < steps; ++i) REQUIRE(rk4.step(s).ok());
  return std::abs(s.positions()(1, 0) - 1.0 - 0.1 * std::cos(2.0));
}

// Distance of the planet from its start (1, 0, 0) after one period 2 pi, in `steps` steps.
double orbit_error(int steps) {
  auto s = massspring::test::orbit<SystemS>();
  massspring::RK4<SystemS> rk4;
  rk4.precompute(s, 2 * M_PI / steps);
  for (int i = 0; i < steps; ++i) REQUIRE(rk4.step(s).ok());
  return (s.positions().row(1) - Eigen::RowVector3d(1, 0, 0)).norm();
}

}  // namespace

TEST_CASE("rk4: each step is the exact RK4 recurrence I + hA + (hA)^2/2 + (hA)^3/6 + (hA)^4/24") {
  // Double: rounding only (each step rounds x = 1 + u, ~1e-16 relative); measured 6e-14.
  CHECK(recurrence_deviation<SystemS>(2000) < 1e-12);
  CHECK(recurrence_deviation<SystemD>(2000) < 1e-12);
  // Float: the same recurrence to float rounding (about 1e-7 per step, 200 steps); measured
  // 1e-6.
  CHECK(recurrence_deviation<SystemF>(200) < 1e-5);
}

TEST_CASE("rk4: fourth order on the oscillator: halving h divides the error by 16") {
  // Errors measured 6.4e-8, 3.9e-9, 2.4e-10 at these steps: far above rounding (~1e-15).
  const double e1 = oscillator_error(0.04), e2 = oscillator_error(0.02),
               e3 = oscillator_error(0.01);
  CHECK(e1 / e2 == doctest::Approx(16).epsilon(0.1));
  CHECK(e2 / e3 == doctest::Approx(16).epsilon(0.1));
}

TEST_CASE("rk4: the circular orbit closes after 2 pi, the error dropping 16x per halving") {
  // Errors measured 9.6e-9, 5.7e-10, 3.5e-11 (ratios 16.7, 16.3; from 100 steps the ratio is
  // still 18.4, not yet asymptotic).
  const double e1 = orbit_error(400), e2 = orbit_error(800), e3 = orbit_error(1600);
  CHECK(e1 < 1e-7);
  CHECK(e1 / e2 == doctest::Approx(16).epsilon(0.1));
  CHECK(e2 / e3 == doctest::Approx(16).epsilon(0.1));
}

TEST_CASE("rk4: pinned points never move and have zero velocity") {
  auto s = massspring::test::perturbed_cloth<SystemS>(3);
  s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  auto f = to_float(massspring::test::perturbed_cloth<SystemS>(3));
  f.add_force(massspring::Gravity<float>(Eigen::Vector3f(0, -9.8f, 0)));
  REQUIRE(s.num_pinned() == 2);
  const massspring::Points<double> pins = s.positions()(s.pinned(), Eigen::all);
  const massspring::Points<float> pins_f = f.positions()(f.pinned(), Eigen::all);
  massspring::RK4<SystemS> rk4;
  massspring::RK4<SystemF> rk4_f;
  rk4.precompute(s, 2e-3);
  rk4_f.precompute(f, 2e-3f);
  for (int i = 0; i < 200; ++i) {
    REQUIRE(rk4.step(s).ok());
    REQUIRE(rk4_f.step(f).ok());
    CHECK(s.positions()(s.pinned(), Eigen::all) == pins);
    CHECK(s.velocities()(s.pinned(), Eigen::all).isZero(0));
    CHECK(f.positions()(f.pinned(), Eigen::all) == pins_f);
    CHECK(f.velocities()(f.pinned(), Eigen::all).isZero(0));
  }
  // The free points did move (by about g t^2 / 2 = 0.8 m at t = 0.4 s, less the springs' pull).
  CHECK(s.positions().col(1).minCoeff() < -0.1);
  CHECK(f.positions().col(1).minCoeff() < -0.1f);
}

TEST_CASE("rk4: step() allocates nothing (Dense, Sparse, float)") {
  auto d = massspring::test::perturbed_cloth<SystemD>();
  auto s = massspring::test::perturbed_cloth<SystemS>();
  auto f = to_float(massspring::test::perturbed_cloth<SystemS>());
  d.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  s.add_force(massspring::Gravity<double>(Eigen::Vector3d(0, -9.8, 0)));
  f.add_force(massspring::Gravity<float>(Eigen::Vector3f(0, -9.8f, 0)));
  massspring::RK4<SystemD> id;
  massspring::RK4<SystemS> is;
  massspring::RK4<SystemF> iff;
  id.precompute(d, 1e-3);
  is.precompute(s, 1e-3);
  iff.precompute(f, 1e-3f);
  const massspring::Points<double> x0 = s.positions();
  {
    massspring::test::CountAllocations count;
    for (int i = 0; i < 50; ++i) {
      REQUIRE(id.step(d).ok());
      REQUIRE(is.step(s).ok());
      REQUIRE(iff.step(f).ok());
    }
    CHECK(count.count() == 0);
  }
  CHECK((s.positions() - x0).cwiseAbs().maxCoeff() > 1e-4);  // it did move
  CHECK((d.positions() - s.positions()).cwiseAbs().maxCoeff() < 1e-13);
}

TEST_CASE("rk4: a non-finite result is reported and changes nothing") {
  auto s = massspring::test::oscillator<SystemS>(1, 1, 1, 0.1);
  massspring::Points<double> v = massspring::Points<double>::Zero(2, 3);
  v(1, 0) = 1e308;
  s.set_velocities(v);
  massspring::RK4<SystemS> rk4;
  rk4.precompute(s, 10.0);
  const massspring::Points<double> x0 = s.positions();
  const auto r = rk4.step(s);
  CHECK_FALSE(r.finite);
  CHECK_FALSE(r.ok());
  CHECK(s.positions() == x0);
  CHECK(s.velocities() == v);
}

TEST_CASE("rk4: refuses step before precompute, a bad dt, a resized system") {
  auto s = massspring::test::oscillator<SystemS>(1, 1, 1, 0.1);
  massspring::RK4<SystemS> rk4;
  CHECK_THROWS_WITH_AS(rk4.step(s), "RK4: step() before precompute()", massspring::Error);
  CHECK_THROWS_WITH_AS(rk4.precompute(s, 0.0), "RK4: dt must be finite and > 0, got 0",
                       massspring::Error);
  CHECK_THROWS_AS(rk4.precompute(s, NAN), massspring::Error);
  CHECK_THROWS_AS(rk4.precompute(s, -1.0), massspring::Error);
  rk4.precompute(s, 0.1);
  massspring::Points<double> x = massspring::Points<double>::Zero(3, 3);
  x(1, 0) = 1;
  x(2, 0) = 2;
  SystemS three(x, massspring::Edges(0, 2), 1.0, 1.0);
  CHECK_THROWS_WITH_AS(rk4.step(three),
                       "RK4: the system has 3 points, precompute() saw 2; call precompute() again",
                       massspring::Error);
}
