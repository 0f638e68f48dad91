// scene/voronoi_masses.hpp: lumped mixed-Voronoi areas (Meyer et al. 2003), checked against closed
// forms, an independent circumcentre construction, the surface area, and SOURCE.md's totals.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <massspring/scene/voronoi_masses.hpp>
#include <random>
#include <vector>

#include "massspring/io/obj.hpp"
#include "support/paths.hpp"

namespace {

using massspring::Error;
using massspring::voronoi_masses;

template <class Scalar>
using Points = massspring::Points<Scalar>;

template <class Scalar>
doctest::Approx near(Scalar x) {
  return doctest::Approx(double(x)).epsilon(std::is_same_v<Scalar, float> ? 1e-5 : 1e-12);
}

// Area of the fan triangulation (f0, fi, fi+1) of each polygon, from cross products.
double fan_area(const Points<double>& v, const std::vector<std::vector<int>>& faces) {
  double area = 0;
  for (const auto& f : faces)
    for (std::size_t t = 1; t + 1 < f.size(); ++t) {
      const Eigen::Vector3d a = v.row(f[t]) - v.row(f[0]), b = v.row(f[t + 1]) - v.row(f[0]);
      area += a.cross(b).norm() / 2;
    }
  return area;
}

// Voronoi area of corner p of a non-obtuse triangle (p, q, r): the quadrilateral p, mid(p, q),
// circumcentre, mid(p, r).
double voronoi_corner(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                      const Eigen::Vector3d& r) {
  const Eigen::Vector3d a = q - p, b = r - p, n = a.cross(b);
  const Eigen::Vector3d o =
      p + (a.squaredNorm() * b.cross(n) + b.squaredNorm() * n.cross(a)) / (2 * n.squaredNorm());
  const Eigen::Vector3d mq = (p + q) / 2, mr = (p + r) / 2;
  return ((mq - p).cross(o - p).norm() + (o - p).cross(mr - p).norm()) / 2;
}

}  // namespace

TEST_CASE_TEMPLATE("voronoi_masses: an equilateral triangle gives each corner a third", Scalar,
                   float, double) {
  Points<Scalar> v(3, 3);
  v << 0, 0, 0, 2, 0, 0, 1, Scalar(std::sqrt(3.0)), 0;
  const auto m = voronoi_masses(v, {{0, 1, 2}});
  const Scalar area = Scalar(std::sqrt(3.0));
  for (int i = 0; i < 3; ++i) CHECK(m(i) == near(area / 3));
}

TEST_CASE_TEMPLATE(
    "voronoi_masses: a right isosceles triangle gives 1/4 at the right angle, 1/8 at "
    "the others",
    Scalar, float, double) {
  Points<Scalar> v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0;  // area 1/2
  const auto m = voronoi_masses(v, {{1, 0, 2}});
  CHECK(m(0) == near(Scalar(0.25)));
  CHECK(m(1) == near(Scalar(0.125)));
  CHECK(m(2) == near(Scalar(0.125)));
}

TEST_CASE_TEMPLATE(
    "voronoi_masses: an obtuse triangle gives 1/2 of its area to the obtuse corner "
    "and 1/4 to each other",
    Scalar, float, double) {
  Points<Scalar> v(3, 3);
  v << 0, 0, 0, 4, 0, 0, 2, 1, 0;  // obtuse at vertex 2 (5 + 5 < 16), area 2
  const auto m = voronoi_masses(v, {{0, 1, 2}});
  CHECK(m(2) == near(Scalar(1)));
  CHECK(m(0) == near(Scalar(0.5)));
  CHECK(m(1) == near(Scalar(0.5)));
}

TEST_CASE("voronoi_masses: acute triangles match the circumcentre construction") {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  while (tested < 200) {
    Points<double> v(3, 3);
    for (int i = 0; i < 3; ++i) v.row(i) << u(random), u(random), u(random);
    const Eigen::Vector3d p = v.row(0), q = v.row(1), r = v.row(2);
    const double a2 = (q - r).squaredNorm(), b2 = (p - r).squaredNorm(), c2 = (p - q).squaredNorm();
    if (a2 >= b2 + c2 || b2 >= a2 + c2 || c2 >= a2 + b2) continue;  // not acute
    ++tested;
    const auto m = voronoi_masses(v, {{0, 1, 2}});
    CHECK(m(0) == doctest::Approx(voronoi_corner(p, q, r)).epsilon(1e-9));
    CHECK(m(1) == doctest::Approx(voronoi_corner(q, r, p)).epsilon(1e-9));
    CHECK(m(2) == doctest::Approx(voronoi_corner(r, p, q)).epsilon(1e-9));
  }
}

TEST_CASE("voronoi_masses: the total is the surface area of a curved mesh of mixed polygons") {
  // a bumpy 7 x 6 grid; cells alternate quads, triangle pairs and, per row, one pentagon
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  const int cols = 7, rows = 6;
  Points<double> v(cols * rows, 3);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      v.row(r * cols + c) << c + u(random), std::sin(c) * std::cos(r) + u(random), r + u(random);
  std::vector<std::vector<int>> faces;
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c) {
      const int a = r * cols + c, b = a + 1, d = a + cols, e = d + 1;
      if ((r + c) % 2)
        faces.push_back({a, b, e, d});
      else {
        faces.push_back({a, b, e});
        faces.push_back({a, e, d});
      }
    }
  faces.push_back({0, 1, 2, 3, 3 + cols});  // a pentagon over cells of row 0 (overlap is fine)
  const auto m = voronoi_masses(v, faces);
  CHECK(m.sum() == doctest::Approx(fan_area(v, faces)).epsilon(1e-12));
  CHECK((m.array() > 0).all());
}

TEST_CASE("voronoi_masses: scaling lengths by 2 scales every mass by 4; untouched vertices get 0") {
  Points<double> v(5, 3);
  v << 0, 0, 0, 1, 0.1, 0, 1.2, 1, 0.3, -0.1, 0.9, 0, 9, 9, 9;
  const std::vector<std::vector<int>> faces = {{0, 1, 2, 3}};
  const auto m = voronoi_masses(v, faces);
  const Points<double> w = 2 * v;
  const auto m2 = voronoi_masses(w, faces);
  for (int i = 0; i < 5; ++i) CHECK(m2(i) == doctest::Approx(4 * m(i)).epsilon(1e-14));
  CHECK(m(4) == 0);
}

TEST_CASE("voronoi_masses: a degenerate triangle adds nothing") {
  Points<double> v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 2, 0, 0;
  CHECK(voronoi_masses(v, {{0, 1, 2}}).isZero(0));
}

TEST_CASE("voronoi_masses refuses faces of fewer than 3 vertices and indices out of range") {
  Points<double> v = Points<double>::Zero(3, 3);
  CHECK_THROWS_WITH_AS(voronoi_masses(v, {{0, 1, 2}, {0, 1}}),
                       doctest::Contains("face 1: a polygon needs 3 or more vertices, got 2"),
                       Error);
  CHECK_THROWS_WITH_AS(voronoi_masses(v, {{0, 1, 3}}),
                       doctest::Contains("face 0: vertex index 3 out of range [0, 3)"), Error);
}

TEST_CASE("voronoi_masses of the JSON+OBJ scenes' flag and skirt: SOURCE.md's totals and ranges" *
          doctest::skip(!massspring::test::have_jacobson())) {
  struct Expected {
    const char* file;
    double total, min, max;  // min and max to 3 significant digits
  };
  for (const Expected& e : {Expected{"flag.obj", 2.0000000000000009, 1.62e-4, 6.49e-4},
                            Expected{"skirt.obj", 5.0259740751116446, 1.00e-4, 8.34e-4}}) {
    CAPTURE(e.file);
    const auto mesh = massspring::io::read_obj(massspring::test::jacobson_dir() / e.file);
    const auto m = voronoi_masses(mesh.vertices, mesh.faces);
    CHECK(m.sum() == doctest::Approx(e.total).epsilon(1e-12));
    CHECK(m.sum() == doctest::Approx(fan_area(mesh.vertices, mesh.faces)).epsilon(1e-12));
    CHECK(std::abs(m.minCoeff() - e.min) <= 0.005 * std::pow(10.0, std::floor(std::log10(e.min))));
    CHECK(std::abs(m.maxCoeff() - e.max) <= 0.005 * std::pow(10.0, std::floor(std::log10(e.max))));
  }
}
