// contact/distance/point_point.hpp, point_segment.hpp, point_plane.hpp: closest points, normals and
// distances against closed forms, in 3D and in the plane z = 0.
#include <doctest/doctest.h>

#include <cmath>
#include <massspring/contact/distance/point_plane.hpp>
#include <massspring/contact/distance/point_point.hpp>
#include <massspring/contact/distance/point_segment.hpp>

#include "contact/support.hpp"

using massspring::test::v3;
using massspring::test::V3;
namespace contact = massspring::contact;

TEST_CASE("point_point_distance: n = q - p, its length and unit normal") {
  const auto d = contact::point_point_distance<double>(v3(1, 2, 3), v3(4, 6, 3));
  CHECK(d.n.isApprox(v3(3, 4, 0)));
  CHECK(d.distance == doctest::Approx(5));
  CHECK(d.normal().isApprox(v3(0.6, 0.8, 0)));
  CHECK(contact::point_point_distance<double>(v3(1, 1, 1), v3(1, 1, 1)).normal().isZero());
}

TEST_CASE("point_segment_distance: interior foot, clamped ends, degenerate segment") {
  // segment from (0,0,0) to (2,0,0): foot of (0.5, 1, 1) is (0.5, 0, 0), alpha 1/4
  auto d = contact::point_segment_distance<double>(v3(0.5, 1, 1), v3(0, 0, 0), v3(2, 0, 0));
  CHECK(d.alpha == doctest::Approx(0.25));
  CHECK(d.closest.isApprox(v3(0.5, 0, 0)));
  CHECK(d.distance == doctest::Approx(std::sqrt(2.0)));
  CHECK(d.normal().isApprox(v3(0, -1, -1) / std::sqrt(2.0)));
  // beyond the end b: alpha clamps to 1, closest is b
  d = contact::point_segment_distance<double>(v3(5, 4, 0), v3(0, 0, 0), v3(2, 0, 0));
  CHECK(d.alpha == 1);
  CHECK(d.distance == doctest::Approx(5));
  // before a: alpha 0
  d = contact::point_segment_distance<double>(v3(-3, 4, 0), v3(0, 0, 0), v3(2, 0, 0));
  CHECK(d.alpha == 0);
  CHECK(d.distance == doctest::Approx(5));
  // a = b: the distance to the point
  d = contact::point_segment_distance<double>(v3(0, 3, 4), v3(0, 0, 0), v3(0, 0, 0));
  CHECK(d.alpha == 0);
  CHECK(d.distance == doctest::Approx(5));
}

TEST_CASE("point_plane_distance: a normal of any length; unsigned and signed distances") {
  // the line y = x through the origin, normal (1, -1) scaled by 3
  contact::Plane<double> plane{v3(0, 0), v3(3, -3)};
  const auto d = contact::point_plane_distance<double>(v3(2, 0), plane);
  CHECK(d.distance == doctest::Approx(std::sqrt(2.0)));
  CHECK(d.signed_distance == doctest::Approx(std::sqrt(2.0)));  // on the normal's side
  CHECK(d.closest.isApprox(v3(1, 1)));
  CHECK(d.normal().isApprox(v3(-1, 1) / std::sqrt(2.0)));  // from the point towards the plane
  const auto e = contact::point_plane_distance<double>(v3(0, 2), plane);
  CHECK(e.signed_distance == doctest::Approx(-std::sqrt(2.0)));
  CHECK(e.distance == doctest::Approx(std::sqrt(2.0)));
}
