// contact/distance/bounding_balls.hpp: the bounds never reject a pair that comes within the
// distance (checked against the exact point-triangle and edge-edge distances, at rest and at 401
// times along random straight-line motions), and do reject pairs well apart.
#include <doctest/doctest.h>

#include <array>
#include <massspring/contact/distance/bounding_balls.hpp>
#include <massspring/contact/distance/edge_edge.hpp>
#include <massspring/contact/distance/point_triangle.hpp>
#include <random>

namespace {

using BbV3 = massspring::Vector3<double>;
using BbPoints = std::array<BbV3, 4>;

// The exact distance between the hulls of x[0..split) and x[split..4).
double bb_exact(const BbPoints& x, int split) {
  if (split == 1)
    return std::sqrt(massspring::contact::point_triangle_squared_distance(x[0], x[1], x[2], x[3]));
  return std::sqrt(
      massspring::contact::edge_edge_distance(x[0], x[1], x[2], x[3]).squared_distance);
}

BbPoints bb_random(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  BbPoints x;
  for (BbV3& p : x) p = BbV3(u(rng), u(rng), u(rng));
  return x;
}

}  // namespace

TEST_CASE("balls_within never rejects a pair within the distance, and rejects far pairs") {
  namespace contact = massspring::contact;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> gap(0.0, 0.3);
  int rejected = 0;
  for (int split : {1, 2}) {
    for (int trial = 0; trial < 20000; ++trial) {
      const BbPoints x = bb_random(rng, 1.0);
      const double d = gap(rng);
      if (!contact::balls_within(x, split, d)) {
        ++rejected;
        CHECK(bb_exact(x, split) >= d);
      }
    }
    // Two elements of size 0.1 whose centres are 1 apart: rejected at 0.5.
    BbPoints far = {BbV3(0, 0, 0), BbV3(1, 0, 0), BbV3(1.1, 0, 0), BbV3(1, 0.1, 0)};
    if (split == 2) far = {BbV3(0, 0, 0), BbV3(0.1, 0, 0), BbV3(1, 0, 0), BbV3(1, 0.1, 0)};
    CHECK_FALSE(contact::balls_within(far, split, 0.5));
    CHECK(contact::balls_within(far, split, 1.0));
  }
  CHECK(rejected > 1000);  // the test is not vacuous
}

TEST_CASE("swept_balls_within never rejects a motion that comes within the distance") {
  namespace contact = massspring::contact;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> gap(0.0, 0.3);
  int rejected = 0;
  for (int split : {1, 2}) {
    for (int trial = 0; trial < 3000; ++trial) {
      const BbPoints x0 = bb_random(rng, 1.0);
      BbPoints x1 = bb_random(rng, 0.5);
      for (std::size_t k = 0; k < 4; ++k) x1[k] += x0[k];
      const double d = gap(rng);
      if (contact::swept_balls_within(x0, x1, split, d)) continue;
      ++rejected;
      for (int s = 0; s <= 400; ++s) {
        const double t = s / 400.0;
        BbPoints xt;
        for (std::size_t k = 0; k < 4; ++k) xt[k] = (1 - t) * x0[k] + t * x1[k];
        REQUIRE(bb_exact(xt, split) >= d);
      }
    }
    // Two small elements that pass each other about 1 apart: rejected at 0.5, not at 1.
    BbPoints a0 = {BbV3(-1, 0, 0), BbV3(1, 1, 0), BbV3(1.05, 1, 0), BbV3(1, 1.05, 0)};
    BbPoints a1 = {BbV3(1, 0, 0), BbV3(-1, 1, 0), BbV3(-0.95, 1, 0), BbV3(-1, 1.05, 0)};
    if (split == 2) {
      a0 = {BbV3(-1, 0, 0), BbV3(-1, 0.05, 0), BbV3(1, 1, 0), BbV3(1, 1.05, 0)};
      a1 = {BbV3(1, 0, 0), BbV3(1, 0.05, 0), BbV3(-1, 1, 0), BbV3(-1, 1.05, 0)};
    }
    CHECK_FALSE(contact::swept_balls_within(a0, a1, split, 0.5));
    CHECK(contact::swept_balls_within(a0, a1, split, 1.0));
  }
  CHECK(rejected > 500);
}
