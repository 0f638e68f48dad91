// contact/response/inelastic_projection.hpp against closed forms: an inelastic impact of two
// points head-on (equal masses: both take the mean normal velocity; one pinned: the other takes
// the pin's), three points in a row, and a constraint nothing may satisfy.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <massspring/contact/response/inelastic_projection.hpp>
#include <vector>

namespace {

using massspring::Points;
using massspring::Vector;
using Projection = massspring::contact::InelasticProjection<double>;
using Constraint = massspring::contact::ProjectionConstraint<double>;

// The constraint n . (d_i - d_j) >= target between points i and j (n from j to i).
Constraint between(int i, int j, const Eigen::Vector3d& n, double target = 0) {
  Constraint c;
  c.p = {i, j, i, i};
  c.a = {1, -1, 0, 0};
  c.n = n;
  c.target = target;
  return c;
}

// Positions at the start, and at the end of a step dt with velocities v.
struct Motion {
  Points<double> x0, x1;
};
Motion moving(const Points<double>& x0, const Points<double>& v, double dt) {
  return {x0, x0 + dt * v};
}

}  // namespace

TEST_CASE("inelastic projection: two equal masses head-on stop along the normal, keep the rest") {
  const double dt = 0.1;
  Points<double> x0(2, 3), v(2, 3);
  x0 << -1, 0, 0, 1, 0, 0;
  v << 2, 0.5, -0.25, -1, -0.3, 0.75;  // approaching along x, sliding along y and z
  Motion m = moving(x0, v, dt);
  const Vector<double> w = Vector<double>::Constant(2, 0.5);  // 2 kg each
  Projection p;
  p.add(between(0, 1, {-1, 0, 0}));  // from point 1 to point 0
  std::vector<char> moved(2, 0);
  const auto r = p.solve(w, m.x0, m.x1, 1e-14, 100, moved);
  CHECK(r.violation <= 1e-14);
  CHECK_FALSE(r.immobile_violated);
  const Points<double> v1 = (m.x1 - m.x0) / dt;
  // Normal relative velocity 0: both at the mean, (2 - 1) / 2.
  CHECK(v1(0, 0) == doctest::Approx(0.5).epsilon(1e-14));
  CHECK(v1(1, 0) == doctest::Approx(0.5).epsilon(1e-14));
  // Tangential velocities unchanged, momentum unchanged.
  CHECK(v1.rightCols(2).isApprox(v.rightCols(2), 1e-14));
  CHECK((v1.colwise().sum() - v.colwise().sum()).norm() <= 1e-14);
  CHECK(moved[0] == 1);
  CHECK(moved[1] == 1);
}

TEST_CASE(
    "inelastic projection: a pinned point does not move, the other takes its normal velocity") {
  const double dt = 0.1;
  Points<double> x0(2, 3), v(2, 3);
  x0 << -1, 0, 0, 1, 0, 0;
  v << 2, 0.5, -0.25, -1, -0.3, 0.75;
  Motion m = moving(x0, v, dt);
  Vector<double> w(2);
  w << 1, 0;  // point 1 pinned: infinite mass
  const Points<double> pinned_end = m.x1.row(1);
  Projection p;
  p.add(between(0, 1, {-1, 0, 0}));
  std::vector<char> moved(2, 0);
  p.solve(w, m.x0, m.x1, 1e-14, 100, moved);
  CHECK(m.x1.row(1) == pinned_end);  // exactly
  CHECK(moved[1] == 0);
  const Points<double> v1 = (m.x1 - m.x0) / dt;
  CHECK(v1(0, 0) == doctest::Approx(-1).epsilon(1e-13));
  CHECK(v1(0, 1) == doctest::Approx(0.5).epsilon(1e-14));
  CHECK(v1(0, 2) == doctest::Approx(-0.25).epsilon(1e-14));
}

TEST_CASE("inelastic projection: three equal masses in a row end with one normal velocity") {
  // Outer points approach the resting middle one at 1 m/s; both contacts are inelastic, so all
  // three end at the mean normal velocity, 0, with the sliding velocities untouched. Projected
  // Gauss-Seidel needs several sweeps here: each contact's multiplier depends on the other's.
  const double dt = 0.1;
  Points<double> x0(3, 3), v(3, 3);
  x0 << -1, 0, 0, 0, 0, 0, 1, 0, 0;
  v << 1, 0.2, 0, 0, 0, 0.3, -1, -0.1, 0.4;
  Motion m = moving(x0, v, dt);
  const Vector<double> w = Vector<double>::Ones(3);
  Projection p;
  p.add(between(1, 0, {1, 0, 0}));  // from 0 to 1
  p.add(between(2, 1, {1, 0, 0}));  // from 1 to 2
  std::vector<char> moved(3, 0);
  const auto r = p.solve(w, m.x0, m.x1, 1e-15, 1000, moved);
  CHECK(r.sweeps > 1);
  const Points<double> v1 = (m.x1 - m.x0) / dt;
  for (int i = 0; i < 3; ++i) {
    CAPTURE(i);
    CHECK(std::abs(v1(i, 0)) <= 1e-12);
  }
  CHECK(v1.rightCols(2).isApprox(v.rightCols(2), 1e-14));
  CHECK((v1.colwise().sum() - v.colwise().sum()).norm() <= 1e-13);
}

TEST_CASE(
    "inelastic projection: a parting target is met exactly, a constraint of immobile points "
    "is reported") {
  Points<double> x0(2, 3);
  x0 << 0, 1, 0, 0, 0, 0;
  Points<double> x1 = x0;
  x1(0, 1) -= 0.05;  // point 0 falls 5 cm onto point 1
  Vector<double> w(2);
  w << 1, 0;
  Projection p;
  p.add(between(0, 1, {0, 1, 0}, 0.001));  // must part by 1 mm along +y
  std::vector<char> moved(2, 0);
  auto r = p.solve(w, x0, x1, 1e-15, 10, moved);
  CHECK(x1(0, 1) == doctest::Approx(1.001).epsilon(1e-14));
  CHECK_FALSE(r.immobile_violated);

  Points<double> y1 = x0;
  y1(0, 1) -= 0.05;
  w(0) = 0;  // both immobile: nothing may meet it
  Projection q;
  q.add(between(0, 1, {0, 1, 0}));
  r = q.solve(w, x0, y1, 1e-15, 10, moved);
  CHECK(r.immobile_violated);
  CHECK(r.violation == doctest::Approx(0.05));
  CHECK(y1(0, 1) == doctest::Approx(0.95));  // unmoved
}

TEST_CASE(
    "inelastic projection: a constraint whose mobile weights are negligible is left to the rigid "
    "zones, not swept") {
  // Point 0 is immobile with weight 1; the mobile point 1 carries a weight of 1e-17, as an
  // element's far corner does when the contact is at its other end. Meeting the constraint
  // would move point 1 by violation / 1e-17 (1.5e15 m for 1.5 cm).
  Points<double> x0(3, 3);
  x0 << 0, 0.01, 0, 0, 0, 0, 1, 0, 0;
  Points<double> x1 = x0;
  x1(0, 1) = -0.005;  // point 0 ends 1.5 cm lower than it should
  Vector<double> w(3);
  w << 0, 1, 0;
  Constraint c;
  c.p = {0, 1, 2, 2};
  c.a = {1, -1e-17, -1 + 1e-17, 0};
  c.n = {0, 1, 0};
  Projection p;
  p.add(c);
  CHECK_FALSE(Projection::mobile(c, w));
  std::vector<char> moved(3, 0);
  const Points<double> before = x1;
  const auto r = p.solve(w, x0, x1, 1e-12, 100, moved);
  CHECK(x1 == before);
  CHECK(r.immobile_violated);
  CHECK(r.violation == doctest::Approx(0.015));
  // A share of 1/512 is mobile: it is swept and met.
  c.a = {1, -1.0 / 512, -1 + 1.0 / 512, 0};
  CHECK(Projection::mobile(c, w));
  Projection q;
  q.add(c);
  const auto s = q.solve(w, x0, x1, 1e-12, 100, moved);
  CHECK(s.violation <= 1e-12);
  CHECK_FALSE(s.immobile_violated);
}

TEST_CASE("inelastic projection: contradictory constraints stop as stalled, their motion bounded") {
  // Point 1 (mobile) must rise 1 cm above immobile point 0 and stay 1 cm below immobile point 2,
  // which ends level with point 0: no position meets both. Each sweep pushes point 1 up by the
  // first and down by the second, by the same amounts once the multipliers are large, so the
  // sweeps' motion never shrinks.
  Points<double> x0(3, 3);
  x0 << 0, 0, 0, 0, 0.5, 0, 0, 1, 0;
  Points<double> x1 = x0;
  x1(2, 1) = 0;  // point 2 comes down onto point 0
  Vector<double> w(3);
  w << 0, 1, 0;
  Projection p;
  p.add(between(1, 0, {0, 1, 0}, 0.01 - 0.5));  // y1 - y0 >= 0.01 at the end
  p.add(between(2, 1, {0, 1, 0}, 0.01 - 0.5));  // y2 - y1 >= 0.01 at the end
  std::vector<char> moved(3, 0);
  const auto r = p.solve(w, x0, x1, 1e-12, 1000, moved);
  CHECK(r.stalled);
  CHECK(r.sweeps <= 3 * Projection::kStallSweeps);
  // Each sweep ends with the second met (y1 = -0.01), the first short by 2 cm.
  CHECK(r.violation == doctest::Approx(0.02));
  CHECK(x1(1, 1) == doctest::Approx(-0.01));
  CHECK(x1.row(0) == x0.row(0));
  CHECK(x1(2, 1) == 0);

  // Made consistent (point 2 stays 3 cm above point 0), the same pair is met without a stall.
  Points<double> y1 = x0;
  y1(2, 1) = 0.03;
  Projection q;
  q.add(between(1, 0, {0, 1, 0}, 0.01 - 0.5));
  q.add(between(2, 1, {0, 1, 0}, 0.01 - 0.5));
  const auto s = q.solve(w, x0, y1, 1e-12, 1000, moved);
  CHECK_FALSE(s.stalled);
  CHECK(s.violation <= 1e-12);
  CHECK(y1(1, 1) >= 0.01 - 1e-12);
  CHECK(y1(1, 1) <= 0.02 + 1e-12);
}
