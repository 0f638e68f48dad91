// integrators/detail/self_contact_term.hpp: self-contact inside BackwardEuler's solve, against
// oracles apart from the code:
// - one pair's correction keeps the pair's momentum when its points are free (sum m_k move_k = 0,
//   computed here from the moves) and restores the distance d = thickness * kDistanceFactor along
//   the normal, with the barycentric weights of the point over the triangle (closed form);
// - a point beside a triangle, past the plane of the triangle but farther than d from it, is not
//   a contact: no correction;
// - pairs are kept by the elements' relative displacement: a point 10 cm over a triangle, both
//   moving 1 m the same way, gives no pair; the point alone moving 10 cm down gives that pair;
// - outgrown(): an iterate within d / 2 of the guess at every point keeps the pairs, one point
//   past it asks for them again;
// - a free triangle falling onto a pinned one comes to rest at d over the pinned triangle's plane
//   (closed form), held within BackwardEuler's solve, even when the step's inertial guess passes
//   through the triangle: the end-of-step pass applies no impulse at any step;
// - with Dense storage (whose solves allocate nothing), a step with the term acting allocates
//   nothing once the pair list has reached its size (the allocation counter of tests/support);
// - two cloth patches dropped one on the other onto the floor never cross (the brute-force
//   counter of tests/support/intersections.hpp) and rest apart, the end-of-step pass doing less
//   than without the term (contact_weight 0).
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <massspring/contact/response/surface_contact.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/detail/self_contact_term.hpp>
#include <massspring/scene/contact_recipes.hpp>
#include <massspring/scene/make_system.hpp>
#include <vector>

#include "support/alloc_counter.hpp"
#include "support/intersections.hpp"

namespace self_contact_term_test {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using Solver = massspring::BackwardEuler<System>;
using Term = massspring::detail::SelfContactTerm<double>;
using V3 = Eigen::Vector3d;
constexpr double kDt = 1.0 / 30;
constexpr double kThickness = 0.004;
constexpr double kKept = kThickness * Term::kDistanceFactor;

// Points 0-2: a large triangle pinned in the plane y = 0; points 3-5: a small free triangle
// (springs 100 N/m at rest, 0.1 kg a point) at height `height` above its interior, moving down at
// `speed` [m/s], under gravity. Surface: both triangles; self-collision without friction.
System falling_triangle(double height, double speed) {
  massspring::Points<double> p(6, 3);
  p << -1, 0, -1, 1, 0, -1, 0, 0, 1,  //
      -0.1, height, -0.1, 0.1, height, -0.1, 0, height, 0.1;
  massspring::Edges e(6, 2);
  e << 0, 1, 1, 2, 2, 0, 3, 4, 4, 5, 5, 3;
  System s(p, e, 0.1, 100.0);
  for (int i = 0; i < 3; ++i) s.pin(i);
  massspring::Points<double> v = massspring::Points<double>::Zero(6, 3);
  for (int i = 3; i < 6; ++i) v(i, 1) = -speed;
  s.set_velocities(v);
  s.add_force(massspring::Gravity<double>(V3(0, -9.81, 0)));
  massspring::Triangles t(2, 3);
  t << 0, 1, 2, 3, 4, 5;
  s.set_surface(t);
  s.set_self_collision({kThickness, 0.0});
  return s;
}

// Every point its own row, in order (BackwardEuler's layout).
std::vector<int> identity(int n) {
  std::vector<int> r(std::size_t(n), 0);
  for (int i = 0; i < n; ++i) r[std::size_t(i)] = i;
  return r;
}

std::vector<double> flat(const massspring::Points<double>& x) {
  return std::vector<double>(x.data(), x.data() + x.size());
}

// A free point (0) at `at` near a free triangle (1, 2, 3) in the plane y = 0, masses all
// different; the point's own triangle (0, 4, 5) rises steeply away from it.
System point_and_triangle(const V3& at) {
  massspring::Points<double> q(6, 3);
  q << at.x(), at.y(), at.z(),        //
      0, 0, 0, 0.3, 0, 0, 0, 0, 0.3,  //
      at.x(), 0.5, at.z(), at.x(), 0.5, at.z() + 0.45;
  massspring::Edges qe(6, 2);
  qe << 1, 2, 2, 3, 3, 1, 0, 4, 4, 5, 5, 0;
  System s(q, qe, 1.0, 10.0);
  massspring::Vector<double> m(6);
  m << 0.3, 0.5, 0.7, 1.1, 0.2, 0.4;
  s.set_masses(m);
  massspring::Triangles t(2, 3);
  t << 1, 2, 3, 0, 4, 5;
  s.set_surface(t);
  s.set_self_collision({kThickness, 0.0});
  return s;
}

TEST_CASE("self contact term: one pair's correction keeps its momentum and restores d") {
  // The point 1 mm over (0.1, 0.05) of the triangle: the pair (0; 1, 2, 3) is the only one
  // closer than d.
  System s = point_and_triangle(V3(0.1, 0.001, 0.05));
  Term term;
  term.build(s, identity(6), identity(6), 6);
  std::vector<double> x = flat(s.positions());
  term.prepare(s, x.data());
  REQUIRE(term.active());
  std::vector<double> move(18, 0.0);
  REQUIRE(term.correct(x.data(), nullptr, 6, move.data()));
  V3 momentum = V3::Zero();
  for (int i = 0; i < 6; ++i)
    momentum += s.masses()(i) * V3(move[std::size_t(3 * i)], move[std::size_t(3 * i + 1)],
                                   move[std::size_t(3 * i + 2)]);
  CHECK(momentum.norm() < 1e-15);
  // Points 4 and 5 are in no close pair: not moved.
  for (int k = 12; k < 18; ++k) CHECK(move[std::size_t(k)] == 0.0);
  // Along the pair's normal (+y, the side the point started on) and with its barycentric
  // weights at x (1/2, 1/3, 1/6: the point is over (0.1, 0.05) of the triangle), the moves
  // restore the distance d exactly.
  std::vector<double> y = x;
  for (std::size_t k = 0; k < 18; ++k) y[k] += move[k];
  const double height = y[1] - (y[4] / 2 + y[7] / 3 + y[10] / 6);
  CHECK(height == doctest::Approx(kKept).epsilon(1e-12));
  // Only normal moves (no friction).
  for (int i = 0; i < 4; ++i) {
    CHECK(move[std::size_t(3 * i)] == 0.0);
    CHECK(move[std::size_t(3 * i + 2)] == 0.0);
  }
}

TEST_CASE(
    "self contact term: past the plane of a triangle beside it is no contact; through its face "
    "on the way is") {
  // Start: the point 1 mm over (0.1, 0.05) of the triangle's face (the pair records the side
  // +y). The point then ends 2 mm below the triangle's plane, beside its long edge x + z = 0.3.
  System s = point_and_triangle(V3(0.1, 0.001, 0.05));
  Term term;
  term.build(s, identity(6), identity(6), 6);
  const std::vector<double> x = flat(s.positions());
  term.prepare(s, x.data());
  REQUIRE(term.active());
  std::vector<double> move(18, 1.0);
  SUBCASE("its straight path crosses the plane beside the face: no contact") {
    // To (0.4, -0.002, 0.4): the path meets y = 0 a third of the way, at x + z = 0.383 > 0.3;
    // the point ends 0.35 m from the triangle.
    std::vector<double> y = x;
    y[0] = 0.4;
    y[1] = -0.002;
    y[2] = 0.4;
    CHECK_FALSE(term.correct(y.data(), nullptr, 6, move.data()));
    for (double m : move) CHECK(m == 0.0);
  }
  SUBCASE("its straight path crosses the face: pushed back to d on its side") {
    // To 2 cm beside the long edge: the path meets y = 0 a third of the way (heights 1 mm and
    // -2 mm), at (X, Z) below, inside the face, so the pair crossed; its weights are the
    // barycentric coordinates there, (1 - X / 0.3 - Z / 0.3, X / 0.3, Z / 0.3) on the corners
    // (0, 0, 0), (0.3, 0, 0), (0, 0, 0.3).
    const double out = 0.02 / std::sqrt(2.0);
    std::vector<double> y = x;
    y[0] = 0.2 + out;
    y[1] = -0.002;
    y[2] = 0.1 + out;
    const double X = 0.1 + (y[0] - 0.1) / 3, Z = 0.05 + (y[2] - 0.05) / 3;
    REQUIRE(X + Z < 0.3);
    REQUIRE(term.correct(y.data(), nullptr, 6, move.data()));
    for (std::size_t k = 0; k < 18; ++k) y[k] += move[k];
    const double height =
        y[1] - ((1 - X / 0.3 - Z / 0.3) * y[4] + X / 0.3 * y[7] + Z / 0.3 * y[10]);
    CHECK(height == doctest::Approx(kKept).epsilon(1e-12));
  }
  SUBCASE("over the face, below it: pushed back to d on its side") {
    std::vector<double> y = x;
    y[1] = -0.002;
    REQUIRE(term.correct(y.data(), nullptr, 6, move.data()));
    for (std::size_t k = 0; k < 18; ++k) y[k] += move[k];
    const double height = y[1] - (y[4] / 2 + y[7] / 3 + y[10] / 6);
    CHECK(height == doctest::Approx(kKept).epsilon(1e-12));
  }
}

TEST_CASE("self contact term: pairs are kept by the elements' relative displacement") {
  System s = point_and_triangle(V3(0.1, 0.1, 0.05));
  Term term;
  term.build(s, identity(6), identity(6), 6);
  std::vector<double> guess = flat(s.positions());
  for (std::size_t k = 0; k < guess.size(); k += 3) guess[k] += 1.0;  // all 1 m along x
  term.prepare(s, guess.data());
  CHECK(term.pairs() == 0);
  guess = flat(s.positions());
  guess[1] -= 0.1;  // the point alone onto the triangle's plane
  term.prepare(s, guess.data());
  CHECK(term.pairs() >= 1);
}

TEST_CASE("self contact term: outgrown() past d / 2 of the guess at any point") {
  System s = point_and_triangle(V3(0.1, 0.001, 0.05));
  Term term;
  CHECK_FALSE(term.outgrown(flat(s.positions()).data()));  // not built
  term.build(s, identity(6), identity(6), 6);
  std::vector<double> x = flat(s.positions());
  term.prepare(s, x.data());
  std::vector<double> y = x;
  for (std::size_t k = 0; k < y.size(); ++k) y[k] += 0.49 * kKept / std::sqrt(3.0);
  CHECK_FALSE(term.outgrown(y.data()));
  y[14] += 0.02 * kKept;  // point 4's z: now more than d / 2 from the guess
  CHECK(term.outgrown(y.data()));
}

TEST_CASE(
    "self contact term: a triangle falling onto a pinned one rests at d, held within "
    "BackwardEuler's solve") {
  for (const double speed : {0.0, 0.5, 2.0}) {
    CAPTURE(speed);
    System s = falling_triangle(0.03, speed);
    Solver solver;  // the defaults: the contact term on, self-contact in it
    solver.precompute(s, kDt);
    int impulses = 0;
    for (int step = 0; step < 90; ++step) {
      const massspring::StepReport r = solver.step(s);
      REQUIRE(r.ok());
      impulses += r.contact_impulses;
      for (int i = 3; i < 6; ++i) REQUIRE(s.positions()(i, 1) > kThickness);
    }
    CHECK(impulses == 0);
    // At rest on the plane y = 0 at the distance d (closed form: the pinned triangle's normal is
    // the y axis and every free corner is over its interior).
    for (int i = 3; i < 6; ++i) {
      CHECK(s.positions()(i, 1) == doctest::Approx(kKept).epsilon(1e-4));
      CHECK(std::abs(s.velocities()(i, 1)) < 1e-4);
    }
  }
}

TEST_CASE("self contact term: BackwardEuler's step with the term acting allocates nothing") {
  using DenseSystem = massspring::MassSpringSystem<double, massspring::Dense>;
  System sparse = falling_triangle(0.03, 0.5);
  DenseSystem s(sparse.positions(), sparse.springs(), 0.1, 100.0);
  for (int i = 0; i < 3; ++i) s.pin(i);
  s.set_velocities(sparse.velocities());
  s.add_force(massspring::Gravity<double>(V3(0, -9.81, 0)));
  s.set_surface(sparse.surface());
  s.set_self_collision({kThickness, 0.0});
  massspring::BackwardEuler<DenseSystem> solver;
  solver.precompute(s, kDt);
  for (int step = 0; step < 30; ++step) REQUIRE(solver.step(s).ok());
  REQUIRE(s.positions()(3, 1) < 2 * kKept);  // resting: the pairs act at every iterate
  massspring::test::CountAllocations count;
  for (int step = 0; step < 5; ++step) REQUIRE(solver.step(s).ok());
  CHECK(count.count() == 0);
}

TEST_CASE("self contact term: two cloth patches dropped one on the other never cross") {
  namespace d = massspring::detail;
  int impulses[2] = {0, 0};
  for (const double weight : {1.0, 0.0}) {  // the default; the term off
    CAPTURE(weight);
    massspring::SceneDescription<double> scene = d::disjoint_union(
        d::contact_cloth(11, 11, 0.5, 0.5, 0.05), d::contact_cloth(11, 11, 0.4, 0.4, 0.1));
    scene.colliders = {d::contact_floor()};
    System s = massspring::make_system<System>(scene);
    s.add_force(massspring::Gravity<double>(V3(0, -9.81, 0)));
    s.set_self_collision({kThickness, 0.3});
    Solver solver;
    solver.options.contact_weight = weight;
    solver.precompute(s, kDt);
    const massspring::Triangles& triangles = s.surface();
    int crossings = 0;
    for (int step = 0; step < 60; ++step) {
      const massspring::StepReport r = solver.step(s);
      REQUIRE(r.ok());
      impulses[weight > 0 ? 0 : 1] += r.contact_impulses;
      if (std::getenv("DBG"))
        printf("w %g step %d imp %d it %d conv %d\n", weight, step, r.contact_impulses,
               r.iterations, int(r.converged));
      crossings += massspring::test::count_crossings(s.positions(), triangles);
    }
    CHECK(crossings == 0);
    // Resting on the floor, the upper patch (the second) above the lower one on average.
    const int n = int(s.num_points()) / 2;
    const double lower = s.positions().col(1).head(n).mean();
    const double upper = s.positions().col(1).tail(n).mean();
    CHECK(upper - lower > kThickness / 2);
    CHECK(upper < 0.05);
  }
  CHECK(impulses[0] < impulses[1]);
}

}  // namespace self_contact_term_test
