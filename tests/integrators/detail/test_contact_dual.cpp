// integrators/detail/contact_dual.hpp: edge_distance() in closed form, and what it is for: a
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

TEST_CASE("edge_distance: the longest surface edge over sqrt(2), with a box or a capsule; else 0") {
  // 11 x 11 points over 0.5 m: squares of 5 cm cut into triangles, whose diagonals (7.07 cm) are
  // the longest edges: rho = 0.05 sqrt(2) / sqrt(2) = 5 cm.
  massspring::SceneDescription<double> scene =
      massspring::detail::contact_cloth(11, 11, 0.5, 0.5, 1.0);
  scene.colliders = {box(V3(0, 0.5, 0), V3(0.2, 0.2, 0.2))};
  const System with_box = massspring::make_system<System>(scene);
  REQUIRE(with_box.surface().rows() > 0);
  CHECK(massspring::detail::edge_distance(with_box) == doctest::Approx(0.05).epsilon(1e-12));

  massspring::ColliderDescription<double> rod;
  rod.shape = massspring::contact::ColliderShape::Capsule;
  rod.a = V3(-0.5, 0.5, 0);
  rod.b = V3(0.5, 0.5, 0);
  rod.radius = 0.01;
  scene.colliders = {rod};
  CHECK(massspring::detail::edge_distance(massspring::make_system<System>(scene)) ==
        doctest::Approx(0.05).epsilon(1e-12));

  scene.colliders = {massspring::detail::contact_sphere(V3(0, 0.5, 0), 0.2)};
  CHECK(massspring::detail::edge_distance(massspring::make_system<System>(scene)) == 0);

  scene.colliders = {box(V3(0, 0.5, 0), V3(0.2, 0.2, 0.2))};
  System no_surface = massspring::make_system<System>(scene);
  no_surface.set_surface(massspring::Triangles(0, 3));
  CHECK(massspring::detail::edge_distance(no_surface) == 0);
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
