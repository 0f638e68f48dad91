// scene/make_system.hpp: a SceneDescription becomes the system it describes.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <massspring/scene/chain.hpp>
#include <massspring/scene/cloth.hpp>
#include <massspring/scene/make_system.hpp>
#include <massspring/scene/net.hpp>
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
                       doctest::Contains("point 4: lies on no face of nonzero area"), Error);
  // read from a file (MeshSource): named by the file, the vertex's line and its 1-based index
  loose.source.file = "tail.obj";
  loose.source.vertex_lines = {2, 3, 4, 5, 9};
  CHECK_THROWS_WITH_AS(make_system<SparseSystem>(loose),
                       "tail.obj:9: vertex 5: lies on no face of nonzero area, so its Voronoi mass "
                       "is 0; give a mass (\"m\")",
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

TEST_CASE_TEMPLATE("make_system: the faces split into fans are the surface", System,
                   MassSpringSystem<double, Dense>, MassSpringSystem<double, Sparse>,
                   MassSpringSystem<float, Dense>, MassSpringSystem<float, Sparse>) {
  // The quad (0, 1, 2, 3) gives (0, 1, 2), (0, 2, 3); the tail 2-4 is a spring, not surface.
  const System s = make_system<System>(square_with_tail());
  massspring::Triangles expected(2, 3);
  expected << 0, 1, 2, 0, 2, 3;
  CHECK(s.surface() == expected);
  massspring::Edges edges(5, 2);
  edges << 0, 1, 0, 2, 0, 3, 1, 2, 2, 3;
  CHECK(s.surface_edges() == edges);
  CHECK_FALSE(s.self_collision().has_value());

  // A pentagon (0, 1, 2, 3, 4): three triangles, all from vertex 0.
  SceneDescription<double> pentagon;
  pentagon.vertices.resize(5, 3);
  pentagon.vertices << 1, 0, 0, 0.3, 0.95, 0, -0.8, 0.6, 0, -0.8, -0.6, 0, 0.3, -0.95, 0;
  pentagon.faces = {{0, 1, 2, 3, 4}};
  pentagon.stiffness = 1;
  massspring::Triangles fan(3, 3);
  fan << 0, 1, 2, 0, 2, 3, 0, 3, 4;
  CHECK(make_system<System>(pentagon).surface() == fan);
  CHECK(massspring::fan_triangles(pentagon.faces) == fan);
}

TEST_CASE("make_system: a generated cloth has 2 surface triangles per cell; chains and nets none") {
  massspring::ClothOptions o;
  o.columns = 6;
  o.rows = 4;
  for (const auto shear : {massspring::ClothShear::Both, massspring::ClothShear::One}) {
    CAPTURE(int(shear));
    o.shear = shear;
    const auto s = make_system<SparseSystem>(massspring::make_cloth(o));
    const int cells = (o.columns - 1) * (o.rows - 1);
    CHECK(s.surface().rows() == 2 * cells);
    // Every side of a cell once, and one diagonal per cell.
    const int sides = o.rows * (o.columns - 1) + (o.rows - 1) * o.columns;
    CHECK(s.surface_edges().rows() == sides + cells);
    // Cell (0, 0): points 0, 1, 7, 6.
    CHECK(s.surface()(0, 0) == 0);
    CHECK(s.surface()(0, 1) == 1);
    CHECK(s.surface()(0, 2) == o.columns + 1);
  }
  o.shear = massspring::ClothShear::None;  // no faces: no surface
  CHECK(make_system<SparseSystem>(massspring::make_cloth(o)).surface().rows() == 0);
  CHECK(make_system<SparseSystem>(massspring::make_chain({})).surface().rows() == 0);
  CHECK(make_system<SparseSystem>(massspring::make_net({})).surface().rows() == 0);
}

TEST_CASE("make_system refuses a face of zero area or with a repeated vertex, naming the face") {
  auto collinear = square_with_tail();
  collinear.vertices.row(2) << 2, 0, 0;  // 0, 1, 2 on a line: the fan's first triangle is flat
  collinear.vertices.row(3) << 0, 1, 0;
  CHECK_THROWS_WITH_AS(
      make_system<SparseSystem>(collinear),
      "face 0 (0, 1, 2, 3): surface triangle 0 = (0, 1, 2): zero area at the rest positions",
      Error);

  auto second = square_with_tail();
  second.faces = {{0, 1, 2}, {2, 3, 4}};
  second.vertices.row(4) << -1, 1, 0;  // on the line through 2 and 3
  CHECK_THROWS_WITH_AS(
      make_system<SparseSystem>(second),
      "face 1 (2, 3, 4): surface triangle 1 = (2, 3, 4): zero area at the rest positions", Error);

  // read from a file (MeshSource): the face's line and the file's 1-based indices
  collinear.source.file = "square.obj";
  collinear.source.face_lines = {7};
  CHECK_THROWS_WITH_AS(make_system<SparseSystem>(collinear),
                       "square.obj:7: face (1, 2, 3, 4): fan triangle (1, 2, 3): zero area at the "
                       "rest positions",
                       Error);
  second.source.file = "two.obj";
  second.source.face_lines = {7, 8};
  CHECK_THROWS_WITH_AS(make_system<SparseSystem>(second),
                       "two.obj:8: face (3, 4, 5): zero area at the rest positions", Error);
  second.source.face_lines = {7};  // lines that do not match the faces are not used
  CHECK_THROWS_WITH_AS(
      make_system<SparseSystem>(second),
      "face 1 (2, 3, 4): surface triangle 1 = (2, 3, 4): zero area at the rest positions", Error);

  auto repeated = square_with_tail();
  repeated.faces = {{0, 1, 2, 1}};
  CHECK_THROWS_WITH_AS(make_system<SparseSystem>(repeated), "face 0: vertex 1 appears twice",
                       Error);
}

TEST_CASE_TEMPLATE("make_system applies the scene's self-collision after the surface", System,
                   MassSpringSystem<double, Sparse>, MassSpringSystem<float, Dense>) {
  using Scalar = typename System::Scalar;
  auto scene = square_with_tail();
  scene.self_collision = massspring::contact::SelfCollision<double>{0.01, 0.5};
  const System s = make_system<System>(scene);
  REQUIRE(s.self_collision().has_value());
  CHECK(s.self_collision()->thickness == Scalar(0.01));
  CHECK(s.self_collision()->friction == Scalar(0.5));

  auto no_faces = massspring::make_chain({});
  no_faces.self_collision = massspring::contact::SelfCollision<double>{};
  CHECK_THROWS_WITH_AS(make_system<System>(no_faces),
                       doctest::Contains("self_collision: the scene has no faces"), Error);

  scene.self_collision->thickness = 0;
  CHECK_THROWS_WITH_AS(make_system<System>(scene),
                       "self-collision: thickness must be finite and > 0, got 0", Error);
  scene.self_collision->thickness = 1e-60;  // > 0 in double, 0 in float
  if (std::is_same_v<Scalar, float>)
    CHECK_THROWS_WITH_AS(make_system<System>(scene), doctest::Contains("thickness"), Error);
  scene.self_collision->thickness = 0.004;
  scene.self_collision->friction = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(make_system<System>(scene), doctest::Contains("friction must be finite"),
                       Error);
}
