// integrators/backward_euler.hpp with options.contact_weight = alpha > 0: contact and Coulomb
// friction inside BackwardEuler's solve (the ADMM term of FastMassSpring, with the weight
// alpha sqrt(m (m + h^2 k)) per point), at dt = 1/30 s with its default 20 iterations and
// tolerance and one setting, alpha = 1, against closed forms:
// - a block on a 30 degree incline slides with a = g (sin t - mu cos t) (mu = 0.2), Newton and
//   Linearized, and does not move at mu = 0.7;
// - run to convergence, the step is the exact implicit-Euler step with Signorini-Coulomb contact
//   whatever alpha;
// - a cloth dropped on a ball turning at 1 rad/s about the vertical turns with it (friction), and
//   no point is ever inside the ball at a step end;
// - the dual variables saved and restored resume a run bit for bit; set_contact_duals refuses
//   what it cannot hold.
// (A particle at rest on a plane: tests/contact/colliders/test_collider_response.cpp.)
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <massspring/integrators/backward_euler.hpp>
#include <string>

#include "support/contact_scenes.hpp"

namespace backward_euler_contact_test {

using System = massspring::test::ContactSystem;
using Solver = massspring::BackwardEuler<System>;
using massspring::test::cloth_over_ball;
using massspring::test::discrete_slide;
using massspring::test::incline_block;
using massspring::test::incline_slide;
constexpr double kDt = massspring::test::kContactDt;

massspring::BackwardEulerOptions<double> in_solve_options(double alpha,
                                                          massspring::BackwardEulerMode mode,
                                                          int iterations = 20) {
  massspring::BackwardEulerOptions<double> o;
  o.mode = mode;
  o.iterations = iterations;
  o.contact_weight = alpha;
  return o;
}

const massspring::BackwardEulerMode kModes[] = {massspring::BackwardEulerMode::Newton,
                                                massspring::BackwardEulerMode::Linearized};
const char* mode_name(massspring::BackwardEulerMode m) {
  return m == massspring::BackwardEulerMode::Newton ? "Newton" : "Linearized";
}

// Measured: exact to 1e-6 (Newton and Linearized: the block's forces are linear); alpha 2:
// -0.05%; alpha 16 lags by 31%, its dual converging more slowly.
TEST_CASE(
    "BackwardEuler, contact in the solve: a block slides down an incline with a = g (sin t - mu "
    "cos t) at dt = 1/30") {
  const double theta = 30 * M_PI / 180, mu = 0.2;
  const int steps = 30;  // 1 s
  for (const auto mode : kModes) {
    CAPTURE(std::string(mode_name(mode)));
    System s = incline_block(theta, mu);
    Solver solver(in_solve_options(1, mode));
    const double slid = incline_slide(s, solver, theta, steps);
    CHECK(std::abs(slid / discrete_slide(theta, mu, steps) - 1) <= 0.02);
  }
}

TEST_CASE(
    "BackwardEuler, contact in the solve: static friction holds a block on an incline to 1e-9 m "
    "over 1 s at dt = 1/30") {
  const double theta = 30 * M_PI / 180, mu = 0.7;  // mu > tan 30 = 0.577
  for (const auto mode : kModes)
    for (const double alpha : {1.0, 16.0}) {
      CAPTURE(std::string(mode_name(mode)));
      CAPTURE(alpha);
      System s = incline_block(theta, mu);
      Solver solver(in_solve_options(alpha, mode));
      CHECK(massspring::test::incline_hold(s, solver, 30) <= 1e-9);
    }
}

// The dual variable makes the converged step independent of the weight (a penalty would leave
// the point inside by the depth its weight allows and scale its friction down with it).
TEST_CASE(
    "BackwardEuler, contact in the solve: converged, the step is exact implicit Euler with "
    "Coulomb friction for every weight") {
  const double theta = 30 * M_PI / 180, mu = 0.2;
  const int steps = 10;
  for (const auto mode : kModes)
    for (const double alpha : {0.5, 1.0, 4.0, 16.0}) {
      CAPTURE(std::string(mode_name(mode)));
      CAPTURE(alpha);
      System s = incline_block(theta, mu);
      // Converged: a step's error of tolerance (1 + |x|) grows over N steps by up to N^2 / 2
      // through the velocity, so 1e-13 for 1e-8 of the slide.
      auto o = in_solve_options(alpha, mode, 1000);
      o.tolerance = 1e-13;
      Solver solver(o);
      const double slid = incline_slide(s, solver, theta, steps);
      CHECK(std::abs(slid / discrete_slide(theta, mu, steps) - 1) <= 1e-8);
    }
}

// Dropped on a ball turning at 1 rad/s about the vertical (mu = 0.5), the cloth lands flat and is
// carried up to speed by friction alone. Newton with 20 iterations and alpha 1: its resting
// points move with the ball's surface to 1.5% after 2 s (2.6% with alpha 2); with the friction
// at the end of the step (alpha 0) they lag by 16%.
TEST_CASE(
    "BackwardEuler, contact in the solve: a cloth on a ball turning at 1 rad/s turns with it "
    "after 2 s (mu = 0.5, dt = 1/30), never inside it") {
  const double omega = 1;
  System s = cloth_over_ball(41, 0.5, omega);
  Solver solver(in_solve_options(1, massspring::BackwardEulerMode::Newton));
  solver.precompute(s, kDt);
  double nearest = 1e9;  // the smallest distance of a point from the ball's centre
  for (int k = 0; k < 60; ++k) {
    REQUIRE(solver.step(s).ok());
    nearest = std::min(nearest, s.positions().rowwise().norm().minCoeff());
  }
  CHECK(nearest >= 0.5 - 1e-12);
  int resting = 0;
  const double lag = massspring::test::lag_behind_surface(s, omega, resting);
  CAPTURE(resting);
  REQUIRE(resting > 100);
  CHECK(lag <= 0.05);
}

TEST_CASE(
    "BackwardEuler, contact in the solve: a run resumed with its dual variables continues bit "
    "for bit") {
  massspring::test::check_resume_with_duals<Solver>(
      in_solve_options(1, massspring::BackwardEulerMode::Newton), 11);
}

TEST_CASE("BackwardEuler, contact in the solve: set_contact_duals refuses what it cannot hold") {
  System s = cloth_over_ball(5, 0.5, 0);
  Solver solver(in_solve_options(16, massspring::BackwardEulerMode::Newton));
  massspring::Points<double> u = massspring::Points<double>::Zero(s.num_points(), 3);
  CHECK_THROWS_WITH(solver.set_contact_duals(u),
                    "BackwardEuler: set_contact_duals() before precompute()");
  solver.precompute(s, kDt);
  CHECK_THROWS_WITH(solver.set_contact_duals(massspring::Points<double>::Zero(3, 3)),
                    "BackwardEuler::set_contact_duals: expected one value per point (25), got 3");
  u(7, 1) = std::nan("");
  CHECK_THROWS_WITH(solver.set_contact_duals(u),
                    "point 7: contact dual must be finite, got (0, nan, 0)");
  s.pin(4);
  solver.precompute(s, kDt);
  u.setZero();
  u(3, 0) = 1e-3;
  u(4, 2) = 1e-3;
  CHECK_THROWS_WITH(solver.set_contact_duals(u),
                    "BackwardEuler: set_contact_duals: row 4 is not zero, but point 4 is pinned");
  CHECK(solver.contact_duals().cwiseAbs().maxCoeff() == 0);  // nothing changed
  u(4, 2) = 0;
  solver.set_contact_duals(u);
  CHECK(solver.contact_duals() == u);
}

TEST_CASE("BackwardEuler: contact_weight must be finite and >= 0") {
  System s = incline_block(0.5, 0.2);
  for (const double alpha : {-1.0, std::nan("")}) {
    Solver solver(in_solve_options(alpha, massspring::BackwardEulerMode::Newton));
    solver.precompute(s, kDt);
    CHECK_THROWS_AS(solver.step(s), massspring::Error);
  }
}

}  // namespace backward_euler_contact_test
