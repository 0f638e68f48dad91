// contact/fosssim/polynomial_intervals.hpp and contact/fosssim/time_of_impact.hpp against closed
// forms: the first time at which polynomials are all positive; the time of impact of two particles
// closing at a known speed, of a particle reaching a plane, of a particle reaching an edge's
// interior and an edge's end; no impact when the motion misses or separates.
#include <doctest/doctest.h>

#include <cmath>
#include <massspring/contact/fosssim/polynomial_intervals.hpp>
#include <massspring/contact/fosssim/time_of_impact.hpp>

#include "contact/support.hpp"

namespace contact = massspring::contact;
using massspring::test::v3;
using P = contact::Polynomial<double>;

TEST_CASE("first_time_all_positive: roots, touching zeros, none, identically zero") {
  // (t - 0.3)(t - 0.7) > 0 and t - 0.5 > 0: first from 0.7
  const P a = P::linear(-0.3, 1) * P::linear(-0.7, 1);
  const P b = P::linear(-0.5, 1);
  P polys[2] = {a, b};
  CHECK(contact::first_time_all_positive(polys, 2) == doctest::Approx(0.7).epsilon(1e-14));
  // -(t - 0.25)^2 is never > 0; (t - 0.25)^2 > 0 from 0
  P touch = (-1.0) * (P::linear(-0.25, 1) * P::linear(-0.25, 1));
  CHECK(std::isinf(contact::first_time_all_positive(&touch, 1)));
  P square = P::linear(-0.25, 1) * P::linear(-0.25, 1);
  CHECK(contact::first_time_all_positive(&square, 1) == 0);
  // a quintic with roots 0.1, 0.2, 0.4, 0.6, 0.9 (positive on (0.1, 0.2), (0.4, 0.6), > 0.9)
  P q = P::linear(-0.1, 1) * P::linear(-0.2, 1) * P::linear(-0.4, 1) * P::linear(-0.6, 1) *
        P::linear(-0.9, 1);
  P window = P::linear(-0.3, 1);  // and t > 0.3
  P both[2] = {q, window};
  CHECK(contact::first_time_all_positive(both, 2) == doctest::Approx(0.4).epsilon(1e-13));
  P zero;
  CHECK(std::isinf(contact::first_time_all_positive(&zero, 1)));
}

TEST_CASE("point_point_time_of_impact: closing head-on, first contact at (d - s) / closing") {
  // 1 at x = 0 moving +3 over the step, 2 at x = 2 moving -1: gap 2 - 0.5 = 1.5 closes at 4
  const auto r =
      contact::point_point_time_of_impact<double>(v3(0, 0), v3(3, 0), v3(2, 0), v3(-1, 0), 0.5);
  CHECK(r.hit);
  CHECK(r.time == doctest::Approx(1.5 / 4));
  CHECK(r.n.isApprox(v3(0.5, 0)));  // x2(t) - x1(t) at contact: the sum of radii
  // they pass each other sideways without touching
  CHECK(!contact::point_point_time_of_impact<double>(v3(0, 0), v3(3, 0), v3(2, 1), v3(-1, 0), 0.5)
             .hit);
  // separating while overlapping: no impact
  CHECK(!contact::point_point_time_of_impact<double>(v3(0, 0), v3(-1, 0), v3(0.3, 0), v3(1, 0), 0.5)
             .hit);
  // too slow to reach within the step
  CHECK(!contact::point_point_time_of_impact<double>(v3(0, 0), v3(0.5, 0), v3(2, 0), v3(0, 0), 0.5)
             .hit);
}

TEST_CASE("point_plane_time_of_impact: a floor with a normal of any length") {
  contact::Plane<double> floor{v3(0, -1), v3(0, 5)};
  // from y = 1 down by 4: reaches y = -1 + 0.2 after (2 - 0.2) / 4
  const auto r = contact::point_plane_time_of_impact<double>(v3(0.3, 1), v3(0.7, -4), floor, 0.2);
  CHECK(r.hit);
  CHECK(r.time == doctest::Approx(1.8 / 4));
  CHECK(r.n.isApprox(v3(0, -0.2)));
  CHECK(!contact::point_plane_time_of_impact<double>(v3(0, 1), v3(0, 1), floor, 0.2).hit);
}

TEST_CASE("point_edge_time_of_impact: the edge's interior, its end, a miss, a moving edge") {
  // edge from (-1, 0) to (1, 0); particle from (0.25, 2) straight down by 3, s = 0.5:
  // contact at y = 0.5, t = 1.5 / 3, alpha = 0.625
  auto r = contact::point_edge_time_of_impact<double>(v3(0.25, 2), v3(0, -3), v3(-1, 0), v3(0, 0),
                                                      v3(1, 0), v3(0, 0), 0.5);
  CHECK(r.hit);
  CHECK(r.time == doctest::Approx(0.5));
  CHECK(r.alpha == doctest::Approx(0.625));
  CHECK(r.n.isApprox(v3(0, -0.5)));
  // beyond the end (x = 1.3): the capsule's end cap is reached later than the line; FOSSSim's
  // conditions (alpha in [0, 1]) report no particle-edge impact there
  CHECK(!contact::point_edge_time_of_impact<double>(v3(1.3, 2), v3(0, -3), v3(-1, 0), v3(0, 0),
                                                    v3(1, 0), v3(0, 0), 0.5)
             .hit);
  // the edge moves up by 1 while the particle falls by 2: closing speed 3, gap 1.5
  r = contact::point_edge_time_of_impact<double>(v3(0, 2), v3(0, -2), v3(-1, 0), v3(0, 1), v3(1, 0),
                                                 v3(0, 1), 0.5);
  CHECK(r.hit);
  CHECK(r.time == doctest::Approx(0.5));
  // moving apart: no impact
  CHECK(!contact::point_edge_time_of_impact<double>(v3(0, 0.3), v3(0, 1), v3(-1, 0), v3(0, 0),
                                                    v3(1, 0), v3(0, 0), 0.5)
             .hit);
}
