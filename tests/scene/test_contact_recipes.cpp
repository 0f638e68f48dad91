// scene/contact_recipes.hpp: the sizes, masses and obstacles each scene states, and that each
// starts clean: no crossing and a positive separation of its surface (tests/support/
// intersections.hpp, independent of the library's contact code), and every point outside every
// obstacle by at least 5 cm, the distances computed here by hand.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <massspring/scene/contact_recipes.hpp>
#include <string>
#include <vector>

#include "massspring/scene/collider_description.hpp"
#include "massspring/scene/face_springs.hpp"
#include "massspring/scene/voronoi_masses.hpp"
#include "support/intersections.hpp"

namespace {

using massspring::ColliderDescription;
using massspring::SceneDescription;
using massspring::Triangles;
using Shape = massspring::contact::ColliderShape;
using V3 = Eigen::Vector3d;

// The faces as #faces x 3 triangles; every face of these scenes is a triangle.
Triangles triangles_of(const SceneDescription<double>& s) {
  REQUIRE(std::all_of(s.faces.begin(), s.faces.end(),
                      [](const std::vector<int>& f) { return f.size() == 3; }));
  Triangles t(Eigen::Index(s.faces.size()), 3);
  for (std::size_t f = 0; f < s.faces.size(); ++f)
    t.row(Eigen::Index(f)) << s.faces[f][0], s.faces[f][1], s.faces[f][2];
  return t;
}

// Signed distance from x to the surface of an obstacle (negative inside), by hand: a plane's
// (x - point) . n / |n|; a sphere's |x - center| - radius; a capsule's distance to its axis
// segment (the clamped projection) minus the radius.
double clearance(const ColliderDescription<double>& c, const V3& x) {
  switch (c.shape) {
    case Shape::Plane:
      return (x - c.point).dot(c.normal) / c.normal.norm();
    case Shape::Sphere:
      return (x - c.center).norm() - c.radius;
    case Shape::Capsule: {
      const V3 d = c.b - c.a;
      const double t = std::clamp((x - c.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      return (x - (c.a + t * d)).norm() - c.radius;
    }
    default:
      FAIL("no hand-made distance for this shape");
      return 0;
  }
}

// The smallest clearance of any point from any collider.
double min_clearance(const SceneDescription<double>& s) {
  double m = std::numeric_limits<double>::infinity();
  for (const auto& c : s.colliders)
    for (Eigen::Index i = 0; i < s.vertices.rows(); ++i)
      m = std::min(m, clearance(c, s.vertices.row(i).transpose()));
  return m;
}

// Springs of a columns x rows cloth with one diagonal per cell and skip-one bending springs.
int cloth_springs(int c, int r) {
  return (c - 1) * r + c * (r - 1) + (c - 1) * (r - 1) + (c - 2) * r + c * (r - 2);
}

// What every contact scene shares: triangle faces, k = 1000, nothing pinned, the floor y = 0
// first, valid colliders (make_collider accepts them), a clean surface, 5 cm of clearance.
// Returns the surface's triangles.
Triangles check_common(const SceneDescription<double>& s, double separation) {
  CHECK(s.stiffness == 1000);
  CHECK(s.pinned.empty());
  REQUIRE(!s.colliders.empty());
  CHECK(s.colliders[0].shape == Shape::Plane);
  CHECK(s.colliders[0].point == V3::Zero());
  CHECK(s.colliders[0].normal == V3::UnitY());
  for (const auto& c : s.colliders) {
    CHECK(c.static_friction == 0.3);
    CHECK_NOTHROW(massspring::make_collider<double>(c));
  }
  const Triangles t = triangles_of(s);
  CHECK(massspring::test::count_crossings(s.vertices, t) == 0);
  CHECK(massspring::test::min_separation(s.vertices, t) ==
        doctest::Approx(separation).epsilon(1e-9));
  CHECK(min_clearance(s) >= 0.05 - 1e-12);
  return t;
}

}  // namespace

TEST_CASE("clothesline: a 31 x 31 cloth, 4 cm spacing, 10 cm above a 1 cm rod along x") {
  const SceneDescription<double> s = massspring::clothesline_scene();
  REQUIRE(s.vertices.rows() == 31 * 31);
  CHECK(s.faces.size() == 2 * 30 * 30);
  CHECK(massspring::face_springs(31 * 31, s.faces, s.edges).rows() == cloth_springs(31, 31));
  CHECK((s.vertices.col(1).array() == 1.1).all());  // horizontal, at y = 1.1
  CHECK(s.vertices.col(0).minCoeff() == doctest::Approx(-0.6));
  CHECK(s.vertices.col(0).maxCoeff() == doctest::Approx(0.6));
  CHECK(s.vertices.col(2).minCoeff() == doctest::Approx(-0.6));
  CHECK(s.vertices.col(2).maxCoeff() == doctest::Approx(0.6));
  CHECK((s.vertices.row(1) - s.vertices.row(0)).norm() == doctest::Approx(0.04));
  CHECK(massspring::voronoi_masses(s.vertices, s.faces).sum() == doctest::Approx(1.44));

  REQUIRE(s.colliders.size() == 2);
  const ColliderDescription<double>& rod = s.colliders[1];
  CHECK(rod.shape == Shape::Capsule);
  CHECK(rod.radius == 0.01);
  CHECK(rod.a.y() == 1.0);
  CHECK(rod.b.y() == 1.0);
  CHECK((rod.b - rod.a).normalized().isApprox(V3::UnitX()));
  CHECK(rod.a.x() + rod.b.x() == 0);  // centred under the cloth's centre (0, 1.1, 0)
  CHECK(rod.a.z() == 0);
  CHECK(rod.b.z() == 0);
  CHECK(rod.b.x() - rod.a.x() > 1.2);  // longer than the cloth is wide

  // The row z = 0 lies right above the axis: 10 cm from it, 9 cm from the rod's surface.
  const Triangles t = check_common(s, 0.04 / std::sqrt(2.0));
  CHECK(clearance(rod, V3(0, 1.1, 0)) == doctest::Approx(0.09));
  double closest = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < s.vertices.rows(); ++i)
    closest = std::min(closest, clearance(rod, s.vertices.row(i).transpose()));
  CHECK(closest == doctest::Approx(0.09));
  CHECK(massspring::test::count_segment_crossings(s.vertices, t, rod.a, rod.b) == 0);
}

TEST_CASE("ribbon_pile: a 0.24 m x 1.8 m ribbon of 9 x 61 points, upright, 5 cm above the floor") {
  const SceneDescription<double> s = massspring::ribbon_pile_scene();
  REQUIRE(s.vertices.rows() == 9 * 61);
  CHECK(s.faces.size() == 2 * 8 * 60);
  CHECK(massspring::face_springs(9 * 61, s.faces, s.edges).rows() == cloth_springs(9, 61));
  CHECK(massspring::voronoi_masses(s.vertices, s.faces).sum() == doctest::Approx(0.24 * 1.8));
  REQUIRE(s.colliders.size() == 1);
  // Lower end (row 60) 5 cm above the floor; the top 1.8 cos(0.05) higher; centred on x = 0.
  CHECK(s.vertices.col(1).minCoeff() == doctest::Approx(0.05));
  CHECK(s.vertices(60 * 9, 1) == doctest::Approx(0.05));
  CHECK(s.vertices.col(1).maxCoeff() == doctest::Approx(0.05 + 1.8 * std::cos(0.05)));
  CHECK(s.vertices.col(0).minCoeff() == doctest::Approx(-0.12));
  CHECK(s.vertices.col(0).maxCoeff() == doctest::Approx(0.12));
  // Nearly upright: the tilt moves the top 1.8 sin(0.05) = 9 cm along z.
  CHECK(s.vertices.col(2).maxCoeff() == doctest::Approx(1.8 * std::sin(0.05)));
  // Spacing 3 cm both ways (a rigid tilt of a flat grid): separation 0.03 / sqrt(2).
  CHECK((s.vertices.row(1) - s.vertices.row(0)).norm() == doctest::Approx(0.03));
  CHECK((s.vertices.row(9) - s.vertices.row(0)).norm() == doctest::Approx(0.03));
  check_common(s, 0.03 / std::sqrt(2.0));
}

TEST_CASE("two_cloths_on_ball: two 21 x 21 cloths, 10 cm apart, above a 0.3 m ball") {
  const SceneDescription<double> s = massspring::two_cloths_on_ball_scene();
  REQUIRE(s.vertices.rows() == 2 * 21 * 21);
  CHECK(s.faces.size() == 2 * 2 * 20 * 20);
  CHECK(massspring::face_springs(2 * 441, s.faces, s.edges).rows() == 2 * cloth_springs(21, 21));
  CHECK(massspring::voronoi_masses(s.vertices, s.faces).sum() == doctest::Approx(2.0));
  // Points 0 ... 440 at y = 0.8, 441 ... 881 at y = 0.9; no face or spring joins the two.
  CHECK((s.vertices.topRows(441).col(1).array() == 0.8).all());
  CHECK((s.vertices.bottomRows(441).col(1).array() == 0.9).all());
  int joining = 0;
  for (const auto& f : s.faces)
    joining += (f[0] < 441) != (f[1] < 441) || (f[1] < 441) != (f[2] < 441);
  for (Eigen::Index e = 0; e < s.edges.rows(); ++e)
    joining += (s.edges(e, 0) < 441) != (s.edges(e, 1) < 441);
  CHECK(joining == 0);
  CHECK(s.vertices.col(0).minCoeff() == doctest::Approx(-0.5));
  CHECK(s.vertices.col(0).maxCoeff() == doctest::Approx(0.5));
  REQUIRE(s.colliders.size() == 2);
  const ColliderDescription<double>& ball = s.colliders[1];
  CHECK(ball.shape == Shape::Sphere);
  CHECK(ball.radius == 0.3);
  CHECK(ball.center.isApprox(V3(0, 0.3, 0)));
  // The lower cloth's centre is 20 cm above the ball's top: the closest point to any obstacle.
  CHECK(min_clearance(s) == doctest::Approx(0.2));
  // Within each cloth 0.05 / sqrt(2) = 3.5 cm < the 10 cm between them.
  check_common(s, 0.05 / std::sqrt(2.0));
}

TEST_CASE("large_drape: 81 x 81 points over 2 m, 1.9 kg, k = 1000, over a 0.5 m ball") {
  const SceneDescription<double> s = massspring::large_drape_scene();
  REQUIRE(s.vertices.rows() == 81 * 81);
  CHECK(s.faces.size() == 2 * 80 * 80);
  CHECK(massspring::face_springs(81 * 81, s.faces, s.edges).rows() == cloth_springs(81, 81));
  REQUIRE(s.mass.has_value());
  CHECK(*s.mass * 81 * 81 == doctest::Approx(1.9));
  CHECK((s.vertices.col(1).array() == 1.1).all());
  CHECK(s.vertices.col(0).minCoeff() == doctest::Approx(-1.0));
  CHECK(s.vertices.col(0).maxCoeff() == doctest::Approx(1.0));
  CHECK(s.vertices.col(2).minCoeff() == doctest::Approx(-1.0));
  CHECK(s.vertices.col(2).maxCoeff() == doctest::Approx(1.0));
  REQUIRE(s.colliders.size() == 2);
  const ColliderDescription<double>& ball = s.colliders[1];
  CHECK(ball.shape == Shape::Sphere);
  CHECK(ball.radius == 0.5);
  CHECK(ball.center.isApprox(V3(0, 0.5, 0)));
  CHECK(min_clearance(s) == doctest::Approx(0.1));  // the cloth's centre above the ball's top
  check_common(s, 0.025 / std::sqrt(2.0));
}
