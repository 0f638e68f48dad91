// contact/response/impact_zones.hpp and contact/fosssim/hybrid.hpp: a rigid zone keeps its shape
// and its linear momentum and turns by FOSSSim's angle L_z / I_zz in the plane; a zone with a fixed
// particle or a plane stays where it started, at rest; two equal particles colliding head-on with
// no impulse rounds (maxiters = 0) end as one body (velocities averaged), with enough rounds and e
// = 1 they exchange velocities; zones merge through shared particles.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <massspring/contact/fosssim/hybrid.hpp>
#include <random>

#include "contact/support.hpp"

namespace contact = massspring::contact;
using massspring::test::apply;
using massspring::test::Pts;
using massspring::test::v3;
using massspring::test::V3;
using Vec = massspring::Vector<double>;

TEST_CASE("rigid_zone_motion: rigid, momentum kept, FOSSSim Theme 2's 2D angle L_z / I_zz") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 4;
  Pts qs(n, 3), qe(n, 3), ve = Pts::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    qs.row(i) << u(rng), u(rng), 0;
    qe.row(i) = qs.row(i) + 0.1 * V3(u(rng), u(rng), 0).transpose();
  }
  Vec m(n);
  m << 1, 2, 0.5, 1.5;
  const double dt = 0.01;
  // FOSSSim's closed form (HybridCollisionHandler::performFailsafe, 2D)
  const double M = m.sum();
  V3 c = V3::Zero(), p = V3::Zero();
  for (int i = 0; i < n; ++i) {
    c += m(i) * V3(qs.row(i).transpose());
    p += m(i) * V3((qe.row(i) - qs.row(i)).transpose());
  }
  c /= M;
  p /= M;
  double L = 0, I = 0;
  for (int i = 0; i < n; ++i) {
    const V3 r = V3(qs.row(i).transpose()) - c, v = V3((qe.row(i) - qs.row(i)).transpose()) - p;
    L += m(i) * (r.x() * v.y() - r.y() * v.x());
    I += m(i) * r.squaredNorm();
  }
  const double w = L / I;
  const std::array<int, 4> zone{0, 1, 2, 3};
  Pts x = qe;
  contact::rigid_zone_motion(zone.data(), n, false, m, qs, dt, x, ve);
  for (int i = 0; i < n; ++i) {
    const V3 r = V3(qs.row(i).transpose()) - c;
    const V3 expected = c + p + std::cos(w) * r + std::sin(w) * v3(-r.y(), r.x());
    CHECK((V3(x.row(i).transpose()) - expected).norm() < 1e-13);
    CHECK((ve.row(i) - (x.row(i) - qs.row(i)) / dt).norm() < 1e-12);
    for (int j = 0; j < n; ++j)  // rigid
      CHECK((x.row(i) - x.row(j)).norm() == doctest::Approx((qs.row(i) - qs.row(j)).norm()));
  }
  V3 p_after = V3::Zero();
  for (int i = 0; i < n; ++i) p_after += m(i) * V3(ve.row(i).transpose());
  CHECK((p_after - M * p / dt).norm() < 1e-10);
  // pinned or plane: back to the start, at rest
  x = qe;
  contact::rigid_zone_motion(zone.data(), 2, true, m, qs, dt, x, ve);
  CHECK(x.topRows(2) == qs.topRows(2));
  CHECK(ve.topRows(2).isZero());
}

TEST_CASE("ImpactZones: zones merge through shared particles, planes flag them") {
  contact::ImpactZones z;
  z.reset(6);
  CHECK(z.add(std::array<int, 2>{0, 1}, 2, false));
  CHECK(z.add(std::array<int, 2>{2, 3}, 2, false));
  CHECK(!z.add(std::array<int, 2>{1, 0}, 2, false));    // nothing new
  CHECK(z.add(std::array<int, 3>{1, 4, 2}, 3, false));  // merges both
  CHECK(z.zone_of(0) == z.zone_of(3));
  CHECK(z.zone_of(5) == -1);
  CHECK(!z.has_plane(z.zone_of(0)));
  CHECK(z.add(std::array<int, 1>{3}, 1, true));
  CHECK(z.has_plane(z.zone_of(0)));
  std::vector<int> members, starts;
  z.groups(members, starts);
  CHECK(members.size() == 5);
  CHECK(starts == std::vector<int>{0, 5});
}

TEST_CASE("hybrid: head-on equal masses; zones only (maxiters 0) or impulses (e = 1)") {
  Pts xs(2, 3), vs(2, 3);
  xs << -0.5, 0, 0, 0.5, 0, 0;
  vs << 100, 0, 0, -60, 0, 0;
  const double dt = 0.01;
  const Pts xe0 = xs + dt * vs;
  {
    contact::HybridCollisionHandler<double> h(massspring::test::particles(2, 0.2), 1.0, 0);
    Pts xe = xe0, ve = vs;
    apply(h, xs, vs, xe, ve, dt, Vec::Ones(2));
    // one rigid body: both move by the mean displacement (0.2), velocity 20, no rotation
    CHECK(ve(0, 0) == doctest::Approx(20));
    CHECK(ve(1, 0) == doctest::Approx(20));
    CHECK(xe(0, 0) == doctest::Approx(-0.3));
    CHECK(xe(1, 0) == doctest::Approx(0.7));
    CHECK(h.last_zone_rounds() >= 1);
  }
  {
    contact::HybridCollisionHandler<double> h(massspring::test::particles(2, 0.2), 1.0, 100);
    Pts xe = xe0, ve = vs;
    apply(h, xs, vs, xe, ve, dt, Vec::Ones(2));
    CHECK(ve(0, 0) == doctest::Approx(-60));  // exchanged
    CHECK(ve(1, 0) == doctest::Approx(100));
    CHECK(h.last_zone_rounds() == 0);
  }
  {  // a particle and a plane with no impulse rounds: back to the start, at rest
    contact::ContactGeometry<double> g = massspring::test::particles(1, 0.1);
    g.planes.push_back({v3(0, 0), v3(0, 1)});
    contact::HybridCollisionHandler<double> h(g, 1.0, 0);
    Pts s(1, 3), v(1, 3);
    s << 0, 0.5, 0;
    v << 0, -100, 0;
    Pts xe = s + dt * v, ve = v;
    apply(h, s, v, xe, ve, dt, Vec::Ones(1));
    CHECK(xe == s);
    CHECK(ve.isZero());
  }
}

TEST_CASE("hybrid: a break of nine balls ends with no two balls overlapping") {
  // a triangle of touching balls hit by a fast one (the shape of ImpulsesTests/test06, our
  // numbers); with 2 impulse rounds the zones must finish the job
  const int n = 10;
  Pts xs(n, 3), vs = Pts::Zero(n, 3);
  int k = 1;
  xs.row(0) << -1, -0.35, 0;
  vs.row(0) << 300, 100, 0;
  for (int row = 0; row < 4; ++row)
    for (int j = 0; j <= row && k < n; ++j, ++k) xs.row(k) << 0.21 * row, 0.21 * (j - row / 2.0), 0;
  contact::ContactGeometry<double> g = massspring::test::particles(n, 0.1);
  contact::HybridCollisionHandler<double> h(g, 0.3, 2);
  const double dt = 0.01;
  Pts xe = xs + dt * vs, ve = vs;
  apply(h, xs, vs, xe, ve, dt, Vec::Ones(n));
  // no two balls overlap at the end of the step (rigid zones keep their start distances, and
  // every other collision grows a zone)
  int overlapping = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) overlapping += (xe.row(i) - xe.row(j)).norm() < 0.2;
  CHECK(overlapping == 0);
  CHECK(xe.allFinite());
  CHECK(ve.allFinite());
}
