// scene/make_system.hpp: a SceneDescription becomes the system it describes.
#include <doctest/doctest.h>

#include <cmath>
#include <massspring/scene/make_system.hpp>
#include <vector>

#include "massspring/system/mass_spring_system.hpp"

namespace {

using massspring::Dense;
using massspring::Error;
using massspring::make_system;
using massspring::MassSpringSystem;
using massspring::SceneDescription;
using massspring::Sparse;
using SparseSystem = MassSpringSystem<double, Sparse>;

// A unit square (0, 1, 2, 3) as one quad, a tail 2-4 as an edge.
SceneDescription<double> square_with_tail() {
  SceneDescription<double> s;
  s.vertices.resize(5, 3);
  s.vertices << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 3, 0;
  s.faces = {{0, 1, 2, 3}};
  s.edges.resize(1, 2);
  s.edges << 4, 2;
  s.pinned = {3, 0};
  s.stiffness = 40;
  s.mass = 0.5;
  return s;
}

}  // namespace

TEST_CASE_TEMPLATE("make_system: springs from faces and edges, rest lengths, mass, stiffness, pins",
                   System, MassSpringSystem<double, Dense>, MassSpringSystem<double, Sparse>,
                   MassSpringSystem<float, Dense>, MassSpringSystem<float, Sparse>) {
  using Scalar = typename System::Scalar;
  const auto scene = square_with_tail();
  const System s = make_system<System>(scene);
  CHECK(s.num_points() == 5);
  CHECK(s.num_springs() == 7);  // 4 sides + 2 diagonals + the tail
  int sides = 0, diagonals = 0, tails = 0;
  for (int e = 0; e < s.num_springs(); ++e) {
    const Scalar r = s.rest_lengths()(e);
    if (r == Scalar(1)) ++sides;
    if (std::abs(r - Scalar(std::sqrt(2.0))) < Scalar(1e-6)) ++diagonals;
    if (r == Scalar(2)) ++tails;
  }
  CHECK(sides == 4);
  CHECK(diagonals == 2);
  CHECK(tails == 1);
  CHECK((s.masses().array() == Scalar(0.5)).all());
  CHECK((s.stiffness().array() == Scalar(40)).all());
  CHECK(s.pinned() == std::vector<int>{0, 3});
  CHECK(s.pin_targets().row(1) == s.rest_positions().row(3));
  CHECK(s.positions() == s.rest_positions());
  CHECK(s.velocities().isZero(0));
}

TEST_CASE("make_system: without a mass, each point gets its lumped Voronoi area") {
  auto scene = square_with_tail();
  scene.edges.resize(0, 2);
  scene.vertices.conservativeResize(4, 3);
  scene.mass.reset();
  const auto s = make_system<MassSpringSystem<double, Sparse>>(scene);
  // fan (0, 1, 2), (0, 2, 3): two right triangles of area 1/2 with the right angles at 1 and 3:
  // 1/4 at each right angle, 1/8 at each of the others, which 0 and 2 get twice.
  CHECK(s.masses()(0) == doctest::Approx(0.25));
  CHECK(s.masses()(1) == doctest::Approx(0.25));
  CHECK(s.masses()(2) == doctest::Approx(0.25));
  CHECK(s.masses()(3) == doctest::Approx(0.25));
}

TEST_CASE("make_system refuses a scene it cannot give masses to, or an invalid pin") {
  auto edges_only = square_with_tail();
  edges_only.faces.clear();
  edges_only.mass.reset();
  CHECK_THROWS_WITH_AS(make_system<SparseSystem>(edges_only),
                       doctest::Contains("scene has no faces to take masses from"), Error);

  auto loose = square_with_tail();  // point 4 is on the tail only
  loose.mass.reset();
  CHECK_THROWS_WITH_AS(make_system<SparseSystem>(loose),
                       doctest::Contains("point 4 (OBJ vertex 5): lies on no face of nonzero area"),
                       Error);

  auto bad_pin = square_with_tail();
  bad_pin.pinned = {5};
  CHECK_THROWS_AS(make_system<SparseSystem>(bad_pin), Error);

  auto bad_face = square_with_tail();
  bad_face.faces = {{0, 1, 7}};
  CHECK_THROWS_WITH_AS(make_system<SparseSystem>(bad_face),
                       doctest::Contains("face 0: vertex index 7 out of range"), Error);

  auto negative = square_with_tail();
  negative.stiffness = -1;
  CHECK_THROWS_AS(make_system<SparseSystem>(negative), Error);
}
