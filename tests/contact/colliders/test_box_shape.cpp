// contact/colliders/box_shape.hpp: Collider::push_off_edges() of a box, in closed form, and the
// guarantee detail::edge_distances() relies on, checked apart from the code: for points outside a
// box and at least rho = L / sqrt(2) from its edges and corners (a brute-force distance to the
// twelve edges; tests/support/box_checks.hpp), no segment of length <= L crosses the box (a slab
// test) and no triangle with edges <= L is pierced by a box edge (a segment-triangle test); with a
// smaller rho the same sampling finds both, so the check is not vacuous.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <massspring/contact/colliders/box_shape.hpp>
#include <massspring/contact/colliders/collider.hpp>
#include <random>

#include "support/box_checks.hpp"

namespace box_shape_test {

using V3 = Eigen::Vector3d;
using Collider = massspring::contact::Collider<double>;

const V3 kHalf(1.0, 0.5, 2.0);

// The distance from p to the nearest of the twelve edges of the box [-h, h], by brute force over
// the edges as segments.
double distance_to_edges(const V3& p, const V3& h) {
  double best = 1e300;
  for (const auto& [e0, e1] : massspring::test::box_edges(h)) {
    const V3 d = e1 - e0;
    const double t = std::clamp((p - e0).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (e0 + t * d)).norm());
  }
  return best;
}

// Collider::push_off_edges() without its push, from a step's start far from the box (its whole
// band applies) or from `start`.
bool push_off(const Collider& c, V3& p, double rho, const V3& start = V3(100, 100, 100)) {
  massspring::contact::ColliderContact<double> push;
  return c.push_off_edges(p, start, rho, push);
}

bool inside_closed_box(const V3& p, const V3& h) { return (p.cwiseAbs() - h).maxCoeff() <= 0; }

// Whether the segment p-q crosses the triangle (a, b, c) (Moller and Trumbore 1997).
bool segment_crosses_triangle(const V3& p, const V3& q, const V3& a, const V3& b, const V3& c) {
  const V3 d = q - p, e1 = b - a, e2 = c - a, s = d.cross(e2);
  const double det = e1.dot(s);
  if (std::abs(det) < 1e-14) return false;
  const V3 w = p - a;
  const double u = w.dot(s) / det;
  if (u < 0 || u > 1) return false;
  const V3 r = w.cross(e1);
  const double v = d.dot(r) / det, t = e2.dot(r) / det;
  return v >= 0 && u + v <= 1 && t >= 0 && t <= 1;
}

// Samples segments (and triangles) of edges <= L near the corner (h) and the edge through it
// along x, with every end outside the box and >= rho from its edges; counts those that meet the
// box (segments) or are pierced by a box edge (triangles).
struct Sampled {
  int segments = 0, segments_crossing = 0, triangles = 0, triangles_pierced = 0;
};
Sampled sample(double L, double rho, int tries) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  const auto ok = [&](const V3& p) {
    return !inside_closed_box(p, kHalf) && distance_to_edges(p, kHalf) >= rho;
  };
  const auto random_direction = [&] {
    V3 d;
    do d = V3(unit(rng), unit(rng), unit(rng));
    while (d.squaredNorm() > 1 || d.squaredNorm() < 1e-6);
    return V3(d.normalized());
  };
  const auto edges = massspring::test::box_edges(kHalf);
  Sampled s;
  for (int k = 0; k < tries; ++k) {
    // Around the corner, or along the edge through it.
    const V3 centre = k % 2 ? kHalf : V3(0.3, kHalf.y(), kHalf.z());
    const V3 a = centre + V3(unit(rng), unit(rng), unit(rng)) * L;
    if (!ok(a)) continue;
    const V3 b = a + random_direction() * (L * (0.5 + 0.5 * std::abs(unit(rng))));
    if (!ok(b)) continue;
    ++s.segments;
    s.segments_crossing += massspring::test::segment_meets_box(a, b, V3::Zero(), kHalf);
    const V3 c = a + random_direction() * (L * std::abs(unit(rng)));
    if (!ok(c) || (c - b).norm() > L) continue;
    ++s.triangles;
    bool pierced = false;
    for (const auto& e : edges) pierced = pierced || segment_crosses_triangle(e[0], e[1], a, b, c);
    s.triangles_pierced += pierced;
  }
  return s;
}

}  // namespace box_shape_test

using namespace box_shape_test;

TEST_CASE("push_off_edges: a point beside an edge or a corner, or over a face by the rim") {
  const Collider box = Collider::box(V3::Zero(), kHalf);
  const double rho = 0.05;
  // Near the edge y = 0.5, z = 2: nearest edge point (0.3, 0.5, 2), moved out radially.
  V3 p(0.3, 0.51, 2.01);
  REQUIRE(push_off(box, p, rho));
  CHECK((p - (V3(0.3, 0.5, 2) + rho * V3(0, 1, 1) / std::sqrt(2.0))).norm() <= 1e-14);
  // Near the corner (1, 0.5, 2).
  p = V3(1.01, 0.51, 2.01);
  REQUIRE(push_off(box, p, rho));
  CHECK((p - (V3(1, 0.5, 2) + rho * V3(1, 1, 1) / std::sqrt(3.0))).norm() <= 1e-14);
  // On the top face 2 cm from the rim, and 1 cm over it: lifted along the face's normal to
  // rho from the edge.
  const double lift = std::sqrt(rho * rho - 0.02 * 0.02);
  for (const double over : {0.0, 0.01}) {
    p = V3(0.3, 0.5 + over, 1.98);
    REQUIRE(push_off(box, p, rho));
    CHECK((p - V3(0.3, 0.5 + lift, 1.98)).norm() <= 1e-14);
  }
  // On the edge: along one of its faces' normals (the first axis), to rho.
  p = V3(0.3, 0.5, 2);
  REQUIRE(push_off(box, p, rho));
  CHECK((p - V3(0.3, 0.5 + rho, 2)).norm() <= 1e-14);
  // Over the top face near its corner: lifted by what the nearer edge needs.
  p = V3(0.99, 0.5, 1.97);
  REQUIRE(push_off(box, p, rho));
  CHECK((p - V3(0.99, 0.5 + std::sqrt(rho * rho - 0.01 * 0.01), 1.97)).norm() <= 1e-14);
  // Far from every edge, or inside: unchanged.
  for (const V3& q : {V3(0.3, 0.6, 0.0), V3(0.3, 0.5 + 1e-3, 1.0), V3(0.2, 0.1, 0.3)}) {
    V3 r = q;
    CHECK_FALSE(push_off(box, r, rho));
    CHECK(r == q);
  }
  // A point already rho from the edge stays.
  p = V3(0.3, 0.5, 2) + rho * V3(0, 0.6, 0.8);
  const V3 at = p;
  CHECK_FALSE(push_off(box, p, rho * (1 - 1e-12)));
  CHECK(p == at);
}

TEST_CASE("push_off_edges: the collider's thickness adds to the distance; its pose is applied") {
  Collider box = Collider::box(V3(1, 2, 3), kHalf);
  box.set_thickness(0.01);
  V3 p = V3(1, 2, 3) + V3(0.3, 0.51, 2.01);
  REQUIRE(push_off(box, p, 0.04));
  CHECK((p - (V3(1, 2, 3) + V3(0.3, 0.5, 2) + 0.05 * V3(0, 1, 1) / std::sqrt(2.0))).norm() <=
        1e-13);
  // Shapes without edges: nothing.
  for (const Collider& c :
       {Collider::sphere(V3::Zero(), 0.5), Collider::plane(V3::Zero(), V3(0, 1, 0))}) {
    V3 q(0.1, 0.5, 0.0);
    CHECK_FALSE(push_off(c, q, 0.1));
  }
}

TEST_CASE("push_off_edges: a box's band is at most the start's distance from its edges") {
  Collider box = Collider::box(V3::Zero(), kHalf);
  const double rho = 0.05;
  // Starting 2 cm over the top face, 1 cm from the rim (sqrt(5) cm from the edge), ending 0.5 cm
  // over it: lifted back to the start's distance from the edge, its height 2 cm, not to the
  // whole band's sqrt(rho^2 - 1 cm^2).
  const V3 start(0.3, 0.52, 1.99);
  V3 p(0.3, 0.505, 1.99);
  REQUIRE(push_off(box, p, rho, start));
  CHECK((p - V3(0.3, 0.52, 1.99)).norm() <= 1e-14);
  // Ending farther than it started (but in the band): unchanged.
  p = V3(0.3, 0.53, 1.99);
  CHECK_FALSE(push_off(box, p, rho, start));
  CHECK(p == V3(0.3, 0.53, 1.99));
  // Starting inside the box: no band (the box's own push acts).
  p = V3(0.3, 0.505, 1.99);
  CHECK_FALSE(push_off(box, p, rho, V3(0.3, 0.4, 1.9)));
  // A moving box: the start is taken at the start pose, the end at the end pose. Rising 1 cm
  // over the step, the same start (local (0.3, 0.52, 1.99) then) and an end at local height 0.5 cm
  // give the local height 2 cm at the end pose.
  box.set_velocity(V3(0, 0.1, 0));
  box.begin_step(0.1);
  p = V3(0.3, 0.515, 1.99);
  REQUIRE(push_off(box, p, rho, start));
  CHECK((p - V3(0.3, 0.53, 1.99)).norm() <= 1e-14);
}

TEST_CASE("points rho = L / sqrt(2) from a box's edges and corners leave no room to cut it") {
  const double L = 0.1;
  const Sampled safe = sample(L, L / std::sqrt(2.0), 400000);
  CHECK(safe.segments > 20000);
  CHECK(safe.triangles > 2000);
  CHECK(safe.segments_crossing == 0);
  CHECK(safe.triangles_pierced == 0);
  // Closer to the rim segments cut it (two points on the two faces, rho from the rim, are
  // sqrt(2) rho apart), and box edges pierce triangles.
  CHECK(sample(L, 0.6 * L, 400000).segments_crossing > 0);
  CHECK(sample(L, 0.3 * L, 400000).triangles_pierced > 0);
}
