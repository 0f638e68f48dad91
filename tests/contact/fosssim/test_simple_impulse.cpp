// contact/fosssim/simple_impulse.hpp and contact/fosssim/impulse.hpp, against closed forms and invariants:
// a head-on collision of equal masses with COR e exchanges the velocities scaled by e; a fixed
// particle has infinite mass; a particle dropped on a half-plane rebounds to e^2 of its height;
// particle-edge impulses conserve linear momentum and, for a free edge, angular momentum;
// separating or distant pairs get nothing.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <massspring/contact/fosssim/simple_impulse.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/symplectic_euler.hpp>
#include <massspring/system/mass_spring_system.hpp>
#include <random>

#include "contact/support.hpp"

namespace contact = massspring::contact;
using massspring::test::apply;
using massspring::test::Pts;
using massspring::test::v3;
using massspring::test::V3;
using Vec = massspring::Vector<double>;

TEST_CASE("simple: head-on, equal masses, COR e: velocities exchanged and scaled by e") {
  for (double e : {0.0, 0.3, 1.0}) {
    CAPTURE(e);
    contact::SimpleCollisionHandler<double> h(massspring::test::particles(2, 0.2), e);
    Pts x(2, 3), v(2, 3);
    x << 0, 0, 0, 0.35, 0, 0;  // overlapping (0.35 < 0.4)
    v << 2, 0, 0, -2, 0, 0;    // approaching
    const Pts xs = x, vs = v;
    apply(h, xs, vs, x, v, 0.01, Vec::Ones(2));
    CHECK(v(0, 0) == doctest::Approx(-2 * e));  // e times the other's velocity
    CHECK(v(1, 0) == doctest::Approx(2 * e));
    CHECK(x == xs);  // positions are not changed
    // general equal masses: v1' = ((1 - e) v1 + (1 + e) v2) / 2 along the normal
    v << 3, 1, 0, -1, 4, 0;
    apply(h, xs, vs, x, v, 0.01, Vec::Ones(2));
    CHECK(v(0, 0) == doctest::Approx(((1 - e) * 3 + (1 + e) * -1) / 2));
    CHECK(v(1, 0) == doctest::Approx(((1 - e) * -1 + (1 + e) * 3) / 2));
    CHECK(v(0, 1) == 1);  // tangential velocities unchanged
    CHECK(v(1, 1) == 4);
  }
}

TEST_CASE("simple: unequal masses conserve momentum; a fixed particle has infinite mass") {
  contact::SimpleCollisionHandler<double> h(massspring::test::particles(2, 0.2), 1.0);
  Pts x(2, 3), v(2, 3);
  x << 0, 0, 0, 0.3, 0.1, 0;
  v << 1, 0.5, 0, -0.5, 0, 0;
  const Pts xs = x;
  Vec m(2);
  m << 1, 3;
  const V3 p0 = m(0) * V3(v.row(0).transpose()) + m(1) * V3(v.row(1).transpose());
  const double k0 = 0.5 * (m(0) * v.row(0).squaredNorm() + m(1) * v.row(1).squaredNorm());
  apply(h, xs, Pts(v), x, v, 0.01, m);
  const V3 p1 = m(0) * V3(v.row(0).transpose()) + m(1) * V3(v.row(1).transpose());
  CHECK((p1 - p0).norm() < 1e-14);
  CHECK(0.5 * (m(0) * v.row(0).squaredNorm() + m(1) * v.row(1).squaredNorm()) ==
        doctest::Approx(k0));  // e = 1: elastic
  // particle 1 fixed: particle 0 reflects its normal velocity, particle 1 does not move
  v << 1, 0, 0, 0, 0, 0;
  x << 0, 0, 0, 0.3, 0, 0;
  apply(h, xs, Pts(v), x, v, 0.01, m, {1});
  CHECK(v(0, 0) == doctest::Approx(-1));
  CHECK(v.row(1).isZero());
}

TEST_CASE("simple: separating, distant and resting pairs get no impulse") {
  contact::SimpleCollisionHandler<double> h(massspring::test::particles(2, 0.2), 1.0);
  Pts x(2, 3), v(2, 3);
  x << 0, 0, 0, 0.3, 0, 0;
  v << -1, 0, 0, 1, 0, 0;  // separating
  Pts v0 = v;
  apply(h, x, v0, x, v, 0.01, Vec::Ones(2));
  CHECK(v == v0);
  x << 0, 0, 0, 0.5, 0, 0;  // apart (0.5 > 0.4)
  v << 1, 0, 0, -1, 0, 0;
  v0 = v;
  apply(h, x, v0, x, v, 0.01, Vec::Ones(2));
  CHECK(v == v0);
}

TEST_CASE("simple: particle-edge impulses conserve linear and angular momentum (free edge)") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  contact::ContactGeometry<double> g = massspring::test::particles(3, 0.1);
  g.edges.resize(1, 2);
  g.edges << 1, 2;
  g.edge_radii = Vec::Constant(1, 0.05);
  for (int trial = 0; trial < 20; ++trial) {
    CAPTURE(trial);
    Pts x(3, 3), v(3, 3);
    // edge from (-1, 0) to (1, 0) (z = 0 or not), particle just above it, moving down
    // (closer than 0.15 = r + r_e whatever the tilt; falling faster than the edge can move)
    x << 0.8 * u(rng), 0.05, 0.05 * u(rng), -1, 0, 0, 1, 0.05 * u(rng), 0;
    v << u(rng), -3 - std::abs(u(rng)), 0, u(rng), u(rng), u(rng), u(rng), u(rng), 0;
    Vec m(3);
    m << 1 + std::abs(u(rng)), 1 + std::abs(u(rng)), 1 + std::abs(u(rng));
    auto momentum = [&](const Pts& vel) {
      V3 p = V3::Zero(), L = V3::Zero();
      for (int i = 0; i < 3; ++i) {
        p += m(i) * V3(vel.row(i).transpose());
        L += m(i) * V3(x.row(i).transpose()).cross(V3(vel.row(i).transpose()));
      }
      return std::make_pair(p, L);
    };
    const auto [p0, L0] = momentum(v);
    const double e = 0.5 * (trial % 3);
    contact::SimpleCollisionHandler<double> h(g, e);
    const Pts vs = v;
    apply(h, x, vs, x, v, 0.01, m);
    CHECK(v != vs);  // an impulse was applied
    const auto [p1, L1] = momentum(v);
    CHECK((p1 - p0).norm() < 1e-13);
    CHECK((L1 - L0).norm() < 1e-13);
    // the relative normal velocity at the contact point is -e times what it was
    const auto d = contact::point_segment_distance<double>(
        x.row(0).transpose(), x.row(1).transpose(), x.row(2).transpose());
    auto rel = [&](const Pts& vel) {
      const V3 edge =
          (1 - d.alpha) * V3(vel.row(1).transpose()) + d.alpha * V3(vel.row(2).transpose());
      return (V3(vel.row(0).transpose()) - edge).dot(d.normal());
    };
    CHECK(rel(v) == doctest::Approx(-e * rel(vs)).epsilon(1e-12));
  }
}

TEST_CASE("simple: a particle dropped on a half-plane rebounds to e^2 of its height") {
  // h = 1 m above the floor y = 0 (radius 0.05: the contact is at y = 0.05), g = 9.81,
  // symplectic Euler with dt = 1e-4; the rebound apex is e^2 h above the contact height
  // within O(dt sqrt(g / h)) relative.
  using System = massspring::MassSpringSystem<double, massspring::Dense>;
  for (double e : {0.5, 0.8}) {
    CAPTURE(e);
    Pts x0(1, 3);
    x0 << 0, 1.05, 0;
    System sys(x0, massspring::Edges(0, 2), 1.0, 0.0);
    sys.add_force(massspring::Gravity<double>(v3(0, -9.81, 0)));
    contact::ContactGeometry<double> g = massspring::test::particles(1, 0.05);
    g.planes.push_back({v3(0, 0), v3(0, 2)});  // normal not of unit length
    sys.set_collision_handler(contact::SimpleCollisionHandler<double>(g, e));
    massspring::SymplecticEuler<System> se;
    se.precompute(sys, 1e-4);
    bool bounced = false;
    double apex = 0;
    for (int k = 0; k < 20000; ++k) {
      se.step(sys);
      const double y = sys.positions()(0, 1), vy = sys.velocities()(0, 1);
      if (vy > 0) bounced = true;
      if (bounced) apex = std::max(apex, y);
      if (bounced && vy < 0) break;
    }
    CHECK(bounced);
    CHECK((apex - 0.05) / 1.0 == doctest::Approx(e * e).epsilon(0.01));
  }
}
