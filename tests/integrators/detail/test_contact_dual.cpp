// integrators/detail/contact_dual.hpp: edge_distances() in closed form, and what it is for: a
// cloth dropped on a table (a box) with FastMassSpring's defaults at dt = 1/30 s ends with no
// link past 15% strain and no cloth edge meeting the box, both computed here from the positions
// (a slab test per edge), the end-of-step pass having nothing to hold at the rim. Likewise a
// cloth hung on a 1 cm rod (a capsule): no cloth edge comes within the rod's radius of its axis
// (a distance between segments computed here), and once it hangs no link passes 15% and the pass
// has almost nothing to do at the rod.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <massspring/contact/colliders/box_shape.hpp>
#include <massspring/contact/self_collision.hpp>
#include <massspring/forces/gravity.hpp>
#include <massspring/integrators/backward_euler.hpp>
#include <massspring/integrators/detail/contact_dual.hpp>
#include <massspring/integrators/local_global/fast_mass_spring.hpp>
#include <massspring/scene/contact_recipes.hpp>
#include <massspring/scene/make_system.hpp>

#include "support/box_checks.hpp"
#include "support/segment_checks.hpp"

namespace contact_dual_test {

using System = massspring::MassSpringSystem<double, massspring::Sparse>;
using V3 = Eigen::Vector3d;

// The largest strain |l / l0 - 1| of the system's springs.
double largest_strain(const System& s) {
  double worst = 0;
  for (Eigen::Index e = 0; e < s.springs().rows(); ++e) {
    const double l =
        (s.positions().row(s.springs()(e, 0)) - s.positions().row(s.springs()(e, 1))).norm();
    worst = std::max(worst, std::abs(l / s.rest_lengths()(e) - 1));
  }
  return worst;
}

// A box collider description: centre c, half extents h, friction 0.3.
massspring::ColliderDescription<double> box(const V3& c, const V3& h) {
  massspring::ColliderDescription<double> b;
  b.shape = massspring::contact::ColliderShape::Box;
  b.center = c;
  b.half_extents = h;
  b.static_friction = b.kinetic_friction = 0.3;
  return b;
}

}  // namespace contact_dual_test

using namespace contact_dual_test;

TEST_CASE("edge_distances: per point, the longest edge of its triangles over sqrt(2); else 0") {
  // 11 x 11 points over 0.5 m: squares of 5 cm cut into triangles, whose diagonals (7.07 cm) are
  // the longest edges: rho = 0.05 sqrt(2) / sqrt(2) = 5 cm at every point.
  massspring::SceneDescription<double> scene =
      massspring::detail::contact_cloth(11, 11, 0.5, 0.5, 1.0);
  scene.colliders = {box(V3(0, 0.5, 0), V3(0.2, 0.2, 0.2))};
  System with_box = massspring::make_system<System>(scene);
  REQUIRE(with_box.surface().rows() > 0);
  Eigen::VectorXd rho;
  massspring::detail::edge_distances(with_box, rho);
  REQUIRE(rho.size() == 121);
  for (Eigen::Index i = 0; i < rho.size(); ++i)
    CHECK(rho(i) == doctest::Approx(0.05).epsilon(1e-12));

  // One point lifted 1 m: the edges from it are the longest of its triangles (over 1 m against
  // 7.07 cm), so its rho is its farthest triangle neighbour's distance over sqrt(2), each
  // neighbour's at least its own distance from it over sqrt(2); every other point keeps 5 cm.
  const int lifted = 5 * 11 + 5;
  massspring::Points<double> moved = with_box.positions();
  moved(lifted, 1) += 1;
  with_box.set_positions(moved);
  massspring::detail::edge_distances(with_box, rho);
  std::vector<double> from_lifted(121, 0.0);  // distance to `lifted` of its triangle neighbours
  const massspring::Triangles& t = with_box.surface();
  for (Eigen::Index f = 0; f < t.rows(); ++f) {
    if (t(f, 0) != lifted && t(f, 1) != lifted && t(f, 2) != lifted) continue;
    for (int k = 0; k < 3; ++k)
      from_lifted[std::size_t(t(f, k))] = (moved.row(t(f, k)) - moved.row(lifted)).norm();
  }
  double farthest = 0;
  for (int i = 0; i < 121; ++i) {
    farthest = std::max(farthest, from_lifted[std::size_t(i)]);
    if (i == lifted) continue;
    if (from_lifted[std::size_t(i)] == 0)
      CHECK(rho(i) == doctest::Approx(0.05).epsilon(1e-12));
    else
      CHECK(rho(i) >= from_lifted[std::size_t(i)] / std::sqrt(2.0) * (1 - 1e-12));
  }
  CHECK(farthest > 1);
  CHECK(rho(lifted) == doctest::Approx(farthest / std::sqrt(2.0)).epsilon(1e-12));

  massspring::ColliderDescription<double> rod;
  rod.shape = massspring::contact::ColliderShape::Capsule;
  rod.a = V3(-0.5, 0.5, 0);
  rod.b = V3(0.5, 0.5, 0);
  rod.radius = 0.01;
  scene.colliders = {rod};
  massspring::detail::edge_distances(massspring::make_system<System>(scene), rho);
  CHECK(rho.minCoeff() == doctest::Approx(0.05).epsilon(1e-12));
  CHECK(rho.maxCoeff() == doctest::Approx(0.05).epsilon(1e-12));

  scene.colliders = {massspring::detail::contact_sphere(V3(0, 0.5, 0), 0.2)};
  massspring::detail::edge_distances(massspring::make_system<System>(scene), rho);
  CHECK(rho.size() == 121);
  CHECK(rho.isZero(0));

  scene.colliders = {box(V3(0, 0.5, 0), V3(0.2, 0.2, 0.2))};
  System no_surface = massspring::make_system<System>(scene);
  no_surface.set_surface(massspring::Triangles(0, 3));
  massspring::detail::edge_distances(no_surface, rho);
  CHECK(rho.isZero(0));
}

TEST_CASE("a cloth with one far point over a rod: its long triangles' band throws nothing out") {
  // The clothesline's cloth 10 cm over its 1 cm rod, one point 30 m away (its springs at rest
  // there): the band of its triangles is 21 m wide, but the points start 10 cm from the axis, and
  // the band never pushes a point farther than it started, so one step moves every point by
  // about what gravity gives (g dt^2 = 1.1 cm), not by metres.
  massspring::SceneDescription<double> scene = massspring::clothesline_scene();
  const int far = 5 * 31 + 15;
  scene.vertices(far, 2) += 30;
  System s = massspring::make_system<System>(scene);
  s.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  const massspring::Points<double> start = s.positions();
  for (const bool backward_euler : {false, true}) {
    s.set_positions(start);
    s.set_velocities(massspring::Points<double>::Zero(start.rows(), 3));
    massspring::StepReport report;
    if (backward_euler) {
      massspring::BackwardEuler<System> solver;  // the defaults
      solver.precompute(s, 1.0 / 30);
      report = solver.step(s);
    } else {
      massspring::FastMassSpring<System> solver;  // the defaults
      solver.precompute(s, 1.0 / 30);
      report = solver.step(s);
    }
    REQUIRE(report.ok());
    CHECK((s.positions() - start).rowwise().norm().maxCoeff() < 0.05);
  }
}

TEST_CASE("a cloth dropped on a table: no link past 15%, no cloth edge through the box") {
  // 31 x 31 points over 1.2 m (4 cm squares) at y = 0.85 over a table 0.6 m wide, top at 0.75 m.
  massspring::SceneDescription<double> scene =
      massspring::detail::contact_cloth(31, 31, 1.2, 1.2, 0.85);
  const V3 centre(0, 0.375, 0), half(0.3, 0.375, 0.3);
  scene.colliders = {massspring::detail::contact_floor(), box(centre, half)};
  System s = massspring::make_system<System>(scene);
  s.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  massspring::FastMassSpring<System> solver;  // the defaults
  solver.precompute(s, 1.0 / 30);
  for (int k = 0; k < 60; ++k) REQUIRE(solver.step(s).ok());
  CHECK(largest_strain(s) <= 0.15);
  int through = 0;
  const massspring::Triangles& t = s.surface();
  for (Eigen::Index f = 0; f < t.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      through += massspring::test::segment_meets_box(
          s.positions().row(t(f, k)).transpose(), s.positions().row(t(f, (k + 1) % 3)).transpose(),
          centre, half);
  CHECK(through == 0);
  // The cloth lies on the table: its middle point over the top (0.75 m), by no more than the
  // edge distance the rim holds it at (4 cm: the 5.66 cm diagonals over sqrt(2)).
  const int middle = 15 * 31 + 15;
  CHECK(s.positions()(middle, 1) >= 0.75);
  CHECK(s.positions()(middle, 1) <= 0.75 + 0.04);
}

TEST_CASE(
    "a cloth hung on a 1 cm rod: no cloth edge into the rod, no link past 15% once it hangs") {
  // The clothesline: 31 x 31 points over 1.2 m (4 cm squares) dropped from 10 cm onto a rod of
  // radius 1 cm (friction 0.3), self-collision 4 mm thick; its halves meet under the rod in the
  // first second.
  const massspring::SceneDescription<double> scene = massspring::clothesline_scene();
  const V3 a = scene.colliders[1].a, b = scene.colliders[1].b;
  const double radius = scene.colliders[1].radius;
  System s = massspring::make_system<System>(scene);
  s.add_force(massspring::Gravity<double>({0, -9.8, 0}));
  massspring::contact::SelfCollision<double> self;
  self.thickness = 0.004;
  self.friction = 0.3;
  s.set_self_collision(self);
  massspring::FastMassSpring<System> solver;  // the defaults
  solver.precompute(s, 1.0 / 30);
  double nearest = 1e300, worst = 0;
  int impulses = 0;
  const massspring::Triangles& t = s.surface();
  for (int k = 1; k <= 60; ++k) {
    const massspring::StepReport report = solver.step(s);
    REQUIRE(report.ok());
    for (Eigen::Index f = 0; f < t.rows(); ++f)
      for (int j = 0; j < 3; ++j) {
        const V3 p = s.positions().row(t(f, j)).transpose(),
                 q = s.positions().row(t(f, (j + 1) % 3)).transpose();
        if ((p - a).y() > 0.1 || (q - a).y() > 0.1 || std::abs(p.z()) > 0.1) continue;  // far
        nearest = std::min(nearest, massspring::test::segment_segment_distance(p, q, a, b));
      }
    if (k > 30) {  // hanging
      worst = std::max(worst, largest_strain(s));
      impulses += report.contact_impulses;
    }
  }
  CHECK(nearest >= radius);
  CHECK(worst <= 0.15);
  CHECK(impulses < 100);  // the pass has (almost) nothing left to do at the rod
  // It hangs on the rod: some of it above the rod's top, all of it above y = 0.3.
  CHECK(s.positions().col(1).maxCoeff() > 1.01);
  CHECK(s.positions().col(1).minCoeff() > 0.3);
}
