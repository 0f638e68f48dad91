// contact/broad_phase/normal_bounds.hpp. Oracles: the normal n(t) = (b - a) x (c - a) of the
// moving triangle computed directly at 101 times of the step, which the bounds must hold along
// each direction and the axis must see on its positive side; a flat triangle's closed form; and
// the 53-degree rule of the file comment on random normals.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <massspring/contact/broad_phase/normal_bounds.hpp>
#include <random>

namespace {
using Bounds = massspring::contact::NormalBounds<double>;
using V3 = Eigen::Vector3d;

const std::array<V3, 7> kDirections = {V3(1, 0, 0),  V3(0, 1, 0),  V3(0, 0, 1), V3(1, 1, 1),
                                       V3(1, 1, -1), V3(1, -1, 1), V3(-1, 1, 1)};

V3 normal_at(const std::array<V3, 6>& c, double t) {
  const V3 a = (1 - t) * c[0] + t * c[3], b = (1 - t) * c[1] + t * c[4],
           d = (1 - t) * c[2] + t * c[5];
  return (b - a).cross(d - a);
}
}  // namespace

TEST_CASE(
    "NormalBounds: a flat triangle moving in its plane has the axis +z, bounds in closed form") {
  // (0,0,0), (2,0,0), (0,1,0) moved by (1,2,0): n = (0, 0, 2) throughout.
  const V3 s(1, 2, 0);
  const Bounds b = Bounds::of_triangle(V3(0, 0, 0), V3(2, 0, 0), V3(0, 1, 0), V3(0, 0, 0) + s,
                                       V3(2, 0, 0) + s, V3(0, 1, 0) + s);
  // e . n = 0, 0, 2, 2, -2, 2, 2; the margins 1e-6 |e|_1 |n|_1 = 2e-6 and 6e-6.
  const std::array<double, 7> value = {0, 0, 2, 2, -2, 2, 2};
  for (std::size_t j = 0; j < 7; ++j) {
    const double m = j < 3 ? 2e-6 : 6e-6;
    CHECK(b.low[j] == doctest::Approx(value[j] - m).epsilon(1e-14));
    CHECK(b.high[j] == doctest::Approx(value[j] + m).epsilon(1e-14));
  }
  V3 a;
  REQUIRE(b.axis(a));
  CHECK(a == V3(0, 0, 1));
  // Flipped (the corners in the other order): -z.
  const Bounds f = Bounds::of_triangle(V3(0, 0, 0), V3(0, 1, 0), V3(2, 0, 0), V3(0, 0, 0),
                                       V3(0, 1, 0), V3(2, 0, 0));
  REQUIRE(f.axis(a));
  CHECK(a == V3(0, 0, -1));
}

TEST_CASE("NormalBounds: the bounds hold the normal at every time; the axis sees it positive") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int with_axis = 0;
  for (int trial = 0; trial < 600; ++trial) {
    std::array<V3, 6> c;
    for (V3& p : c) p = V3(u(rng), u(rng), u(rng));
    // Half the trials move a little (an axis likely), half anywhere.
    if (trial % 2 == 0)
      for (int k = 3; k < 6; ++k)
        c[std::size_t(k)] = c[std::size_t(k - 3)] + 0.1 * c[std::size_t(k)];
    Bounds b = Bounds::of_triangle(c[0], c[1], c[2], c[3], c[4], c[5]);
    // A second triangle merged in: the union's bounds hold both.
    std::array<V3, 6> d;
    for (V3& p : d) p = V3(u(rng), u(rng), u(rng));
    for (int k = 3; k < 6; ++k) d[std::size_t(k)] = d[std::size_t(k - 3)] + 0.1 * d[std::size_t(k)];
    const Bounds other = Bounds::of_triangle(d[0], d[1], d[2], d[3], d[4], d[5]);
    if (trial % 3 == 0) b = Bounds::merged(b, other);
    V3 a;
    const bool has = b.axis(a);
    with_axis += has;
    if (has) CHECK(std::abs(a.norm() - 1) < 1e-15);
    for (int s = 0; s <= 100; ++s) {
      const double t = s / 100.0;
      for (const std::array<V3, 6>* tri : {&c, &d}) {
        if (tri == &d && trial % 3 != 0) continue;
        const V3 n = normal_at(*tri, t);
        for (std::size_t j = 0; j < 7; ++j) {
          CHECK(b.low[j] <= kDirections[j].dot(n));
          CHECK(kDirections[j].dot(n) <= b.high[j]);
        }
        if (has) CHECK(a.dot(n) > 0);
      }
    }
  }
  CHECK(with_axis > 150);
}

// Every direction lies within 36.2 degrees of one of the fourteen axes, so three Bernstein
// normals within 53 degrees of a common direction always have an axis; at 75 degrees, some do
// not.
TEST_CASE("NormalBounds: normals within 53 degrees of one direction always have an axis") {
  std::mt19937 rng(9);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  const auto random_unit = [&] { return V3(g(rng), g(rng), g(rng)).normalized(); };
  int refused_wide = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double limit = (trial % 2 ? 75.0 : 53.0) * M_PI / 180;
    const V3 centre = random_unit();
    // Three normals at angles up to the limit from the centre, of random lengths.
    std::array<V3, 3> n;
    for (V3& v : n) {
      const V3 side = centre.cross(random_unit()).normalized();
      const double angle = limit * std::sqrt(u(rng));
      v = (0.1 + u(rng)) * (std::cos(angle) * centre + std::sin(angle) * side);
    }
    // A still triangle (0, e, f) per normal, its normal e x f = v, the three merged.
    Bounds b;
    for (int k = 0; k < 3; ++k) {
      const V3& v = n[std::size_t(k)];
      const V3 e = v.unitOrthogonal(), f = v.cross(e);  // e x f = v
      const Bounds one = Bounds::of_triangle(V3::Zero(), e, f, V3::Zero(), e, f);
      b = k == 0 ? one : Bounds::merged(b, one);
    }
    V3 a;
    if (trial % 2 == 0) {
      CAPTURE(trial);
      CHECK(b.axis(a));
    } else {
      refused_wide += !b.axis(a);
    }
  }
  CHECK(refused_wide > 0);
}

TEST_CASE("NormalBounds: a normal that is not finite leaves no axis") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {nan, inf}) {
    const Bounds b = Bounds::of_triangle(V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 0),
                                         V3(bad, 0, 0), V3(0, 1, 0));
    V3 a;
    CHECK_FALSE(b.axis(a));
    // Merged with a good triangle, still none.
    const Bounds good = Bounds::of_triangle(V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), V3(0, 0, 0),
                                            V3(1, 0, 0), V3(0, 1, 0));
    CHECK(good.axis(a));
    CHECK_FALSE(Bounds::merged(good, b).axis(a));
  }
}
