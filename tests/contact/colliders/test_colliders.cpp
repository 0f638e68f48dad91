// contact/colliders/collider.hpp, triangle_mesh.hpp, point_triangle.hpp: the geometry of the
// colliders against independent oracles. Signed distance and outward normal of the plane, sphere,
// capsule and box against their closed forms (inside and outside, a rotated box, a moved pose, the
// pose a velocity and an angular velocity give after a step, and the surface velocity
// v + w x (x - t)); a path through a solid sent back to where it entered, against a sampled path;
// the mesh's closest point and first crossing against a brute force over all triangles written
// here (its own point-triangle distance and segment-plane crossing); the errors for degenerate
// input.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <massspring/contact/colliders/box_shape.hpp>
#include <massspring/contact/colliders/collider.hpp>
#include <massspring/contact/colliders/collider_set.hpp>
#include <massspring/contact/colliders/mesh_shape.hpp>
#include <massspring/contact/colliders/triangle_mesh.hpp>
#include <massspring/error.hpp>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "support/segment_checks.hpp"
namespace contact = massspring::contact;
using V3 = massspring::Vector3<double>;
using M3 = Eigen::Matrix3d;
using Pts = massspring::Points<double>;
using Collider = contact::Collider<double>;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// phi(x) and the normal and surface velocity the collider reports at x (end pose), by asking
// for the contact with an unbounded slop: depth = thickness - phi.
struct Probe {
  double phi;
  V3 normal, velocity;
};
Probe probe(const Collider& c, const V3& x) {
  contact::ColliderContact<double> k;
  const bool hit = c.contact(x, x, 1e30, k);
  REQUIRE(hit);
  return {c.thickness() - k.depth, k.normal, k.velocity};
}

// ---- oracles
// --------------------------------------------------------------------------------------

// Closest point of the segment [a, b] to p (clamped projection).
V3 segment_closest(const V3& p, const V3& a, const V3& b) {
  const V3 d = b - a;
  const double dd = d.squaredNorm();
  const double t = dd > 0 ? std::clamp((p - a).dot(d) / dd, 0.0, 1.0) : 0.0;
  return a + t * d;
}

// Closest point of triangle (a, b, c) to p: the projection onto the plane when it lies inside
// (barycentric coordinates from areas), else the nearest of the three edges' closest points.
// Independent of Ericson's Voronoi-region walk in point_triangle.hpp.
V3 triangle_closest(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 n = (b - a).cross(c - a);
  const V3 q = p - (p - a).dot(n) / n.squaredNorm() * n;
  const double wa = (b - q).cross(c - q).dot(n), wb = (c - q).cross(a - q).dot(n),
               wc = (a - q).cross(b - q).dot(n);
  if (wa >= 0 && wb >= 0 && wc >= 0) return q;
  V3 best = segment_closest(p, a, b);
  for (const V3& e : {segment_closest(p, b, c), segment_closest(p, c, a)})
    if ((e - p).squaredNorm() < (best - p).squaredNorm()) best = e;
  return best;
}

// Where the segment p0 -> p1 crosses triangle (a, b, c): the plane's crossing parameter and the
// signed areas of the crossing point (all >= 0 inside). `margin` is the smallest normalised
// barycentric coordinate (negative outside) and the distance of the ends from the plane relative
// to the segment, so that a caller can leave out the cases within rounding of an edge.
struct Crossing {
  bool hit = false;
  double t = kInf, margin = 0;
};
Crossing segment_triangle(const V3& p0, const V3& p1, const V3& a, const V3& b, const V3& c) {
  Crossing r;
  const V3 n = (b - a).cross(c - a);
  const double s0 = (p0 - a).dot(n), s1 = (p1 - a).dot(n);
  if ((s0 > 0 && s1 > 0) || (s0 < 0 && s1 < 0) || s0 == s1) {
    r.margin = std::min(std::abs(s0), std::abs(s1)) / n.norm() / (p1 - p0).norm();
    return r;
  }
  r.t = s0 / (s0 - s1);
  const V3 q = p0 + r.t * (p1 - p0);
  const double area = n.squaredNorm();
  const double wa = (b - q).cross(c - q).dot(n) / area, wb = (c - q).cross(a - q).dot(n) / area,
               wc = (a - q).cross(b - q).dot(n) / area;
  r.hit = wa >= 0 && wb >= 0 && wc >= 0;
  r.margin = std::min(
      {std::abs(wa), std::abs(wb), std::abs(wc), std::abs(s0) / n.norm(), std::abs(s1) / n.norm()});
  return r;
}

// Signed distance from the axis-aligned box [-h, h] and its outward normal: outside, the distance
// to the clamped point; inside, minus the distance to the nearest of the six faces.
double box_oracle(const V3& p, const V3& h, V3& n) {
  const V3 clamped = p.cwiseMax(-h).cwiseMin(h);
  if (clamped != p) {
    n = (p - clamped).normalized();
    return (p - clamped).norm();
  }
  double best = kInf;
  for (int k = 0; k < 3; ++k)
    for (const double side : {-1.0, 1.0}) {
      const double d = h(k) - side * p(k);  // distance to the face x_k = side h_k
      if (d < best) {
        best = d;
        n = V3::Zero();
        n(k) = side;
      }
    }
  return -best;
}

void check_vec(const V3& got, const V3& want, double tol) {
  INFO("got (" << got.transpose() << "), want (" << want.transpose() << ")");
  CHECK((got - want).norm() <= tol);
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const massspring::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Random points in a cube.
struct Random {
  std::mt19937_64 engine;
  std::uniform_real_distribution<double> u{-1, 1};
  explicit Random(unsigned seed) : engine(seed) {}
  double operator()() { return u(engine); }
  V3 point(double scale = 1) { return scale * V3((*this)(), (*this)(), (*this)()); }
};

}  // namespace

// ---- analytic shapes
// ------------------------------------------------------------------------------

TEST_CASE("plane collider: phi = (x - p) . n / |n| and the unit normal, on both sides") {
  const V3 p(0.3, -0.2, 0.5), n_raw(1, 2, -2);  // |n_raw| = 3
  const Collider c = Collider::plane(p, n_raw);
  const V3 n = n_raw / 3;
  check_vec(c.axis(), n, 1e-15);
  Random r(1);
  for (int k = 0; k < 200; ++k) {
    const V3 x = r.point(2);
    const Probe q = probe(c, x);
    CHECK(std::abs(q.phi - (x - p).dot(n)) <= 1e-14);
    check_vec(q.normal, n, 1e-15);
    CHECK(q.velocity.isZero());
  }
  // Outside and beyond the slop: no contact; within the thickness: contact, depth t - phi.
  Collider thick = Collider::plane(p, n_raw);
  thick.set_thickness(0.1);
  contact::ColliderContact<double> k;
  CHECK_FALSE(thick.contact(p + 0.2 * n, p + 0.2 * n, 0, k));
  REQUIRE(thick.contact(p + 0.05 * n, p + 0.05 * n, 0, k));
  CHECK(std::abs(k.depth - 0.05) <= 1e-15);
}

TEST_CASE("sphere collider: phi = |x - c| - r, n = (x - c) / |x - c|, inside and outside") {
  const V3 center(1, -2, 0.5);
  const double radius = 0.7;
  const Collider c = Collider::sphere(center, radius);
  Random r(2);
  int inside = 0;
  for (int k = 0; k < 300; ++k) {
    const V3 x = center + r.point(1.2);
    const Probe q = probe(c, x);
    const double phi = (x - center).norm() - radius;
    inside += phi < 0;
    CHECK(std::abs(q.phi - phi) <= 1e-14);
    check_vec(q.normal, (x - center).normalized(), 1e-14);
    // x + (-phi) n lies on the sphere.
    CHECK(std::abs((x - q.phi * q.normal - center).norm() - radius) <= 1e-14);
  }
  CHECK(inside > 30);
  CHECK(inside < 270);
}

TEST_CASE("capsule collider: phi = distance to the segment - r, inside and outside, a = b") {
  const V3 a(-0.4, 0.1, 0.2), b(0.6, 0.5, -0.3);
  const double radius = 0.3;
  const Collider c = Collider::capsule(a, b, radius);
  Random r(3);
  int inside = 0, ends = 0;
  for (int k = 0; k < 300; ++k) {
    const V3 x = (a + b) / 2 + r.point(1.0);
    const V3 foot = segment_closest(x, a, b);
    const double phi = (x - foot).norm() - radius;
    inside += phi < 0;
    ends += (foot - a).norm() < 1e-15 || (foot - b).norm() < 1e-15;
    const Probe q = probe(c, x);
    CHECK(std::abs(q.phi - phi) <= 1e-14);
    check_vec(q.normal, (x - foot).normalized(), 1e-13);
  }
  CHECK(inside > 20);
  CHECK(ends > 20);  // the spherical caps were tested too
  // A point on the axis: phi = -r, some unit normal perpendicular to the axis.
  const Probe axis_point = probe(c, (a + b) / 2);
  CHECK(std::abs(axis_point.phi + radius) <= 1e-15);
  CHECK(std::abs(axis_point.normal.norm() - 1) <= 1e-15);
  CHECK(std::abs(axis_point.normal.dot(b - a)) <= 1e-15);
  // a = b is a sphere.
  const Collider ball = Collider::capsule(a, a, radius);
  for (int k = 0; k < 20; ++k) {
    const V3 x = a + r.point(1.0);
    CHECK(std::abs(probe(ball, x).phi - ((x - a).norm() - radius)) <= 1e-14);
  }
}

TEST_CASE("box collider: signed distance and normal, axis-aligned and rotated (w, x, y, z)") {
  const V3 center(0.2, -0.1, 0.4), h(0.5, 0.2, 0.35);
  // A non-unit quaternion: the collider normalises it.
  const Eigen::Vector4d wxyz = 3 * Eigen::Vector4d(0.8, 0.2, -0.4, 0.4).normalized();
  const M3 rotated =
      Eigen::Quaterniond(wxyz(0), wxyz(1), wxyz(2), wxyz(3)).normalized().toRotationMatrix();
  for (const bool rotate : {false, true}) {
    CAPTURE(rotate);
    const M3 R = rotate ? rotated : M3::Identity();
    const Collider c = rotate ? Collider::box(center, h, wxyz) : Collider::box(center, h);
    CHECK((c.rotation() - R).norm() <= 1e-15);
    Random r(rotate ? 5 : 4);
    int inside = 0;
    for (int k = 0; k < 400; ++k) {
      const V3 x = center + r.point(0.6);
      V3 n_local;
      const double phi = box_oracle(R.transpose() * (x - center), h, n_local);
      inside += phi < 0;
      const Probe q = probe(c, x);
      CHECK(std::abs(q.phi - phi) <= 1e-14);
      check_vec(q.normal, R * n_local, 1e-13);
      // Pushed out by -phi along the normal, the point lands on the surface.
      V3 unused;
      CHECK(std::abs(box_oracle(R.transpose() * (x - q.phi * q.normal - center), h, unused)) <=
            1e-14);
    }
    CHECK(inside > 40);
    CHECK(inside < 360);
  }
  // Exact face, edge and corner directions of the axis-aligned box.
  const Collider c = Collider::box(center, h);
  Probe q = probe(c, center + V3(0.9, 0, 0));  // 0.4 beyond the +x face
  CHECK(std::abs(q.phi - 0.4) <= 1e-15);
  check_vec(q.normal, V3::UnitX(), 0);
  q = probe(c, center + V3(0.5 + 0.3, 0.2 + 0.4, 0));  // beyond the (+x, +y) edge: 3-4-5
  CHECK(std::abs(q.phi - 0.5) <= 1e-15);
  check_vec(q.normal, V3(0.6, 0.8, 0), 1e-15);
  q = probe(c, center + V3(0, -0.15, 0.1));  // inside, nearest face -y at 0.05
  CHECK(std::abs(q.phi + 0.05) <= 1e-15);
  check_vec(q.normal, -V3::UnitY(), 0);
}

TEST_CASE("set_pose moves each shape rigidly: reference point to t, axes by R") {
  const M3 R = Eigen::AngleAxisd(0.7, V3(1, -2, 0.5).normalized()).toRotationMatrix();
  const V3 t(0.5, 1.5, -0.25);
  Random r(6);
  SUBCASE("plane: through t with normal R n") {
    Collider c = Collider::plane(V3(1, 1, 1), V3(0, 0, 2));
    c.set_pose(R, t);
    for (int k = 0; k < 50; ++k) {
      const V3 x = t + r.point();
      const Probe q = probe(c, x);
      CHECK(std::abs(q.phi - (x - t).dot(R.col(2))) <= 1e-14);
      check_vec(q.normal, R.col(2), 1e-15);
    }
  }
  SUBCASE("sphere: centre at t") {
    Collider c = Collider::sphere(V3(-3, 0, 0), 0.4);
    c.set_pose(R, t);
    for (int k = 0; k < 50; ++k) {
      const V3 x = t + r.point();
      CHECK(std::abs(probe(c, x).phi - ((x - t).norm() - 0.4)) <= 1e-14);
    }
  }
  SUBCASE("capsule: ends t + R (a - m), t + R (b - m)") {
    const V3 a(0, 0, 0), b(1, 0.5, 0), m = (a + b) / 2;
    Collider c = Collider::capsule(a, b, 0.2);
    c.set_pose(R, t);
    const V3 a2 = t + R * (a - m), b2 = t + R * (b - m);
    for (int k = 0; k < 100; ++k) {
      const V3 x = t + r.point();
      CHECK(std::abs(probe(c, x).phi - ((x - segment_closest(x, a2, b2)).norm() - 0.2)) <= 1e-14);
    }
  }
  SUBCASE("box: centre t; R replaces the orientation (the pose maps its axes)") {
    const V3 h(0.3, 0.2, 0.1);
    const Eigen::Vector4d q0(std::cos(0.3), 0, 0, std::sin(0.3));  // 0.6 rad about z
    Collider c = Collider::box(V3(2, 2, 2), h, q0);
    const M3 R0 = Eigen::AngleAxisd(0.6, V3::UnitZ()).toRotationMatrix();
    CHECK((c.rotation() - R0).norm() <= 1e-15);
    c.set_pose(R * c.rotation(), t);  // turn the box by R about its centre, then move it
    for (int k = 0; k < 100; ++k) {
      const V3 x = t + r.point(0.5);
      V3 n;
      const double phi = box_oracle((R * R0).transpose() * (x - t), h, n);
      const Probe p = probe(c, x);
      CHECK(std::abs(p.phi - phi) <= 1e-14);
      check_vec(p.normal, R * R0 * n, 1e-13);
    }
  }
  SUBCASE("mesh: vertex t + R (v - centre of the bounding box)") {
    Pts v(3, 3);
    v << 0, 0, 0, 2, 0, 0, 0, 1, 0;
    contact::Triangles f(1, 3);
    f << 0, 1, 2;
    Collider c = Collider::mesh(v, f);
    c.set_thickness(10);  // every probe is within the thickness: phi is the distance
    const V3 centre(1, 0.5, 0);
    CHECK((c.translation() - centre).norm() == 0);
    c.set_pose(R, t);
    const V3 a = t + R * (V3(0, 0, 0) - centre), b = t + R * (V3(2, 0, 0) - centre),
             cc = t + R * (V3(0, 1, 0) - centre);
    for (int k = 0; k < 100; ++k) {
      const V3 x = t + r.point();
      CHECK(std::abs(probe(c, x).phi - (x - triangle_closest(x, a, b, cc)).norm()) <= 1e-14);
    }
  }
  // Not a rotation: refused, the pose unchanged.
  Collider c = Collider::sphere(V3(0, 0, 0), 1);
  CHECK_THROWS_AS(c.set_pose(-M3::Identity(), t), massspring::Error);  // det -1
  CHECK_THROWS_AS(c.set_pose(2 * M3::Identity(), t), massspring::Error);
  CHECK_THROWS_AS(c.set_pose(M3::Identity(), V3(0, kInf, 0)), massspring::Error);
  CHECK(c.translation().isZero());
}

TEST_CASE("moving collider: surface velocity v + w x (x - t); begin_step sets the end pose") {
  const V3 v(0.3, -0.1, 0.2), w(0.5, 1.0, -2.0), center(0.1, 0.2, 0.3), h(0.4, 0.3, 0.2);
  const double dt = 0.05;
  Collider c = Collider::box(center, h);
  c.set_velocity(v).set_angular_velocity(w);
  Random r(7);
  // Before a step: the current pose, t = centre.
  for (int k = 0; k < 50; ++k) {
    const V3 x = center + r.point();
    check_vec(probe(c, x).velocity, v + w.cross(x - center), 1e-15);
  }
  // The end-of-step pose of a step of dt: t + v dt, exp([w] dt) R (Eigen's angle-axis).
  c.begin_step(dt);
  CHECK(c.translation() == center);  // not committed yet
  const V3 t1 = center + dt * v;
  const M3 R1 = Eigen::AngleAxisd(w.norm() * dt, w.normalized()).toRotationMatrix();
  for (int k = 0; k < 100; ++k) {
    const V3 x = t1 + r.point(0.6);
    V3 n;
    const double phi = box_oracle(R1.transpose() * (x - t1), h, n);
    const Probe p = probe(c, x);
    CHECK(std::abs(p.phi - phi) <= 1e-14);
    check_vec(p.normal, R1 * n, 1e-13);
    check_vec(p.velocity, v + w.cross(x - t1), 1e-15);
  }
  c.end_step();
  check_vec(c.translation(), t1, 1e-16);
  CHECK((c.rotation() - R1).norm() <= 1e-15);
  // Ten more steps: the pose follows t0 + n v dt and the rotation by n w dt.
  for (int k = 0; k < 10; ++k) {
    c.begin_step(dt);
    c.end_step();
  }
  check_vec(c.translation(), center + 11 * dt * v, 1e-15);
  const M3 R11 = Eigen::AngleAxisd(w.norm() * 11 * dt, w.normalized()).toRotationMatrix();
  CHECK((c.rotation() - R11).norm() <= 1e-14);
}

// Collider::surface_displacement(): where the surface point at x (end pose) was at the step's
// start, by the closed form of the rigid motion (Eigen's angle-axis rotation by w dt about the
// reference point, which moved by v dt); it differs from the tangent dt (v + w x (x - t)) by the
// arc's departure from its tangent, about |w dt|^2 / 2 of the radius.
TEST_CASE("moving collider: the surface's displacement over a step is its rigid motion's") {
  const V3 v(0.3, -0.1, 0.2), w(0.0, 0.0, 3.0), center(0.1, 0.2, 0.3);
  const double dt = 0.1;
  Collider c = Collider::capsule(center - V3(0.5, 0, 0), center + V3(0.5, 0, 0), 0.05);
  c.set_velocity(v).set_angular_velocity(w);
  c.begin_step(dt);
  const V3 t1 = center + dt * v;
  const M3 R = Eigen::AngleAxisd(w.norm() * dt, w.normalized()).toRotationMatrix();
  Random r(11);
  for (int k = 0; k < 50; ++k) {
    const V3 x = t1 + r.point(0.5);
    const V3 start = R.transpose() * (x - t1) + center;
    check_vec(c.surface_displacement(x, dt), x - start, 1e-15);
  }
  // 10 cm from the axis, 0.3 rad a step: the arc's chord and the tangent differ by
  // 10 cm (1 - cos a, sin a - a), a = 0.3.
  const V3 x = t1 + V3(0.1, 0, 0);
  const V3 tangent = dt * (v + w.cross(x - t1));
  CHECK(std::abs((c.surface_displacement(x, dt) - tangent).norm() -
                 0.1 * std::sqrt(2 - 2 * std::cos(0.3) - 0.6 * std::sin(0.3) + 0.09)) <= 1e-15);
  // Translating only: dt v exactly; at rest: 0.
  Collider sliding = Collider::plane(V3::Zero(), V3(0, 1, 0));
  sliding.set_velocity(v);
  sliding.begin_step(dt);
  CHECK(sliding.surface_displacement(V3(1, 2, 3), dt) == dt * v);
  Collider still = Collider::plane(V3::Zero(), V3(0, 1, 0));
  still.begin_step(dt);
  CHECK(still.surface_displacement(V3(1, 2, 3), dt) == V3::Zero());
}

// ---- triangle mesh ------------------------------------------------------------------------------

namespace {

// A bumpy height field (a well-shaped mesh, 2 (k-1)^2 triangles) and a soup of random triangles
// (overlapping, badly shaped boxes for the hierarchy).
void height_field(int k, Pts& v, contact::Triangles& f) {
  v.resize(k * k, 3);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const double x = -1 + 2.0 * i / (k - 1), z = -1 + 2.0 * j / (k - 1);
      v.row(i * k + j) << x, 0.2 * std::sin(3 * x) * std::cos(2 * z), z;
    }
  f.resize(2 * (k - 1) * (k - 1), 3);
  int t = 0;
  for (int i = 0; i + 1 < k; ++i)
    for (int j = 0; j + 1 < k; ++j) {
      const int a = i * k + j, b = a + 1, c = a + k + 1, d = a + k;
      f.row(t++) << a, b, c;
      f.row(t++) << a, c, d;
    }
}

void soup(int m, Pts& v, contact::Triangles& f) {
  Random r(11);
  v.resize(3 * m, 3);
  f.resize(m, 3);
  for (int t = 0; t < m; ++t) {
    const V3 c = r.point(1.0);
    for (int k = 0; k < 3; ++k) v.row(3 * t + k) = (c + r.point(0.3)).transpose();
    f.row(t) << 3 * t, 3 * t + 1, 3 * t + 2;
  }
}

void check_mesh_queries(const Pts& v, const contact::Triangles& f, unsigned seed) {
  const contact::TriangleMesh<double> mesh(v, f);
  auto corner = [&](int t, int k) -> V3 { return v.row(f(t, k)).transpose(); };
  Random r(seed);
  // Closest point within a radius, against the minimum over all triangles.
  int found = 0, none = 0;
  for (int k = 0; k < 300; ++k) {
    const V3 p = r.point(1.4);
    const double radius = 0.05 + 0.5 * (r() + 1) / 2;
    double best = kInf;
    for (int t = 0; t < int(f.rows()); ++t)
      best = std::min(best,
                      (p - triangle_closest(p, corner(t, 0), corner(t, 1), corner(t, 2))).norm());
    V3 q;
    int tri = -1;
    const bool hit = mesh.closest_within(p, radius, q, tri);
    if (std::abs(best - radius) < 1e-12) continue;  // on the boundary of the query
    CAPTURE(k);
    REQUIRE(hit == (best < radius));
    if (!hit) {
      ++none;
      continue;
    }
    ++found;
    CHECK(std::abs((p - q).norm() - best) <= 1e-13);
    // q lies on the triangle the query named.
    CHECK((q - triangle_closest(q, corner(tri, 0), corner(tri, 1), corner(tri, 2))).norm() <=
          1e-13);
  }
  CHECK(found > 50);
  CHECK(none > 20);
  // First crossing of a segment, against the smallest crossing parameter over all triangles;
  // segments that pass within rounding of an edge or start or end on a plane are left out.
  int crossings = 0, misses = 0, left_out = 0;
  for (int k = 0; k < 400; ++k) {
    // Random segments, every other one roughly vertical through the box of the mesh.
    const V3 p0 = r.point(1.3);
    const V3 p1 = k % 2 ? V3(p0 + r.point(0.8)) : V3(p0(0), -p0(1), p0(2)) + r.point(0.2);
    Crossing first;
    bool ambiguous = false;
    for (int t = 0; t < int(f.rows()); ++t) {
      const Crossing c = segment_triangle(p0, p1, corner(t, 0), corner(t, 1), corner(t, 2));
      if (c.margin < 1e-9 && c.t <= 1) ambiguous = true;
      if (c.hit && c.t <= 1 && c.t < first.t) first = c;
    }
    if (ambiguous) {
      ++left_out;
      continue;
    }
    double t_hit = -1;
    int tri = -1;
    const bool hit = mesh.first_crossing(p0, p1, t_hit, tri);
    CAPTURE(k);
    REQUIRE(hit == first.hit);
    if (!hit) {
      ++misses;
      continue;
    }
    ++crossings;
    CHECK(std::abs(t_hit - first.t) <= 1e-12);
    const Crossing own = segment_triangle(p0, p1, corner(tri, 0), corner(tri, 1), corner(tri, 2));
    CHECK(own.hit);
    CHECK(std::abs(own.t - t_hit) <= 1e-12);
  }
  CHECK(crossings > 50);
  CHECK(misses > 50);
  CHECK(left_out < 10);
}

}  // namespace

TEST_CASE("TriangleMesh: closest point and first crossing equal a brute force over all triangles") {
  Pts v;
  contact::Triangles f;
  SUBCASE("height field, 242 triangles") {
    height_field(12, v, f);
    check_mesh_queries(v, f, 21);
  }
  SUBCASE("random soup, 300 triangles") {
    soup(300, v, f);
    check_mesh_queries(v, f, 22);
  }
}

TEST_CASE(
    "TriangleMesh: of triangles at one distance or crossed at one parameter, the lowest index") {
  // A fan of six triangles about the origin in the plane y = 0, behind three far ones, each
  // fan triangle taking each index in turn: a point above the centre is at 0.1 m from all six,
  // and a vertical segment through the centre meets them all at its middle, whatever the tree.
  constexpr double kPi = 3.14159265358979323846;
  for (int turn = 0; turn < 6; ++turn) {
    CAPTURE(turn);
    Pts v(7 + 9, 3);
    v.row(0) << 0, 0, 0;
    for (int k = 0; k < 6; ++k) v.row(1 + k) << std::cos(k * kPi / 3), 0, std::sin(k * kPi / 3);
    for (int j = 0; j < 3; ++j) {
      v.row(7 + 3 * j) << 5 + j, 1, 5;
      v.row(8 + 3 * j) << 6 + j, 1, 5;
      v.row(9 + 3 * j) << 5 + j, 2, 5;
    }
    contact::Triangles f(9, 3);
    for (int j = 0; j < 3; ++j) f.row(j) << 7 + 3 * j, 8 + 3 * j, 9 + 3 * j;
    for (int k = 0; k < 6; ++k) f.row(3 + (k + turn) % 6) << 0, 1 + k, 1 + (k + 1) % 6;
    const contact::TriangleMesh<double> mesh(v, f);
    V3 q;
    int tri = -1;
    REQUIRE(mesh.closest_within(V3(0, 0.1, 0), 0.5, q, tri));
    CHECK(q == V3::Zero());
    CHECK(tri == 3);
    // The tie rule over the library's own segment test, triangle by triangle.
    const V3 p0(0, 1, 0), p1(0, -1, 0);
    int lowest = -1;
    for (int t = 0; t < 9 && lowest < 0; ++t) {
      double u = 0;
      if (contact::segment_crosses_triangle(p0, p1, mesh.vertex(t, 0), mesh.vertex(t, 1),
                                            mesh.vertex(t, 2), u))
        lowest = t;
    }
    REQUIRE(lowest >= 3);
    double t_hit = -1;
    REQUIRE(mesh.first_crossing(p0, p1, t_hit, tri));
    CHECK(t_hit == 0.5);
    CHECK(tri == lowest);
  }
}

TEST_CASE("mesh collider: phi is the unsigned distance; a crossing path is sent back") {
  Pts v;
  contact::Triangles f;
  height_field(8, v, f);
  Collider c = Collider::mesh(v, f);
  c.set_thickness(0.05);
  auto corner = [&](int t, int k) -> V3 { return v.row(f(t, k)).transpose(); };
  auto distance = [&](const V3& p) {
    double best = kInf;
    for (int t = 0; t < int(f.rows()); ++t)
      best = std::min(best,
                      (p - triangle_closest(p, corner(t, 0), corner(t, 1), corner(t, 2))).norm());
    return best;
  };
  Random r(31);
  int near = 0, crossed = 0;
  for (int k = 0; k < 300; ++k) {
    const V3 x = V3(0.9 * r(), 0.3 * r(), 0.9 * r());
    const V3 x_end = x + V3(0.02 * r(), 0.02 * r(), 0.02 * r());
    // Paths that cross the surface are checked below; here the start and end are on one side.
    bool crosses = false;
    for (int t = 0; t < int(f.rows()); ++t)
      crosses |= segment_triangle(x, x_end, corner(t, 0), corner(t, 1), corner(t, 2)).hit;
    if (crosses) continue;
    const double d = distance(x_end);
    contact::ColliderContact<double> kc;
    const bool hit = c.contact(x, x_end, 0, kc);
    if (std::abs(d - 0.05) < 1e-12) continue;
    CHECK(hit == (d < 0.05));
    if (!hit) continue;
    ++near;
    CHECK(std::abs(kc.depth - (0.05 - d)) <= 1e-13);
    // The normal points from the closest point q of the mesh (brute force) to x_end: the push
    // puts the point at the thickness from q.
    V3 q;
    double best = kInf;
    for (int t = 0; t < int(f.rows()); ++t) {
      const V3 qt = triangle_closest(x_end, corner(t, 0), corner(t, 1), corner(t, 2));
      if ((qt - x_end).norm() < best) {
        best = (qt - x_end).norm();
        q = qt;
      }
    }
    check_vec(kc.normal, (x_end - q).normalized(), 1e-9);
    CHECK(std::abs((x_end + kc.depth * kc.normal - q).norm() - 0.05) <= 1e-12);
  }
  CHECK(near > 30);
  // Paths through the surface (from above y = 0.5 to below): the push puts the end on the side
  // of the first triangle crossed (brute force) the path started from, at the thickness from its
  // plane (and a few rounding units), whatever the distance of the end.
  for (int k = 0; k < 200; ++k) {
    const double x0 = 0.8 * r(), z0 = 0.8 * r();
    const V3 a(x0, 0.5, z0), b(x0 + 0.1 * r(), -0.5 + 0.3 * r(), z0 + 0.1 * r());
    Crossing first;
    int first_tri = -1;
    for (int t = 0; t < int(f.rows()); ++t) {
      const Crossing cr = segment_triangle(a, b, corner(t, 0), corner(t, 1), corner(t, 2));
      if (cr.hit && cr.t < first.t) {
        first = cr;
        first_tri = t;
      }
    }
    REQUIRE(first_tri >= 0);
    if (first.margin < 1e-9) continue;  // through an edge: either triangle is right
    contact::ColliderContact<double> kc;
    REQUIRE(c.contact(a, b, 0, kc));
    const V3 v0 = corner(first_tri, 0);
    const V3 n = (corner(first_tri, 1) - v0).cross(corner(first_tri, 2) - v0).normalized();
    const double side = (a - v0).dot(n) > 0 ? 1.0 : -1.0;
    check_vec(kc.normal, side * n, 1e-12);
    const V3 e = b + kc.depth * kc.normal;
    const double height = side * (e - v0).dot(n);  // above the plane, on a's side
    CHECK(height >= 0.05);
    CHECK(height <= 0.05 + 1e-12);
    ++crossed;
  }
  CHECK(crossed > 190);
}

// ---- errors
// ---------------------------------------------------------------------------------------

TEST_CASE("collider errors: degenerate shapes, materials and motions are refused with a message") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto has = [](const std::function<void()>& f, const std::string& part) {
    const std::string m = message_of(f);
    INFO(m);
    CHECK(m.find(part) != std::string::npos);
  };
  has([] { Collider::plane(V3(0, 0, 0), V3(0, 0, 0)); }, "normal must not be zero");
  has([&] { Collider::plane(V3(nan, 0, 0), V3(0, 0, 1)); }, "point must be finite");
  has([&] { Collider::plane(V3(0, 0, 0), V3(0, kInf, 1)); }, "normal must be finite");
  has([] { Collider::sphere(V3(0, 0, 0), 0); }, "radius must be finite and > 0");
  has([] { Collider::sphere(V3(0, 0, 0), -1); }, "radius");
  has([&] { Collider::sphere(V3(0, 0, 0), nan); }, "radius");
  has([&] { Collider::sphere(V3(0, 0, 0), kInf); }, "radius");
  has([&] { Collider::sphere(V3(0, nan, 0), 1); }, "center must be finite");
  has([] { Collider::capsule(V3(0, 0, 0), V3(1, 0, 0), 0); }, "capsule collider: radius");
  has([&] { Collider::capsule(V3(0, 0, 0), V3(nan, 0, 0), 1); }, "capsule: b");
  has([] { Collider::box(V3(0, 0, 0), V3(1, 0, 1)); }, "half_extents");
  has([] { Collider::box(V3(0, 0, 0), V3(1, 1, -1)); }, "half_extents");
  has([] { Collider::box(V3(0, 0, 0), V3(1, 1, 1), Eigen::Vector4d::Zero()); }, "quaternion");
  has([&] { Collider::box(V3(0, 0, 0), V3(1, 1, 1), Eigen::Vector4d(1, nan, 0, 0)); },
      "quaternion");
  // Meshes.
  Pts v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  contact::Triangles f(1, 3);
  f << 0, 1, 2;
  CHECK_NOTHROW(Collider::mesh(v, f));
  has([&] { Collider::mesh(Pts(0, 3), f); }, "no vertices");
  has([&] { Collider::mesh(v, contact::Triangles(0, 3)); }, "no triangles");
  contact::Triangles bad = f;
  bad(0, 2) = 3;
  has([&] { Collider::mesh(v, bad); }, "triangle 0 has vertex index 3, out of range [0, 3)");
  bad(0, 2) = -1;
  has([&] { Collider::mesh(v, bad); }, "out of range");
  bad(0, 2) = 1;  // a repeated vertex
  has([&] { Collider::mesh(v, bad); }, "zero area");
  Pts line = v;
  line.row(2) << 2, 0, 0;  // collinear
  has([&] { Collider::mesh(line, f); }, "zero area");
  Pts not_finite = v;
  not_finite(1, 1) = nan;
  has([&] { Collider::mesh(not_finite, f); }, "not finite");
  // Material and motion.
  Collider c = Collider::sphere(V3(0, 0, 0), 1);
  has([&] { c.set_friction(-0.1); }, "friction must be finite and >= 0");
  has([&] { c.set_friction(nan); }, "friction");
  has([&] { c.set_friction(kInf); }, "friction");
  has([&] { c.set_friction(0.2, 0.3); }, "exceeds static friction");
  has([&] { c.set_restitution(1.5); }, "restitution must be in [0, 1]");
  has([&] { c.set_restitution(-0.1); }, "restitution");
  has([&] { c.set_restitution(nan); }, "restitution");
  has([&] { c.set_thickness(-1e-3); }, "thickness must be finite and >= 0");
  has([&] { c.set_thickness(kInf); }, "thickness");
  has([&] { c.set_velocity(V3(nan, 0, 0)); }, "velocity must be finite");
  has([&] { c.set_angular_velocity(V3(0, 0, kInf)); }, "angular_velocity must be finite");
  // Nothing was changed by the refused calls.
  CHECK(c.static_friction() == 0);
  CHECK(c.kinetic_friction() == 0);
  CHECK(c.restitution() == 0);
  CHECK(c.thickness() == 0);
  CHECK(c.velocity().isZero());
  CHECK(c.angular_velocity().isZero());
  c.set_friction(0.5, 0.3).set_restitution(0.25).set_thickness(0.01);
  CHECK(c.static_friction() == 0.5);
  CHECK(c.kinetic_friction() == 0.3);
  c.set_friction(0.4);
  CHECK(c.kinetic_friction() == 0.4);
}

TEST_CASE(
    "solid colliders: a path through a sphere, capsule or box that ends beyond it is sent "
    "back to the tangent plane where it entered") {
  // Oracle: the entry found by sampling the path densely against each shape's closed-form
  // distance (written here), and the tangent plane's closed form for the sphere.
  const double thickness = 0.01;
  const auto sphere_phi = [](const V3& p) { return p.norm() - 0.5; };
  const auto capsule_phi = [](const V3& p) {
    const double t = std::clamp(p.x() / 1.0, -0.4, 0.4);  // axis from (-0.4,0,0) to (0.4,0,0)
    return (p - V3(t, 0, 0)).norm() - 0.3;
  };
  const auto box_phi = [](const V3& p) {
    const V3 q = p.cwiseAbs() - V3(0.5, 0.3, 0.4);
    return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
  };
  struct Shape {
    Collider collider;
    std::function<double(const V3&)> phi;
  };
  std::vector<Shape> shapes = {{Collider::sphere(V3::Zero(), 0.5), sphere_phi},
                               {Collider::capsule(V3(-0.4, 0, 0), V3(0.4, 0, 0), 0.3), capsule_phi},
                               {Collider::box(V3::Zero(), V3(0.5, 0.3, 0.4)), box_phi}};
  Random r(5);
  for (Shape& s : shapes) {
    s.collider.set_thickness(thickness);
    int crossing = 0;
    for (int k = 0; k < 200; ++k) {
      // From outside on one side to outside on the other, through the middle region.
      const V3 dir = V3(r(), r(), r()).normalized();
      const V3 offset = 0.1 * V3(r(), r(), r());
      const V3 x = offset + 1.5 * dir, x_end = offset - 1.5 * dir;
      double entry = -1;
      for (int j = 0; j <= 100000; ++j) {
        const double t = j / 100000.0;
        if (s.phi(x + t * (x_end - x)) < thickness) {
          entry = t;
          break;
        }
      }
      contact::ColliderContact<double> kc;
      const bool hit = s.collider.contact(x, x_end, 0, kc);
      CHECK(hit == (entry >= 0));
      if (!hit || entry < 0) continue;
      ++crossing;
      // Pushed back onto the tangent plane at the entry e: (x_end + depth n - e) . n = 0, with n
      // the outward normal at e, and the pushed point no longer beyond the solid.
      const V3 e = x + entry * (x_end - x);
      const V3 pushed = x_end + kc.depth * kc.normal;
      CHECK(kc.depth > 0);
      CHECK(std::abs((pushed - e).dot(kc.normal)) < 1e-4);
      CHECK(s.phi(pushed) > thickness - 1e-4);  // out of the solid (convex: the plane bounds it)
      if (&s == &shapes[0]) CHECK((kc.normal - e.normalized()).norm() < 1e-3);
    }
    CHECK(crossing > 150);
  }
  // A path that passes beside the sphere is no contact; one that starts inside is the point's
  // ordinary response (its end is outside: none).
  contact::ColliderContact<double> kc;
  CHECK_FALSE(shapes[0].collider.contact(V3(-2, 0.6, 0), V3(2, 0.6, 0), 0, kc));
}

// Oracle: the closed form. A point falls straight down at x = 0.3 through a sphere of radius 0.5
// with thickness 0.01 and ends below its centre's height, inside (where the nearest surface
// would push it on down) or beyond: its path enters the contact zone at
// e = (0.3, sqrt(0.51^2 - 0.3^2), 0), and the push takes it onto the plane tangent there,
// depth (e - x_end) . e / |e|. The solver's entry may lie up to a millionth of the radius inside
// (a start that close counts as outside): 1e-6 covers it.
TEST_CASE("solid colliders: the push of a path through a sphere equals the closed form") {
  Collider sphere = Collider::sphere(V3::Zero(), 0.5);
  sphere.set_thickness(0.01);
  for (const double end_height : {-0.1, -0.3, -1.0}) {
    CAPTURE(end_height);
    const V3 x(0.3, 2, 0), x_end(0.3, end_height, 0);
    const V3 e(0.3, std::sqrt(0.51 * 0.51 - 0.3 * 0.3), 0);
    const V3 n = e / 0.51;
    contact::ColliderContact<double> kc;
    REQUIRE(sphere.contact(x, x_end, 0, kc));
    CHECK(std::abs(kc.depth - (e - x_end).dot(n)) <= 1e-6);
    CHECK((kc.normal - n).norm() <= 1e-6);
  }
}

// ContactZone::clearance() through Collider and ColliderSet (contact_zone.hpp has no test file
// of its own). Oracles: the closed form of the plane's and the still sphere's clearance (the
// distance to the contact zone, thickness included, less a margin of at most 1e-6 of the scale);
// and, for every shape, still and moving, that no path shorter than the clearance is pushed:
// ColliderSet's project() leaves its end bit for bit, and far() holds. ColliderSet::clearance() is
// the least of its colliders' (+infinity for none). With an edge distance rho (the bands of
// Collider::push_off_edges()), no path shorter than the clearance less rho is pushed.
TEST_CASE("clearance: no path shorter than it is pushed; the plane's and sphere's closed forms") {
  const double dt = 1.0 / 30, thickness = 0.01;
  Pts v;
  contact::Triangles f;
  height_field(6, v, f);
  std::vector<Collider> shapes = {Collider::plane(V3(0.1, -0.2, 0.3), V3(0.2, 1, -0.1)),
                                  Collider::sphere(V3(0.1, 0.2, -0.1), 0.5),
                                  Collider::capsule(V3(-0.3, 0, 0), V3(0.4, 0.2, 0.1), 0.2),
                                  Collider::box(V3(0.1, 0, 0.2), V3(0.3, 0.2, 0.4)),
                                  Collider::mesh(v, f)};
  Random r(31);
  for (const bool moving : {false, true}) {
    for (std::size_t s = 0; s < shapes.size(); ++s) {
      CAPTURE(moving);
      CAPTURE(s);
      Collider c = shapes[s];
      c.set_thickness(thickness);
      if (moving) c.set_velocity(V3(0.3, -0.6, 0.2)).set_angular_velocity(V3(0.5, -1, 2));
      contact::ColliderSet<double> set;
      CHECK(set.clearance(V3::Zero()) == kInf);
      set.add(c);
      set.begin_step(dt);
      const Collider& added = set[0];
      int tested = 0;
      for (int k = 0; k < 400; ++k) {
        const V3 xs = r.point(2.5);
        const double clearance = set.clearance(xs);
        CHECK(clearance == added.clearance(xs));
        if (!moving && s == 0) {
          const V3 n = V3(0.2, 1, -0.1).normalized();
          const double distance = (xs - V3(0.1, -0.2, 0.3)).dot(n) - thickness;
          CHECK(clearance <= distance);
          CHECK(clearance >= distance - 1e-6);
        }
        if (!moving && s == 1) {
          const double distance = (xs - V3(0.1, 0.2, -0.1)).norm() - 0.5 - thickness;
          CHECK(clearance <= distance);
          CHECK(clearance >= distance - 1e-6);
        }
        if (!(clearance > 0)) continue;
        ++tested;
        for (int j = 0; j < 10; ++j) {
          const V3 xe = xs + (0.999 * clearance * std::abs(r())) * r.point().normalized();
          CHECK(added.far(xs, xe, 0));
          Eigen::Vector3d moved = xe;
          set.project(xs.data(), moved.data(), dt);
          CHECK(moved == xe);
        }
        // With the solves' edge distance rho: no path shorter than the clearance less rho.
        const double rho = 0.05;
        for (int j = 0; j < 10 && clearance > rho; ++j) {
          const V3 xe = xs + (0.999 * (clearance - rho) * std::abs(r())) * r.point().normalized();
          Eigen::Vector3d moved = xe;
          set.project(xs.data(), moved.data(), dt, rho);
          CHECK(moved == xe);
        }
      }
      CHECK(tested > 50);
    }
  }
  // Two colliders: the least of the two.
  contact::ColliderSet<double> both;
  both.add(shapes[0]);
  both.add(shapes[1]);
  both.begin_step(dt);
  for (int k = 0; k < 50; ++k) {
    const V3 xs = r.point(2.5);
    CHECK(both.clearance(xs) == std::min(both[0].clearance(xs), both[1].clearance(xs)));
  }
}

// A step's start position far from every test collider's edges and axis: push_off_edges() then
// applies its whole band.
const V3 kFarStart(100, 100, 100);

// Collider::push_off_edges() of a capsule: the band of the solves' edge distance rho about its
// axis, D = max(r + thickness, sqrt(r^2 + rho^2 / 2)), in closed form (beside the axis, beyond an
// end, on the axis, the pose and the surface's velocity, a thick capsule whose band is its
// thickness); the plane and the sphere have no band.
TEST_CASE(
    "push_off_edges: a capsule keeps points max(r + thickness, sqrt(r^2 + rho^2 / 2)) off its "
    "axis") {
  const double r = 0.01, thickness = 0.002, rho = 0.04;
  const double D = std::sqrt(r * r + rho * rho / 2);  // 3 cm, above r + thickness
  Collider rod = Collider::capsule(V3(-1, 0, 0), V3(1, 0, 0), r);
  rod.set_thickness(thickness);
  contact::ColliderContact<double> push;
  V3 p(0.3, 0.02, 0);  // beside the axis: straight out
  REQUIRE(rod.push_off_edges(p, kFarStart, rho, push));
  check_vec(p, V3(0.3, D, 0), 1e-15);
  check_vec(push.normal, V3(0, 1, 0), 1e-13);  // rounding of x (0.3) over the depth (1 cm)
  CHECK(std::abs(push.depth - (D - 0.02)) <= 1e-15);
  CHECK(push.velocity == V3::Zero());
  p = V3(1.01, 0.005, 0);  // beyond the end b: radially from b
  REQUIRE(rod.push_off_edges(p, kFarStart, rho, push));
  check_vec(p, V3(1, 0, 0) + D * V3(0.01, 0.005, 0).normalized(), 1e-15);
  p = V3(0.5, 0, 0);  // on the axis (its foot exact in rounding): along a perpendicular
  REQUIRE(rod.push_off_edges(p, kFarStart, rho, push));
  CHECK(p.x() == 0.5);
  CHECK(std::abs(V3(0, p.y(), p.z()).norm() - D) <= 1e-15);
  // At D already, or farther: unchanged.
  for (const V3& q : {V3(0.3, 0, D * (1 + 1e-12)), V3(0.5, 0.1, 0.2), V3(1 + D, 0, 0)}) {
    V3 s = q;
    CHECK_FALSE(rod.push_off_edges(s, kFarStart, rho, push));
    CHECK(s == q);
  }
  // Moved and turned, and moving: the end pose is used, and the push reports its velocity.
  Collider turned = rod;
  turned.set_pose(Eigen::AngleAxisd(M_PI / 2, V3::UnitZ()).toRotationMatrix(), V3(1, 2, 3));
  turned.set_velocity(V3(0, 0, 0.3));
  turned.begin_step(0.1);  // the end pose: centre (1, 2, 3.03), axis along y
  p = V3(1.02, 2.5, 3.03);
  REQUIRE(turned.push_off_edges(p, kFarStart, rho, push));
  check_vec(p, V3(1 + D, 2.5, 3.03), 1e-14);
  check_vec(push.velocity, V3(0, 0, 0.3), 1e-15);
  // A thick capsule: r + thickness (5.4 cm) is above sqrt(r^2 + rho^2 / 2) (5.05 cm).
  Collider pole = Collider::capsule(V3(-1, 0, 0), V3(1, 0, 0), 0.05);
  pole.set_thickness(0.004);
  p = V3(0.3, 0.052, 0);
  REQUIRE(pole.push_off_edges(p, kFarStart, 0.01, push));
  check_vec(p, V3(0.3, 0.054, 0), 1e-15);
  // Shapes without thin parts: nothing.
  for (const Collider& c :
       {Collider::sphere(V3::Zero(), 0.5), Collider::plane(V3::Zero(), V3(0, 1, 0))}) {
    V3 q(0.1, 0.5, 0.0);
    CHECK_FALSE(c.push_off_edges(q, kFarStart, rho, push));
  }
}

// The band about a capsule's axis is at most the start's distance from it, and at least
// r + thickness (closed forms).
TEST_CASE("push_off_edges: a capsule's band is at most the start's distance from its axis") {
  const double r = 0.01, thickness = 0.002, rho = 0.04;  // the whole band: D = 3 cm
  Collider rod = Collider::capsule(V3(-1, 0, 0), V3(1, 0, 0), r);
  rod.set_thickness(thickness);
  contact::ColliderContact<double> push;
  // Starting 2 cm from the axis, ending 1.5 cm from it: back to 2 cm.
  V3 p(0.3, 0.015, 0);
  REQUIRE(rod.push_off_edges(p, V3(0.3, 0.02, 0), rho, push));
  check_vec(p, V3(0.3, 0.02, 0), 1e-15);
  // Ending at 2.5 cm: unchanged.
  p = V3(0.3, 0.025, 0);
  CHECK_FALSE(rod.push_off_edges(p, V3(0.3, 0.02, 0), rho, push));
  // Starting in the solid's reach (0.5 cm): r + thickness still holds.
  p = V3(0.3, 0.011, 0);
  REQUIRE(rod.push_off_edges(p, V3(0.3, 0.005, 0), rho, push));
  check_vec(p, V3(0.3, r + thickness, 0), 1e-15);
}

// The guarantee detail::edge_distances() relies on for a capsule, sampled: points pushed by
// push_off_edges() with rho (from anywhere near the axis and its ends) are D from the axis, and no
// segment of length <= L = sqrt(2) rho between two of them comes nearer the axis than r (into the
// solid). Pushed with a smaller rho, such segments do (so the check is not vacuous).
TEST_CASE("points pushed off a capsule's axis leave no segment of length sqrt(2) rho into it") {
  const double r = 0.01, thickness = 0.001, rho = 0.04, L = std::sqrt(2.0) * rho;
  const V3 a(-0.3, 0.1, 0), b(0.3, 0.2, 0.1);
  Collider rod = Collider::capsule(a, b, r);
  rod.set_thickness(thickness);
  Random random(17);
  const auto pushed = [&](double by) {
    // A point near the middle or the end b, pushed.
    V3 x = (random() > 0 ? b : V3((a + b) / 2)) + random.point(0.05);
    contact::ColliderContact<double> push;
    rod.push_off_edges(x, kFarStart, by, push);
    return x;
  };
  const auto least = [&](double by, int& segments) {
    double nearest = 1e300;
    segments = 0;
    for (int k = 0; k < 100000 && segments < 5000; ++k) {
      const V3 p = pushed(by), q = pushed(by);
      if ((p - q).norm() > L) continue;
      CHECK((p - segment_closest(p, a, b)).norm() >=
            (1 - 1e-12) * std::max(r + thickness, std::sqrt(r * r + by * by / 2)));
      ++segments;
      nearest = std::min(nearest, massspring::test::segment_segment_distance(p, q, a, b));
    }
    return nearest;
  };
  int segments = 0;
  CHECK(least(rho, segments) >= (1 - 1e-9) * r);
  CHECK(segments == 5000);
  CHECK(least(rho / 2, segments) < r);
  CHECK(segments == 5000);
}

// ColliderSet::project() with an edge distance: Coulomb friction on the band's push, in closed
// form. A static rod along x (r = 1 cm, rho = 4 cm: D = 3 cm); a point moves from 3.3 cm to
// 2.2 cm off the axis and 4 mm along it: pushed back out to 3 cm (depth 8 mm) with the
// tangential 4 mm kept, halved (mu = 0.25: mu depth / 4 mm of it removed) or removed (mu = 1).
TEST_CASE("project: the band about a capsule's axis has the capsule's Coulomb friction") {
  const double rho = 0.04, dt = 0.1;
  for (const auto& [mu, x] : {std::pair{0.0, 0.004}, std::pair{0.25, 0.002}, std::pair{1.0, 0.0}}) {
    CAPTURE(mu);
    contact::ColliderSet<double> set;
    set.add(Collider::capsule(V3(-1, 0, 0), V3(1, 0, 0), 0.01).set_friction(mu));
    set.begin_step(dt);
    const V3 xs(0, 0.033, 0);
    V3 xe(0.004, 0.022, 0);
    set.project(xs.data(), xe.data(), dt, rho);
    check_vec(xe, V3(x, 0.03, 0), 1e-15);
  }
}
