// contact/response/impact_zone_stages.hpp: the inelastic projection keeps a zone's sliding and
// never moves a pinned point; a zone whose pins move differently makes the pass refuse the step
// instead of moving them; a projection that finds the same collisions again hands over to the
// rigid zones at once; and the twisting cloth (scene/contact_recipes.hpp), whose pinned ends
// turn in opposite directions, has no crossing at any step end it commits, and every step it
// does not commit is reported and leaves the state as it was. Crossings are
// counted by tests/support/intersections.hpp (exact predicates, written apart from the
// library's detection).
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <massspring/contact/colliders/colliders.hpp>
#include <massspring/contact/colliders/mesh_shape.hpp>
#include <massspring/contact/response/surface_contact.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/fast_mass_spring.hpp>
#include <massspring/scene/contact_recipes.hpp>
#include <massspring/scene/make_system.hpp>
#include <optional>
#include <vector>

#include "support/intersections.hpp"

namespace {

using massspring::Points;
using massspring::Triangles;
using massspring::Vector;
using Pass = massspring::contact::SurfaceContact<double>;

// Two horizontal triangles: a large one (points 0, 1, 2) at y = 0 and a small one (3, 4, 5) at
// y = 0.05 whose shadow lies inside the large one's.
struct TwoTriangles {
  Points<double> x0 = Points<double>(6, 3);
  Triangles triangles = Triangles(2, 3);
  TwoTriangles() {
    x0 << -1, 0, -1, 1, 0, -1, 0, 0, 1,  //
        -0.1, 0.05, -0.1, 0.1, 0.05, -0.1, 0, 0.05, 0.1;
    triangles << 0, 1, 2, 3, 4, 5;
  }
};

// SurfaceContact::resolve() over the step x0 -> (x1, v1) from rest, the surface's edges those of
// its triangles, the colliders after their begin_step(dt).
massspring::contact::SurfaceContactReport resolve(
    Pass& pass, const Points<double>& x0, Points<double>& x1, Points<double>& v1, double dt,
    const Vector<double>& masses, const std::vector<int>& pinned, const Triangles& triangles,
    const std::optional<massspring::contact::SelfCollision<double>>& self,
    const massspring::contact::ColliderSet<double>& colliders) {
  const Points<double> v0 = Points<double>::Zero(x0.rows(), 3);
  Vector<double> w = masses.cwiseInverse();
  for (int i : pinned) w(i) = 0;
  const massspring::contact::CollisionStep<double> step{x0, v0, x1, v1, dt, masses, w, pinned};
  const massspring::Edges edges = massspring::test::triangle_edges(triangles);
  return pass.resolve({step, triangles, edges, self, colliders});
}

}  // namespace

TEST_CASE(
    "impact zones: the projection lifts a sliding triangle off a pinned one moving up, "
    "keeps its sliding and never moves a pin") {
  const TwoTriangles t;
  const double dt = 0.1;
  // The pinned triangle rises 10 cm; the free one slides 2 cm along x and does not fall.
  Points<double> x1 = t.x0, v1(6, 3);
  x1.topRows(3).col(1).array() += 0.1;
  x1.bottomRows(3).col(0).array() += 0.02;
  v1 = (x1 - t.x0) / dt;
  const Points<double> proposed = x1;
  const Vector<double> masses = Vector<double>::Constant(6, 0.01);
  const std::vector<int> pinned = {0, 1, 2};
  const std::optional<massspring::contact::SelfCollision<double>> self =
      massspring::contact::SelfCollision<double>{0.004, 0.5};
  massspring::contact::ColliderSet<double> colliders;
  Pass pass;
  pass.set_impulse_rounds(0);  // straight to the projection
  const auto r = resolve(pass, t.x0, x1, v1, dt, masses, pinned, t.triangles, self, colliders);
  CHECK(r.resolved);
  CHECK(r.projected_points == 3);
  CHECK(r.zone_points == 0);
  CHECK(x1.topRows(3) == proposed.topRows(3));  // the pins, exactly
  // Each free point is a point-triangle pair with the pinned face (normal +y, gap h / 10): its
  // displacement along y becomes the face's, 0.1 m, plus a tenth of the gap; x and z unchanged.
  const double gap = 0.004 / 10;
  for (int i = 3; i < 6; ++i) {
    CAPTURE(i);
    CHECK(x1(i, 1) - t.x0(i, 1) == doctest::Approx(0.1 + gap / 10).epsilon(1e-9));
    CHECK(std::abs(x1(i, 0) - proposed(i, 0)) <= 1e-12);
    CHECK(std::abs(x1(i, 2) - proposed(i, 2)) <= 1e-12);
    CHECK((v1.row(i) - (x1.row(i) - t.x0.row(i)) / dt).norm() <= 1e-12);
  }
  CHECK(massspring::test::count_crossings(x1, t.triangles,
                                          massspring::test::triangle_edges(t.triangles)) == 0);
}

TEST_CASE("impact zones: pins that move differently through a pinned face are refused, not moved") {
  const TwoTriangles t;
  const double dt = 0.1;
  // Every point pinned; the small triangle's corners fall through the large one by different
  // amounts. No point may move, and no rigid motion carries all three pins.
  Points<double> x1 = t.x0;
  x1(3, 1) -= 0.10;
  x1(4, 1) -= 0.12;
  x1(5, 1) -= 0.08;
  Points<double> v1 = (x1 - t.x0) / dt;
  const Points<double> proposed = x1;
  const Vector<double> masses = Vector<double>::Constant(6, 0.01);
  const std::vector<int> pinned = {0, 1, 2, 3, 4, 5};
  const std::optional<massspring::contact::SelfCollision<double>> self =
      massspring::contact::SelfCollision<double>{};
  massspring::contact::ColliderSet<double> colliders;
  Pass pass;
  const auto r = resolve(pass, t.x0, x1, v1, dt, masses, pinned, t.triangles, self, colliders);
  CHECK_FALSE(r.resolved);
  CHECK(x1 == proposed);
}

// A cloth lying exactly on a mesh collider made of its own triangles (distance 0: every pair
// keeps no gap) and pushed into it. Projecting the same linearised constraints again cannot
// part such pairs; the projection must see that it is stuck after one round and let the rigid
// zones carry the cloth with the obstacle, not spend its 32 rounds re-projecting a growing set.
TEST_CASE(
    "impact zones: a projection that finds the same collisions again hands over to rigid "
    "zones") {
  const int side = 6;  // 6 x 6 points, 0.1 m apart, in the plane y = 0
  Points<double> x0(side * side, 3);
  for (int r = 0; r < side; ++r)
    for (int c = 0; c < side; ++c) x0.row(r * side + c) << 0.1 * c, 0, 0.1 * r;
  Triangles triangles(2 * (side - 1) * (side - 1), 3);
  int t = 0;
  for (int r = 0; r + 1 < side; ++r)
    for (int c = 0; c + 1 < side; ++c) {
      const int i = r * side + c;
      triangles.row(t++) << i, i + 1, i + side;
      triangles.row(t++) << i + 1, i + side + 1, i + side;
    }
  const double dt = 1.0 / 30;
  Points<double> x1 = x0;
  x1.col(1).array() -= 0.01;  // 1 cm down, into the collider
  x1.col(0).array() += 0.002;
  Points<double> v1 = (x1 - x0) / dt;
  const Vector<double> masses = Vector<double>::Constant(side * side, 0.01);
  const std::vector<int> pinned;
  const std::optional<massspring::contact::SelfCollision<double>> self;
  massspring::contact::ColliderSet<double> colliders;
  colliders.add(massspring::contact::Collider<double>::mesh(x0, triangles).set_thickness(0.005));
  colliders.begin_step(dt);
  Pass pass;
  const auto r = resolve(pass, x0, x1, v1, dt, masses, pinned, triangles, self, colliders);
  CHECK(r.resolved);
  // The impulse rounds (at most 12), one projection, one rigid round and the check after it.
  CHECK(r.rounds <= pass.impulse_rounds() + 3);
  CHECK(r.zone_points > 0);
  // No point ends below the collider's plane (an independent check: the plane is y = 0).
  CHECK(x1.col(1).minCoeff() >= -1e-12);
}

TEST_CASE("surface contact: zero rounds of detection are refused when set") {
  Pass pass;
  CHECK_THROWS_WITH_AS(pass.set_max_rounds(0), "surface contact: max_rounds must be >= 1, got 0",
                       massspring::Error);
  CHECK_THROWS_WITH_AS(pass.set_impulse_rounds(-1),
                       "surface contact: impulse_rounds must be >= 0, got -1", massspring::Error);
  CHECK_THROWS_WITH_AS(pass.set_projection_rounds(-2),
                       "surface contact: projection_rounds must be >= 0, got -2",
                       massspring::Error);
  CHECK(pass.max_rounds() == 64);  // unchanged by the refusals
  CHECK(pass.set_max_rounds(1).max_rounds() == 1);
}

// Never silently wrong: with FastMassSpring's defaults, each of the first 32 steps (about half a
// turn of each end: past the step where contact starts, near 13, and the first one refused, near
// 25) either commits an end state with no crossing, or is reported (an energy blow-up or contact
// left unresolved) and leaves the positions and velocities bit for bit. The twist does not yet
// stay bounded: its contact grows over the steps until the energy bound refuses them.
TEST_CASE(
    "impact zones: a cloth twisted by its pinned ends crosses nowhere and reports every "
    "step it refuses") {
  using System = massspring::MassSpringSystem<double>;
  const massspring::SceneDescription<double> scene = massspring::twisting_cloth_scene();
  System s = massspring::make_system<System>(scene);
  s.add_force(massspring::Gravity<double>({0, -9.81, 0}));
  s.set_self_collision(massspring::contact::SelfCollision<double>{0.003, 0.2});
  massspring::FastMassSpring<System> fms;  // the defaults
  const double dt = 1.0 / 30;
  fms.precompute(s, dt);
  const Points<double> start = s.positions();
  const massspring::Edges edges = massspring::test::triangle_edges(s.surface());
  int committed = 0;
  for (int k = 0; k < 32; ++k) {
    for (const int i : scene.pinned)
      s.set_pin_target(i,
                       massspring::twisting_cloth_target(start.row(i).transpose(), (k + 1) * dt));
    const Points<double> x = s.positions(), v = s.velocities();
    const massspring::StepReport r = fms.step(s);
    CAPTURE(k);
    if (r.ok()) {
      ++committed;
      REQUIRE(massspring::test::count_crossings(s.positions(), s.surface(), edges) == 0);
    } else {
      REQUIRE((r.blew_up || !r.contact_resolved || !r.finite));
      REQUIRE(s.positions() == x);
      REQUIRE(s.velocities() == v);
    }
  }
  CHECK(committed > 0);
}
