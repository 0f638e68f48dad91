// contact/fosssim/continuous_time.hpp: a particle fast enough to cross an edge within one step is
// caught by continuous-time detection and missed by the simple (end-of-step) one, which is why
// FOSSSim's Theme 2 has both; the response reflects the mean velocity with restitution e and
// moves the end position by dt times the impulse.
#include <doctest/doctest.h>

#include <massspring/contact/fosssim/continuous_time.hpp>
#include <massspring/contact/fosssim/simple_impulse.hpp>

#include "contact/support.hpp"

namespace contact = massspring::contact;
using massspring::test::apply;
using massspring::test::Pts;
using Vec = massspring::Vector<double>;

namespace {
// particle 0 at (0, 1) falling at 300 m/s; a fixed edge (1, 2) from (-1, 0) to (1, 0)
contact::ContactGeometry<double> tunnel() {
  contact::ContactGeometry<double> g = massspring::test::particles(3, 0.1);
  g.edges.resize(1, 2);
  g.edges << 1, 2;
  g.edge_radii = Vec::Constant(1, 0.015);
  return g;
}
}  // namespace

TEST_CASE("continuous-time catches a particle crossing an edge within a step; simple misses it") {
  const double dt = 0.01, e = 0.5;
  Pts xs(3, 3), vs(3, 3);
  xs << 0, 1, 0, -1, 0, 0, 1, 0, 0;
  vs << 0, -300, 0, 0, 0, 0, 0, 0, 0;
  const Pts xe0 = xs + dt * vs;  // y = -2: through the edge
  const Vec m = Vec::Ones(3);
  {
    contact::SimpleCollisionHandler<double> simple(tunnel(), e);
    Pts xe = xe0, ve = vs;
    apply(simple, xs, vs, xe, ve, dt, m, {1, 2});
    CHECK(xe(0, 1) == doctest::Approx(-2));  // tunnelled: below the edge, unchanged
    CHECK(ve(0, 1) == -300);
  }
  {
    contact::ContinuousTimeCollisionHandler<double> ct(tunnel(), e);
    Pts xe = xe0, ve = vs;
    apply(ct, xs, vs, xe, ve, dt, m, {1, 2});
    // mean velocity -300 reflected with e: +150; position moved by dt * (1 + e) * 300 = 4.5
    CHECK(ve(0, 1) == doctest::Approx(150));
    CHECK(xe(0, 1) == doctest::Approx(-2 + 4.5));
    CHECK(xe(0, 1) > 0);                           // above the edge again
    CHECK(xe.bottomRows(2) == xe0.bottomRows(2));  // the fixed edge did not move
  }
}

TEST_CASE("continuous-time: two particles passing through each other within a step collide") {
  contact::ContinuousTimeCollisionHandler<double> ct(massspring::test::particles(2, 0.1), 1.0);
  Pts xs(2, 3), vs(2, 3);
  xs << -1, 0, 0, 1, 0, 0;
  vs << 200, 0, 0, -200, 0, 0;
  Pts xe = xs + 0.01 * vs, ve = vs;  // they swap sides: no overlap at either end
  apply(ct, xs, vs, xe, ve, 0.01, Vec::Ones(2));
  CHECK(ve(0, 0) == doctest::Approx(-200));  // elastic, equal masses: exchanged
  CHECK(ve(1, 0) == doctest::Approx(200));
  CHECK(xe(0, 0) < xe(1, 0));  // particle 0 stays on the left
}
