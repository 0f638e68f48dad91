// integrators/local_global/contact_projection.hpp: contact and Coulomb friction inside
// FastMassSpring's iteration (options.contact_weight = alpha > 0) at the large time step the
// solver is for, dt = 1/30 s with 10 iterations, against closed forms:
// - a block on a 30 degree incline slides with a = g (sin t - mu cos t) (mu = 0.2), and does not
//   move at mu = 0.7;
// - run to convergence, the step is the exact implicit-Euler step with Signorini-Coulomb contact
//   whatever alpha (the dual variable removes a penalty's error);
// - a cloth dropped on a ball over a floor never has a point inside the ball at a step end, and
//   rests on it with little stretch;
// - a cloth dropped on a ball that turns about the vertical turns with it (friction): to 5% after
//   2 s;
// - the dual variables saved and restored resume a run bit for bit.
// contact_weight 1 with Anderson acceleration serves them all (the slide also runs plain and with
// Chebyshev, the converged step every weight from 0.5 to 16). contact_weight 1 with Chebyshev
// acceleration, its rho estimated (the default), holds the block and turns the cloth too, and
// winds the turning pole further (tests/CMakeLists.txt, tools.pole_fast_mass_spring); the cloth
// on the still ball it leaves still settling after 3 s (docs/contact.md).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/integrators/local_global/option_names.hpp>
#include <string>

#include "support/contact_scenes.hpp"

namespace contact_projection_test {

using System = massspring::test::ContactSystem;
using Solver = massspring::FastMassSpring<System>;

using massspring::test::cloth_over_ball;
using massspring::test::discrete_slide;
using massspring::test::incline_block;
using massspring::test::incline_slide;
using massspring::test::Strain;
using massspring::test::strain_of;
constexpr double kDt = massspring::test::kContactDt;

massspring::FastMassSpringOptions<double> in_solve_options(double alpha, int iterations,
                                                           massspring::Acceleration acceleration) {
  massspring::FastMassSpringOptions<double> o;
  o.iterations = iterations;
  o.contact_weight = alpha;
  o.initial_guess = massspring::InitialGuess::Inertial;
  o.acceleration = acceleration;
  o.chebyshev_rho = 0.5;  // fixed: the estimate is not what is tested here
  return o;
}

// The same with Chebyshev acceleration and its rho estimated by the solver, as a user gets it by
// default (options.chebyshev_rho 0).
massspring::FastMassSpringOptions<double> estimated_chebyshev_options(double alpha) {
  massspring::FastMassSpringOptions<double> o =
      in_solve_options(alpha, 10, massspring::Acceleration::Chebyshev);
  o.chebyshev_rho = 0;
  return o;
}

TEST_CASE(
    "contact in the iteration: a block slides down an incline with a = g (sin t - mu cos t) "
    "at dt = 1/30, 10 iterations") {
  const double theta = 30 * M_PI / 180, mu = 0.2;
  const int steps = 30;  // 1 s
  for (const auto acceleration :
       {massspring::Acceleration::None, massspring::Acceleration::Chebyshev,
        massspring::Acceleration::Anderson}) {
    CAPTURE(std::string(massspring::option_name(acceleration)));
    System s = incline_block(theta, mu);
    Solver solver(in_solve_options(1, 10, acceleration));
    const double slid = incline_slide(s, solver, theta, steps);
    CHECK(std::abs(slid / discrete_slide(theta, mu, steps) - 1) <= 0.02);
  }
}

TEST_CASE(
    "contact in the iteration: static friction holds a block on an incline to 1e-9 m over "
    "1 s at dt = 1/30, 10 iterations") {
  const double theta = 30 * M_PI / 180, mu = 0.7;  // mu > tan 30 = 0.577
  for (const auto& options : {in_solve_options(1, 10, massspring::Acceleration::Anderson),
                              estimated_chebyshev_options(1)}) {
    CAPTURE(std::string(massspring::option_name(options.acceleration)));
    System s = incline_block(theta, mu);
    Solver solver(options);
    CHECK(massspring::test::incline_hold(s, solver, 30) <= 1e-9);
  }
}

// The dual variable makes the converged step independent of the weight: a penalty (the term
// without it) leaves the point inside by the depth its weight allows and scales its friction
// down with it, so its slide would depend on alpha.
TEST_CASE(
    "contact in the iteration: converged, the step is exact implicit Euler with Coulomb "
    "friction for every weight") {
  const double theta = 30 * M_PI / 180, mu = 0.2;
  const int steps = 10;
  for (const double alpha : {0.5, 1.0, 4.0, 16.0}) {
    CAPTURE(alpha);
    System s = incline_block(theta, mu);
    Solver solver(in_solve_options(alpha, 400, massspring::Acceleration::None));
    const double slid = incline_slide(s, solver, theta, steps);
    CHECK(std::abs(slid / discrete_slide(theta, mu, steps) - 1) <= 1e-8);
  }
}

TEST_CASE(
    "contact in the iteration: a cloth dropped on a ball at dt = 1/30 rests on it, never "
    "inside, with mean strain <= 2% and max <= 15%") {
  System s = cloth_over_ball(41, 0.5, 0);
  Solver solver(in_solve_options(1, 10, massspring::Acceleration::Anderson));
  solver.precompute(s, kDt);
  double nearest = 1e9;  // the smallest distance of a point from the ball's centre
  for (int k = 0; k < 90; ++k) {
    REQUIRE(solver.step(s).ok());
    nearest = std::min(nearest, s.positions().rowwise().norm().minCoeff());
  }
  CHECK(nearest >= 0.5 - 1e-12);
  // It rests on the ball: the middle point (above the pole) is on the surface.
  const int middle = 20 * 41 + 20;
  CHECK(s.positions().row(middle).norm() == doctest::Approx(0.5).epsilon(1e-3));
  const Strain strain = strain_of(s);
  CAPTURE(strain.mean);
  CAPTURE(strain.max);
  CHECK(strain.mean <= 0.02);
  CHECK(strain.max <= 0.15);
}

// Dropped on a ball turning at 1 rad/s about the vertical (mu = 0.5) and run for `seconds` with
// 10 iterations: the points resting on the ball's upper half (within 1 cm of its surface), their
// velocity against the surface's, omega x x, on average, relative to the surface's speed.
double lag_behind_ball(const massspring::FastMassSpringOptions<double>& options, int seconds) {
  const double omega = 1;
  System s = cloth_over_ball(41, 0.5, omega);
  Solver solver(options);
  solver.precompute(s, kDt);
  for (int k = 0; k < 30 * seconds; ++k) REQUIRE(solver.step(s).ok());
  int resting = 0;
  const double lag = massspring::test::lag_behind_surface(s, omega, resting);
  CAPTURE(resting);
  REQUIRE(resting > 100);
  return lag;
}

// Dropped on the turning ball, the cloth lands flat and is carried up to speed by friction alone.
// Run to convergence (200 iterations) its resting points move with the ball's surface to 2.3%
// after 2 s. In 10 iterations with Anderson acceleration: 3.9%; with Chebyshev's (rho estimated):
// 4.6%; plain, 8.3% (the friction builds up more slowly), which is why the settings accelerate.
TEST_CASE(
    "contact in the iteration: a cloth on a ball turning at 1 rad/s turns with it after 2 s "
    "(mu = 0.5, dt = 1/30, 10 iterations)") {
  CHECK(lag_behind_ball(in_solve_options(1, 10, massspring::Acceleration::Anderson), 2) <= 0.05);
  CHECK(lag_behind_ball(estimated_chebyshev_options(1), 2) <= 0.05);
}

// The duals carry the term from step to step (support/contact_scenes.hpp).
TEST_CASE("contact in the iteration: a run resumed with its dual variables continues bit for bit") {
  massspring::test::check_resume_with_duals<Solver>(
      in_solve_options(1, 10, massspring::Acceleration::Anderson), 21);
}

// Chebyshev estimates rho from 100 trial iterations on its first step after a factorization.
// Those iterations are not the step's: the step must start from the duals the previous step left,
// so that it is, bit for bit, the step taken with the estimate given as options.chebyshev_rho.
TEST_CASE(
    "contact in the iteration: Chebyshev's estimate of rho leaves the dual variables as they "
    "were") {
  System estimated_run = cloth_over_ball(11, 0.5, 0);
  System given_run = estimated_run;
  Solver estimated(in_solve_options(1, 10, massspring::Acceleration::None));
  Solver given(in_solve_options(1, 10, massspring::Acceleration::None));
  estimated.precompute(estimated_run, kDt);
  given.precompute(given_run, kDt);
  // Plain steps until the cloth lies on the ball, its duals holding the contact.
  for (int k = 0; k < 10; ++k) {
    REQUIRE(estimated.step(estimated_run).ok());
    REQUIRE(given.step(given_run).ok());
  }
  REQUIRE(estimated.contact_duals().cwiseAbs().maxCoeff() > 1e-6);
  REQUIRE(estimated.contact_duals() == given.contact_duals());
  estimated.options.acceleration = massspring::Acceleration::Chebyshev;
  estimated.options.chebyshev_rho = 0;  // estimated on the next step
  REQUIRE(estimated.step(estimated_run).ok());
  REQUIRE(estimated.chebyshev_rho() > 0);
  given.options.acceleration = massspring::Acceleration::Chebyshev;
  given.options.chebyshev_rho = estimated.chebyshev_rho();
  REQUIRE(given.step(given_run).ok());
  CHECK(estimated_run.positions() == given_run.positions());
  CHECK(estimated.contact_duals() == given.contact_duals());
}

TEST_CASE("contact in the iteration: set_contact_duals refuses what the term cannot hold") {
  System s = cloth_over_ball(5, 0.5, 0);
  Solver solver(in_solve_options(1, 10, massspring::Acceleration::Anderson));
  massspring::Points<double> u = massspring::Points<double>::Zero(s.num_points(), 3);
  CHECK_THROWS_WITH(solver.set_contact_duals(u),
                    "FastMassSpring: set_contact_duals() before precompute()");
  solver.precompute(s, kDt);
  CHECK_THROWS_WITH(solver.set_contact_duals(massspring::Points<double>::Zero(3, 3)),
                    "FastMassSpring::set_contact_duals: expected one value per point (25), got 3");
  u(7, 1) = std::nan("");
  CHECK_THROWS_WITH(solver.set_contact_duals(u),
                    "point 7: contact dual must be finite, got (0, nan, 0)");
  // A pinned point: the term does not act on it. Nothing is changed by a refused call.
  s.pin(4);
  solver.precompute(s, kDt);
  u.setZero();
  u(3, 0) = 1e-3;
  u(4, 2) = 1e-3;
  CHECK_THROWS_WITH(solver.set_contact_duals(u),
                    "FastMassSpring: set_contact_duals: row 4 is not zero, but the contact term "
                    "does not act on point 4 (pinned, contact_weight 0 or no colliders)");
  CHECK(solver.contact_duals().cwiseAbs().maxCoeff() == 0);
  u(4, 2) = 0;
  solver.set_contact_duals(u);
  CHECK(solver.contact_duals() == u);
  // contact_weight 0: no term, so only zeros are accepted.
  Solver end_of_step(in_solve_options(0, 10, massspring::Acceleration::None));
  end_of_step.precompute(s, kDt);
  CHECK_THROWS(end_of_step.set_contact_duals(u));
  end_of_step.set_contact_duals(massspring::Points<double>::Zero(s.num_points(), 3));
}

}  // namespace contact_projection_test
