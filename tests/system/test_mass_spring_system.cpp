// system/mass_spring_system.hpp: the matrices it builds and the input it refuses.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <massspring/contact/response/surface_contact.hpp>  // set_surface()
#include <massspring/system/mass_spring_system.hpp>

namespace {

using massspring::Dense;
using massspring::Edges;
using massspring::Error;
using massspring::MassSpringSystem;
using massspring::Sparse;

template <class Scalar>
using Points = massspring::Points<Scalar>;

// A triangle 0-1-2 and a tail 2-3.
template <class Scalar>
Points<Scalar> four_points() {
  Points<Scalar> v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 2;
  return v;
}
Edges four_springs() {
  Edges e(4, 2);
  e << 0, 1, 1, 2, 2, 0, 2, 3;
  return e;
}

template <class Matrix>
Eigen::MatrixXd to_dense(const Matrix& m) {
  if constexpr (std::is_base_of_v<Eigen::SparseMatrixBase<Matrix>, Matrix>)
    return Eigen::MatrixXd(m.template cast<double>());
  else
    return m.template cast<double>();
}

}  // namespace

#define MS_SYSTEM_TYPES                                              \
  MassSpringSystem<double, Sparse>, MassSpringSystem<double, Dense>, \
      MassSpringSystem<float, Sparse>, MassSpringSystem<float, Dense>

TEST_CASE_TEMPLATE("incidence rows are +1 at the first point and -1 at the second", System,
                   MS_SYSTEM_TYPES) {
  using Scalar = typename System::Scalar;
  const System s(four_points<Scalar>(), four_springs(), Scalar(1), Scalar(10));
  const Eigen::MatrixXd a = to_dense(s.incidence());
  Eigen::MatrixXd expected(4, 4);
  expected << 1, -1, 0, 0,  //
      0, 1, -1, 0,          //
      -1, 0, 1, 0,          //
      0, 0, 1, -1;
  CHECK(a == expected);
  // Every row sums to zero: A maps a rigid translation to zero spring vectors.
  CHECK(a.rowwise().sum().cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE_TEMPLATE("mass, stiffness and pin matrices", System, MS_SYSTEM_TYPES) {
  using Scalar = typename System::Scalar;
  massspring::Vector<Scalar> m(4), k(4);
  m << 1, 2, 3, 4;
  k << 10, 20, 30, 40;
  System s(four_points<Scalar>(), four_springs(), m, k);
  s.pin(3);
  s.pin(1);
  CHECK(to_dense(s.mass_matrix()) == Eigen::MatrixXd(m.template cast<double>().asDiagonal()));
  CHECK(to_dense(s.stiffness_matrix()) == Eigen::MatrixXd(k.template cast<double>().asDiagonal()));
  Eigen::MatrixXd c(2, 4);
  c << 0, 1, 0, 0, 0, 0, 0, 1;  // pinned points ascending: 1, 3
  CHECK(to_dense(s.pin_selector()) == c);
  // C X picks the pinned rows.
  const Eigen::MatrixXd cx = c * s.positions().template cast<double>();
  CHECK(cx.row(0) == s.positions().row(1).template cast<double>());
  CHECK(cx.row(1) == s.positions().row(3).template cast<double>());
}

TEST_CASE("rest lengths are the distances at rest; positions start at rest, velocities at zero") {
  const MassSpringSystem<double> s(four_points<double>(), four_springs(), 1.0, 1.0);
  CHECK(s.num_points() == 4);
  CHECK(s.num_springs() == 4);
  CHECK(s.rest_lengths()(0) == 1.0);
  CHECK(s.rest_lengths()(1) == doctest::Approx(std::sqrt(2.0)).epsilon(1e-15));
  CHECK(s.rest_lengths()(3) == 2.0);
  CHECK(s.positions() == s.rest_positions());
  CHECK(s.velocities().isZero(0));
  CHECK(s.damping().isZero(0));
}

TEST_CASE("revision changes with what Q is built from, and only with that") {
  MassSpringSystem<double> s(four_points<double>(), four_springs(), 1.0, 1.0);
  const auto r0 = s.revision();
  s.set_rest_lengths(Eigen::Vector4d(1, 1, 1, 1));
  s.set_positions(four_points<double>() * 2);
  s.set_velocities(Points<double>::Ones(4, 3));
  s.set_damping(Eigen::Vector4d(0.1, 0, 0, 0));
  CHECK(s.revision() == r0);
  s.pin(0);
  const auto r1 = s.revision();
  CHECK(r1 != r0);
  s.set_pin_target(0, Eigen::Vector3d(1, 2, 3));  // free
  s.pin(0, Eigen::Vector3d(0, 0, 1));             // moves the target of a pinned point: free
  CHECK(s.revision() == r1);
  CHECK(s.pin_targets().row(0) == Eigen::RowVector3d(0, 0, 1));
  s.set_masses(Eigen::Vector4d(1, 1, 1, 2));
  const auto r2 = s.revision();
  CHECK(r2 != r1);
  s.set_stiffness(Eigen::Vector4d(1, 1, 1, 2));
  const auto r3 = s.revision();
  CHECK(r3 != r2);
  s.unpin(2);  // not pinned: nothing changes
  CHECK(s.revision() == r3);
  s.unpin(0);
  CHECK(s.revision() != r3);
  CHECK(s.num_pinned() == 0);
  // Two systems never share a revision unless one is a copy of the other.
  const MassSpringSystem<double> t(four_points<double>(), four_springs(), 1.0, 1.0);
  CHECK(t.revision() != s.revision());
  const MassSpringSystem<double> u = t;
  CHECK(u.revision() == t.revision());
}

TEST_CASE("pins are kept sorted with their targets") {
  MassSpringSystem<double> s(four_points<double>(), four_springs(), 1.0, 1.0);
  s.pin(2, Eigen::Vector3d(2, 2, 2));
  s.pin(0, Eigen::Vector3d(0, 0, 0));
  s.pin(3);  // at its rest position
  REQUIRE(s.pinned() == std::vector<int>{0, 2, 3});
  CHECK(s.pin_targets().row(0) == Eigen::RowVector3d(0, 0, 0));
  CHECK(s.pin_targets().row(1) == Eigen::RowVector3d(2, 2, 2));
  CHECK(s.pin_targets().row(2) == s.rest_positions().row(3));
  CHECK(s.is_pinned(2));
  CHECK_FALSE(s.is_pinned(1));
  s.unpin(2);
  REQUIRE(s.pinned() == std::vector<int>{0, 3});
  CHECK(s.pin_targets().row(1) == s.rest_positions().row(3));
}

TEST_CASE("inverse masses are 1 / m, and 0 at the pinned points, through every change") {
  MassSpringSystem<double> s(four_points<double>(), four_springs(), 1.0, 1.0);
  const auto expect = [&](const std::vector<double>& w) {
    REQUIRE(s.inverse_masses().size() == 4);
    for (int i = 0; i < 4; ++i) CHECK(s.inverse_masses()(i) == w[std::size_t(i)]);
  };
  expect({1, 1, 1, 1});  // 1 kg each
  s.set_masses(Eigen::Vector4d(1, 2, 4, 0.5));
  expect({1, 0.5, 0.25, 2});
  s.pin(2);
  s.pin(0, Eigen::Vector3d(1, 1, 1));
  expect({0, 0.5, 0, 2});
  s.set_pin_target(0, Eigen::Vector3d(0, 1, 1));  // a target moved: nothing else
  expect({0, 0.5, 0, 2});
  s.unpin(2);
  expect({0, 0.5, 0.25, 2});
  s.set_masses(Eigen::Vector4d(2, 2, 2, 2));  // a pinned point stays immobile
  expect({0, 0.5, 0.5, 0.5});
  const MassSpringSystem<double> copy = s;
  CHECK(copy.inverse_masses() == s.inverse_masses());
}

TEST_CASE("invalid input raises massspring::Error naming the item, and changes nothing") {
  const auto v = four_points<double>();
  const auto e = four_springs();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  using System = MassSpringSystem<double>;

  SUBCASE("spring index out of range") {
    Edges bad = e;
    bad(2, 1) = 4;
    CHECK_THROWS_WITH_AS(System(v, bad, 1.0, 1.0),
                         "spring 2 = (2, 4): point index 4 out of range [0, 4)", Error);
    bad(2, 1) = -1;
    CHECK_THROWS_WITH_AS(System(v, bad, 1.0, 1.0), doctest::Contains("point index -1"), Error);
  }
  SUBCASE("spring from a point to itself") {
    Edges bad = e;
    bad(3, 0) = 3;
    CHECK_THROWS_WITH_AS(System(v, bad, 1.0, 1.0), "spring 3 connects point 3 to itself", Error);
  }
  SUBCASE("duplicate spring, either orientation") {
    Edges bad(5, 2);
    bad << e, 1, 0;
    CHECK_THROWS_WITH_AS(System(v, bad, 1.0, 1.0),
                         "spring 4 duplicates spring 0: both join points 0 and 1", Error);
  }
  SUBCASE("non-finite coordinate") {
    Points<double> bad = v;
    bad(2, 1) = nan;
    CHECK_THROWS_WITH_AS(System(bad, e, 1.0, 1.0),
                         doctest::Contains("point 2: rest position must be finite"), Error);
    bad(2, 1) = inf;
    CHECK_THROWS_WITH_AS(System(bad, e, 1.0, 1.0), doctest::Contains("point 2"), Error);
  }
  SUBCASE("mass <= 0 or not finite") {
    CHECK_THROWS_WITH_AS(System(v, e, 0.0, 1.0), "point 0: mass must be finite and > 0, got 0",
                         Error);
    CHECK_THROWS_WITH_AS(System(v, e, Eigen::Vector4d(1, 1, -2, 1), Eigen::Vector4d::Ones()),
                         "point 2: mass must be finite and > 0, got -2", Error);
    CHECK_THROWS_WITH_AS(System(v, e, Eigen::Vector4d(1, nan, 1, 1), Eigen::Vector4d::Ones()),
                         doctest::Contains("point 1: mass"), Error);
  }
  SUBCASE("stiffness < 0 or not finite") {
    CHECK_THROWS_WITH_AS(System(v, e, 1.0, -1.0),
                         "spring 0: stiffness must be finite and >= 0, got -1", Error);
    CHECK_THROWS_WITH_AS(System(v, e, Eigen::Vector4d::Ones(), Eigen::Vector4d(1, 1, 1, inf)),
                         doctest::Contains("spring 3: stiffness"), Error);
  }
  SUBCASE("wrong sizes") {
    CHECK_THROWS_WITH_AS(System(v, e, Eigen::Vector3d::Ones(), Eigen::Vector4d::Ones()),
                         "masses: expected one value per point (4), got 3", Error);
    const Eigen::MatrixXd two_columns = Eigen::MatrixXd::Zero(4, 2);
    CHECK_THROWS_WITH_AS(System(two_columns, e, 1.0, 1.0),
                         "rest positions: expected #points by 3, got 4 by 2", Error);
  }
  SUBCASE("setters refuse and leave the system as it was") {
    System s(v, e, 1.0, 1.0);
    const auto revision = s.revision();
    CHECK_THROWS_WITH_AS(s.set_masses(Eigen::Vector4d(1, 1, 1, 0)), doctest::Contains("point 3"),
                         Error);
    CHECK_THROWS_WITH_AS(s.set_stiffness(Eigen::Vector4d(1, -1, 1, 1)),
                         doctest::Contains("spring 1"), Error);
    CHECK_THROWS_WITH_AS(s.set_rest_lengths(Eigen::Vector4d(1, 1, nan, 1)),
                         doctest::Contains("spring 2: rest length"), Error);
    CHECK_THROWS_WITH_AS(s.set_damping(Eigen::Vector4d(-1, 1, 1, 1)),
                         doctest::Contains("spring 0: damping"), Error);
    Points<double> p = v;
    p(1, 0) = inf;
    CHECK_THROWS_WITH_AS(s.set_positions(p), doctest::Contains("point 1: positions"), Error);
    CHECK_THROWS_WITH_AS(s.set_velocities(Points<double>::Zero(3, 3)),
                         "velocities: expected 4 by 3, got 3 by 3", Error);
    CHECK_THROWS_WITH_AS(s.pin(7), "pin: point index 7 out of range [0, 4)", Error);
    CHECK_THROWS_WITH_AS(s.pin(std::vector<int>{0, 9}), doctest::Contains("point index 9"), Error);
    CHECK_THROWS_WITH_AS(s.pin(1, Eigen::Vector3d(0, nan, 0)),
                         doctest::Contains("pin 1: target must be finite"), Error);
    CHECK_THROWS_WITH_AS(s.set_pin_target(1, Eigen::Vector3d::Zero()),
                         "pin target: point 1 is not pinned", Error);
    CHECK_THROWS_WITH_AS(s.unpin(-1), doctest::Contains("out of range"), Error);
    CHECK(s.revision() == revision);
    CHECK(s.num_pinned() == 0);
    CHECK(s.masses() == Eigen::Vector4d::Ones());
    CHECK(s.stiffness() == Eigen::Vector4d::Ones());
    CHECK(s.positions() == v);
  }
}

TEST_CASE("a zero-length spring at rest is allowed") {
  Points<double> v(2, 3);
  v << 1, 2, 3, 1, 2, 3;
  Edges e(1, 2);
  e << 0, 1;
  const MassSpringSystem<double> s(v, e, 1.0, 5.0);
  CHECK(s.rest_lengths()(0) == 0.0);
}

TEST_CASE("an empty system is valid") {
  const MassSpringSystem<double, Dense> s;
  CHECK(s.num_points() == 0);
  CHECK(s.num_springs() == 0);
  CHECK(s.incidence().size() == 0);
}

namespace {

// A 3 x 3 grid of points in the x-y plane (point (r, c) = 3 r + c at (c, r, 0)): 2 x 2 cells,
// each split into triangles (a, b, c), (a, c, d) along its diagonal a-c.
Points<double> grid_points() {
  Points<double> v(9, 3);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v.row(3 * r + c) << c, r, 0;
  return v;
}
massspring::Triangles grid_triangles() {
  massspring::Triangles t(8, 3);
  int k = 0;
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 2; ++c) {
      const int a = 3 * r + c, b = a + 1, cc = a + 4, d = a + 3;
      t.row(k++) << a, b, cc;
      t.row(k++) << a, cc, d;
    }
  return t;
}
Edges grid_structural_springs() {
  Edges e(12, 2);
  int k = 0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c + 1 < 3; ++c) e.row(k++) << 3 * r + c, 3 * r + c + 1;
  for (int r = 0; r + 1 < 3; ++r)
    for (int c = 0; c < 3; ++c) e.row(k++) << 3 * r + c, 3 * r + c + 3;
  return e;
}

}  // namespace

TEST_CASE_TEMPLATE("set_surface: the triangles, and their edges each once, ascending", System,
                   MS_SYSTEM_TYPES) {
  using Scalar = typename System::Scalar;
  System s(grid_points().cast<Scalar>(), grid_structural_springs(), Scalar(1), Scalar(10));
  CHECK(s.surface().rows() == 0);
  CHECK(s.surface_edges().rows() == 0);
  const auto revision = s.revision();
  s.set_surface(grid_triangles());
  CHECK(s.surface() == grid_triangles());
  CHECK(s.revision() == revision);  // not a model change
  // 12 sides of the cells and the 4 diagonals a-c, each once.
  Edges expected(16, 2);
  expected << 0, 1, 0, 3, 0, 4, 1, 2, 1, 4, 1, 5, 2, 5, 3, 4, 3, 6, 3, 7, 4, 5, 4, 7, 4, 8, 5, 8, 6,
      7, 7, 8;
  CHECK(s.surface_edges() == expected);
  // An empty matrix removes it.
  s.set_surface(massspring::Triangles(0, 3));
  CHECK(s.surface().rows() == 0);
  CHECK(s.surface_edges().rows() == 0);
}

TEST_CASE("set_surface refuses a bad triangle, naming it, and changes nothing") {
  MassSpringSystem<double> s(grid_points(), grid_structural_springs(), 1.0, 10.0);
  s.set_surface(grid_triangles());
  massspring::Triangles bad = grid_triangles();
  SUBCASE("an index out of range") {
    bad(5, 2) = 9;
    CHECK_THROWS_WITH_AS(s.set_surface(bad),
                         "surface triangle 5 = (3, 7, 9): point index 9 out of range [0, 9)",
                         Error);
    bad(5, 2) = -1;
    CHECK_THROWS_WITH_AS(s.set_surface(bad), doctest::Contains("surface triangle 5 = (3, 7, -1)"),
                         Error);
  }
  SUBCASE("a point repeated") {
    bad(3, 1) = 1;
    CHECK_THROWS_WITH_AS(s.set_surface(bad), "surface triangle 3 = (1, 1, 4): repeats a point",
                         Error);
  }
  SUBCASE("zero area: three points on a line") {
    bad.row(6) << 3, 4, 5;
    CHECK_THROWS_WITH_AS(s.set_surface(bad),
                         "surface triangle 6 = (3, 4, 5): zero area at the rest positions", Error);
  }
  SUBCASE("zero area: two points at one place") {
    Points<double> v = grid_points();
    v.row(8) = v.row(4);
    MassSpringSystem<double> t(v, grid_structural_springs(), 1.0, 10.0);
    CHECK_THROWS_WITH_AS(t.set_surface(grid_triangles()),
                         "surface triangle 6 = (4, 5, 8): zero area at the rest positions", Error);
    CHECK(t.surface().rows() == 0);
  }
  CHECK(s.surface() == grid_triangles());
  CHECK(s.surface_edges().rows() == 16);
}

TEST_CASE_TEMPLATE("set_self_collision needs a surface and parameters in range", System,
                   MS_SYSTEM_TYPES) {
  using Scalar = typename System::Scalar;
  using Parameters = massspring::contact::SelfCollision<Scalar>;
  System s(grid_points().cast<Scalar>(), grid_structural_springs(), Scalar(1), Scalar(10));
  CHECK_FALSE(s.self_collision().has_value());
  CHECK_FALSE(s.has_collision_response());
  CHECK_THROWS_WITH_AS(s.set_self_collision(Parameters{}),
                       doctest::Contains("self-collision: the system has no surface"), Error);
  CHECK_FALSE(s.self_collision().has_value());

  s.set_surface(grid_triangles());
  const auto refused = [&](Scalar thickness, Scalar friction, const char* message) {
    Parameters p;
    p.thickness = thickness;
    p.friction = friction;
    CHECK_THROWS_WITH_AS(s.set_self_collision(p), doctest::Contains(message), Error);
    CHECK_FALSE(s.self_collision().has_value());
  };
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  refused(0, Scalar(0.2), "self-collision: thickness must be finite and > 0, got 0");
  refused(Scalar(-0.001), Scalar(0.2), "self-collision: thickness must be finite and > 0");
  refused(nan, Scalar(0.2), "self-collision: thickness must be finite and > 0, got nan");
  refused(std::numeric_limits<Scalar>::infinity(), Scalar(0.2), "thickness must be finite");
  refused(Scalar(0.004), Scalar(-0.1), "self-collision: friction must be finite and >= 0");
  refused(Scalar(0.004), nan, "self-collision: friction must be finite and >= 0, got nan");

  const Parameters defaults;
  CHECK(defaults.thickness == Scalar(0.004));
  CHECK(defaults.friction == Scalar(0.2));
  Parameters p;
  p.thickness = Scalar(0.01);
  p.friction = 0;  // frictionless is allowed
  s.set_self_collision(p);
  REQUIRE(s.self_collision().has_value());
  CHECK(s.self_collision()->thickness == Scalar(0.01));
  CHECK(s.self_collision()->friction == Scalar(0));
  CHECK(s.has_collision_response());
  s.clear_self_collision();
  CHECK_FALSE(s.self_collision().has_value());
  CHECK_FALSE(s.has_collision_response());
}
