// contact/distance/edge_edge.hpp: the closest points of two segments against a brute-force oracle
// (a dense grid over (s, t) refined by shrinking grids around the best node; the squared distance
// is convex on the unit square, so the refinement converges to the global minimum), on random
// segments and on a catalogue of degenerate ones; plus closed forms for the catalogue.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <massspring/contact/distance/edge_edge.hpp>
#include <random>

namespace {

using EeV3 = massspring::Vector3<double>;

EeV3 ee_v(double x, double y, double z) { return EeV3(x, y, z); }

double ee_squared_at(const EeV3& a0, const EeV3& a1, const EeV3& b0, const EeV3& b1, double s,
                     double t) {
  return ((a0 + s * (a1 - a0)) - (b0 + t * (b1 - b0))).squaredNorm();
}

// Minimum of a convex function of one variable on [0, 1] by golden-section search (200 rounds,
// far below double resolution), the ends included.
template <class F>
double ee_golden_minimum(const F& f) {
  const double r = 0.5 * (std::sqrt(5.0) - 1);
  double lo = 0, hi = 1, x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < 200; ++k) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = f(x2);
    }
  }
  return std::min({f1, f2, f(0.0), f(1.0)});
}

// Minimum of the squared distance over the unit square: a 101 x 101 grid, refined by nested
// golden-section searches, min over s of (min over t). The squared distance is jointly convex in
// (s, t), so the inner minimum is a convex function of s and the nested search converges to the
// global minimum however thin the valley (nearly parallel segments).
double ee_brute_force_squared(const EeV3& a0, const EeV3& a1, const EeV3& b0, const EeV3& b1) {
  double best = ee_squared_at(a0, a1, b0, b1, 0, 0);
  const int n = 100;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      best = std::min(best, ee_squared_at(a0, a1, b0, b1, double(i) / n, double(j) / n));
  const auto over_t = [&](double s) {
    return ee_golden_minimum([&](double t) { return ee_squared_at(a0, a1, b0, b1, s, t); });
  };
  return std::min(best, ee_golden_minimum(over_t));
}

// The result is a pair of points of the segments, its squared distance is that pair's, and it
// matches the oracle to 1e-12 of the segments' scale squared.
template <class Scalar>
void ee_check_against_oracle(const EeV3& a0, const EeV3& a1, const EeV3& b0, const EeV3& b1,
                             double tolerance) {
  using V = massspring::Vector3<Scalar>;
  const V fa0 = a0.cast<Scalar>(), fa1 = a1.cast<Scalar>(), fb0 = b0.cast<Scalar>(),
          fb1 = b1.cast<Scalar>();
  const auto r = massspring::contact::edge_edge_distance<Scalar>(fa0, fa1, fb0, fb1);
  const EeV3 ca0 = fa0.template cast<double>(), ca1 = fa1.template cast<double>(),
             cb0 = fb0.template cast<double>(), cb1 = fb1.template cast<double>();
  const double scale2 =
      std::max({ca0.squaredNorm(), ca1.squaredNorm(), cb0.squaredNorm(), cb1.squaredNorm(), 1.0});
  CHECK(r.s >= 0);
  CHECK(r.s <= 1);
  CHECK(r.t >= 0);
  CHECK(r.t <= 1);
  const double own = ee_squared_at(ca0, ca1, cb0, cb1, double(r.s), double(r.t));
  CHECK(std::abs(own - double(r.squared_distance)) <= tolerance * scale2);
  const double oracle = ee_brute_force_squared(ca0, ca1, cb0, cb1);
  CHECK(std::abs(double(r.squared_distance) - oracle) <= tolerance * scale2);
}

}  // namespace

TEST_CASE("edge_edge_distance: closed forms of the degenerate catalogue") {
  namespace contact = massspring::contact;
  // crossing: x axis and a segment along y at height 1 crossing above x = 0.5
  auto r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(1, 0, 0), ee_v(0.5, -1, 1),
                                               ee_v(0.5, 1, 1));
  CHECK(r.s == doctest::Approx(0.5));
  CHECK(r.t == doctest::Approx(0.5));
  CHECK(r.squared_distance == doctest::Approx(1));
  // intersecting: distance 0 at the crossing
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(2, 0, 0), ee_v(0.5, -1, 0),
                                          ee_v(0.5, 3, 0));
  CHECK(r.s == doctest::Approx(0.25));
  CHECK(r.t == doctest::Approx(0.25));
  CHECK(r.squared_distance == doctest::Approx(0).epsilon(1e-15));
  // parallel overlapping at distance 2: any pair in the overlap, at distance exactly 2
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(2, 0, 0), ee_v(1, 2, 0),
                                          ee_v(3, 2, 0));
  CHECK(r.squared_distance == doctest::Approx(4));
  CHECK(r.s >= 0.5 - 1e-12);
  CHECK(std::abs((r.s * 2) - (1 + r.t * 2)) < 1e-12);  // the two points share their x
  // parallel disjoint: end to end, (2,0,0) to (3,1,0)
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(2, 0, 0), ee_v(3, 1, 0),
                                          ee_v(5, 1, 0));
  CHECK(r.s == 1);
  CHECK(r.t == 0);
  CHECK(r.squared_distance == doctest::Approx(2));
  // antiparallel disjoint: b runs backwards, its end b1 = (3,1,0) is the nearer
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(2, 0, 0), ee_v(5, 1, 0),
                                          ee_v(3, 1, 0));
  CHECK(r.s == 1);
  CHECK(r.t == 1);
  CHECK(r.squared_distance == doctest::Approx(2));
  // collinear overlapping: distance 0
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(2, 0, 0), ee_v(1, 0, 0),
                                          ee_v(4, 0, 0));
  CHECK(r.squared_distance == 0);
  // collinear disjoint: gap of 1 between (2,0,0) and (3,0,0)
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(2, 0, 0), ee_v(3, 0, 0),
                                          ee_v(4, 0, 0));
  CHECK(r.s == 1);
  CHECK(r.t == 0);
  CHECK(r.squared_distance == doctest::Approx(1));
  // both zero length: the distance between the points
  r = contact::edge_edge_distance<double>(ee_v(1, 1, 1), ee_v(1, 1, 1), ee_v(4, 5, 1),
                                          ee_v(4, 5, 1));
  CHECK(r.squared_distance == doctest::Approx(25));
  // one zero length: point (1, 3, 0) against the x axis segment [0, 2]: foot at s = 0.5
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(2, 0, 0), ee_v(1, 3, 0),
                                          ee_v(1, 3, 0));
  CHECK(r.s == doctest::Approx(0.5));
  CHECK(r.squared_distance == doctest::Approx(9));
  r = contact::edge_edge_distance<double>(ee_v(1, 3, 0), ee_v(1, 3, 0), ee_v(0, 0, 0),
                                          ee_v(2, 0, 0));
  CHECK(r.t == doctest::Approx(0.5));
  CHECK(r.squared_distance == doctest::Approx(9));
  // touching at an endpoint: a1 = b0
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(1, 0, 0), ee_v(1, 0, 0),
                                          ee_v(1, 1, 1));
  CHECK(r.s == 1);
  CHECK(r.t == 0);
  CHECK(r.squared_distance == 0);
  // T: an endpoint of b touches the interior of a
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(2, 0, 0), ee_v(0.5, 0, 0),
                                          ee_v(0.5, 0, 3));
  CHECK(r.s == doctest::Approx(0.25));
  CHECK(r.t == 0);
  CHECK(r.squared_distance == 0);
  // skew lines whose closest points lie outside both segments: endpoint to endpoint
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(1, 0, 0), ee_v(3, 2, 1),
                                          ee_v(3, 4, 1));
  CHECK(r.s == 1);
  CHECK(r.t == 0);
  CHECK(r.squared_distance == doctest::Approx(4 + 4 + 1));
  // nearly parallel (angle 1e-12) with the closest points inside both: x axis against a segment
  // at y = 1e-3 whose z crosses 0 at x = 0.5
  r = contact::edge_edge_distance<double>(ee_v(0, 0, 0), ee_v(1, 0, 0), ee_v(-0.5, 1e-3, -1e-12),
                                          ee_v(1.5, 1e-3, 1e-12));
  CHECK(r.squared_distance == doctest::Approx(1e-6).epsilon(1e-9));
  CHECK(r.squared_distance >= 1e-6 * (1 - 1e-12));
  // NaN in: NaN out
  r = contact::edge_edge_distance<double>(ee_v(std::nan(""), 0, 0), ee_v(1, 0, 0), ee_v(0, 1, 0),
                                          ee_v(1, 1, 0));
  CHECK(std::isnan(r.squared_distance));
}

TEST_CASE("edge_edge_distance: the degenerate catalogue against the brute-force oracle") {
  const EeV3 o = ee_v(0.3, -0.2, 0.7);
  const EeV3 u = ee_v(1, 2, -0.5), w = ee_v(-0.4, 0.1, 1.3);
  const EeV3 cases[][4] = {
      {o, o + u, o + w, o + w + u},                      // parallel, offset
      {o, o + u, o + w, o + w - 2 * u},                  // antiparallel
      {o, o + u, o + 0.5 * u, o + 1.5 * u},              // collinear overlapping
      {o, o + u, o + 2 * u, o + 3 * u},                  // collinear disjoint
      {o, o, o + w, o + w + u},                          // zero length a
      {o, o + u, o + w, o + w},                          // zero length b
      {o, o, o + w, o + w},                              // both zero length
      {o, o, o, o},                                      // all one point
      {o, o + u, o + 0.5 * u - w, o + 0.5 * u + w},      // crossing
      {o, o + u, o + u, o + u + w},                      // touching at an endpoint
      {o, o + u, o + w, o + w + u + 1e-9 * w.cross(u)},  // nearly parallel
      {o, o + u, o + w + 0.3 * u, o + w + 0.3 * u + 1e-7 * u + 1e-9 * w},  // short, parallel-ish
  };
  for (const auto& c : cases) {
    ee_check_against_oracle<double>(c[0], c[1], c[2], c[3], 1e-12);
    ee_check_against_oracle<double>(c[2], c[3], c[0], c[1], 1e-12);
    ee_check_against_oracle<float>(c[0], c[1], c[2], c[3], 1e-5);
  }
}

TEST_CASE("edge_edge_distance: random segments against the brute-force oracle") {
  std::mt19937 rng(20240611u);
  std::uniform_real_distribution<double> coord(-1, 1);
  const auto random_point = [&] { return ee_v(coord(rng), coord(rng), coord(rng)); };
  for (int k = 0; k < 300; ++k) {
    const EeV3 a0 = random_point(), b0 = random_point();
    // a third of the pairs are short segments, another third nearly parallel ones
    EeV3 a1 = random_point(), b1 = random_point();
    if (k % 3 == 1) {
      a1 = a0 + 0.01 * random_point();
      b1 = b0 + 0.01 * random_point();
    } else if (k % 3 == 2) {
      b1 = b0 + (a1 - a0) * (0.5 + 0.5 * std::abs(coord(rng))) + 1e-6 * random_point();
    }
    ee_check_against_oracle<double>(a0, a1, b0, b1, 1e-12);
    ee_check_against_oracle<float>(a0, a1, b0, b1, 1e-5);
  }
}
