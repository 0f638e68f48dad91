// contact/ccd/additive_ccd.hpp: point-triangle and edge-edge continuous collision detection against
// an oracle written independently of the code under test. The oracle samples the distance at N
// uniform times (its own point-triangle distance: projection on the plane when the foot is
// inside, else the nearest edge; its own segment-segment distance: golden-section search over
// one segment's parameter of the distance to the other segment, a convex function). With L the
// sum over both elements of the largest corner displacement (a bound of |d'(t)|), the smallest
// sample is an upper bound of the minimum distance over [0, 1] and that minus L / (2 N) a lower
// bound. A CCD must report a hit whenever the upper bound is below min_distance; a hit when the
// lower bound is above it is a false positive, allowed but counted.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <massspring/contact/ccd/additive_ccd.hpp>
#include <random>

#include "support/alloc_counter.hpp"

namespace {

using AccdV3 = massspring::Vector3<double>;

AccdV3 accd_v(double x, double y, double z) { return AccdV3(x, y, z); }

// A query: corners x[0..3] (point, triangle; or edge a, edge b) with displacements dx.
struct AccdCase {
  bool edge_edge = false;
  AccdV3 x[4], dx[4];
  double min_distance = 0;
};

double accd_point_segment(const AccdV3& p, const AccdV3& a, const AccdV3& b) {
  const AccdV3 e = b - a;
  const double ee = e.dot(e);
  const double u = ee > 0 ? std::clamp((p - a).dot(e) / ee, 0.0, 1.0) : 0.0;
  return (p - (a + u * e)).norm();
}

double accd_oracle_point_triangle(const AccdV3& p, const AccdV3& a, const AccdV3& b,
                                  const AccdV3& c) {
  const AccdV3 n = (b - a).cross(c - a);
  const double nn = n.dot(n);
  if (nn > 0) {
    const AccdV3 q = p - ((p - a).dot(n) / nn) * n;  // foot on the plane
    if ((b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
        (a - c).cross(q - c).dot(n) >= 0)
      return (p - q).norm();
  }
  return std::min(
      {accd_point_segment(p, a, b), accd_point_segment(p, b, c), accd_point_segment(p, c, a)});
}

double accd_oracle_edge_edge(const AccdV3& a0, const AccdV3& a1, const AccdV3& b0,
                             const AccdV3& b1) {
  const auto f = [&](double s) { return accd_point_segment(a0 + s * (a1 - a0), b0, b1); };
  const double r = 0.5 * (std::sqrt(5.0) - 1);
  double lo = 0, hi = 1, x1 = hi - r, x2 = r, f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < 80; ++k) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1, x1 = hi - r * (hi - lo), f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2, x2 = lo + r * (hi - lo), f2 = f(x2);
    }
  }
  return std::min({f1, f2, f(0.0), f(1.0)});
}

double accd_oracle_distance(const AccdCase& q, double t) {
  AccdV3 y[4];
  for (int i = 0; i < 4; ++i) y[i] = q.x[i] + t * q.dx[i];
  return q.edge_edge ? accd_oracle_edge_edge(y[0], y[1], y[2], y[3])
                     : accd_oracle_point_triangle(y[0], y[1], y[2], y[3]);
}

struct AccdBounds {
  double lower = 0, upper = 0;
};

AccdBounds accd_oracle_bounds(const AccdCase& q, int samples) {
  double upper = accd_oracle_distance(q, 0);
  for (int k = 1; k <= samples; ++k)
    upper = std::min(upper, accd_oracle_distance(q, double(k) / samples));
  double lip_first = 0, lip_second = 0;
  for (int i = 0; i < 4; ++i) {
    double& own = (i < (q.edge_edge ? 2 : 1)) ? lip_first : lip_second;
    own = std::max(own, q.dx[i].norm());
  }
  return {upper - (lip_first + lip_second) / (2.0 * samples), upper};
}

// The query rounded to Scalar and back, so the oracle sees exactly what the CCD sees.
template <class Scalar>
AccdCase accd_rounded(const AccdCase& q) {
  AccdCase r = q;
  for (int i = 0; i < 4; ++i) {
    r.x[i] = q.x[i].cast<Scalar>().template cast<double>();
    r.dx[i] = q.dx[i].cast<Scalar>().template cast<double>();
  }
  r.min_distance = double(Scalar(q.min_distance));
  return r;
}

template <class Scalar>
massspring::contact::CcdResult<Scalar> accd_run(const AccdCase& q, int max_iterations = 64) {
  using V = massspring::Vector3<Scalar>;
  V x[4], dx[4];
  for (int i = 0; i < 4; ++i) x[i] = q.x[i].cast<Scalar>(), dx[i] = q.dx[i].cast<Scalar>();
  const Scalar xi = Scalar(q.min_distance);
  return q.edge_edge ? massspring::contact::edge_edge_ccd<Scalar>(
                           x[0], x[1], x[2], x[3], dx[0], dx[1], dx[2], dx[3], xi, max_iterations)
                     : massspring::contact::point_triangle_ccd<Scalar>(
                           x[0], x[1], x[2], x[3], dx[0], dx[1], dx[2], dx[3], xi, max_iterations);
}

// The result's own contract: toi in [0, 1]; no hit means toi = 1; on a hit, the distance at toi
// and at every sample before it is >= min_distance (1e-12 of the coordinates' size below it
// allowed for the oracle's rounding).
template <class Scalar>
void accd_check_result(const AccdCase& q, const massspring::contact::CcdResult<Scalar>& r) {
  const double toi = double(r.toi);
  CHECK(toi >= 0);
  CHECK(toi <= 1);
  if (!r.hit) {
    CHECK(toi == 1);
    return;
  }
  double size = 1;
  for (int i = 0; i < 4; ++i) size = std::max({size, q.x[i].norm() + q.dx[i].norm()});
  const double floor = q.min_distance - 1e-12 * size;
  if (toi > 0) CHECK(accd_oracle_distance(q, toi) >= floor);
  for (int k = 0; k < 64 && k * toi / 64 < toi; ++k)
    CHECK(accd_oracle_distance(q, k * toi / 64) >= floor);
}

enum class AccdExpect { hit, miss, either };

// Runs a catalogue case in double and float, checks the contract and the expected answer.
void accd_check_case(const AccdCase& exact, AccdExpect expect) {
  const auto d = accd_run<double>(exact);
  accd_check_result(exact, d);
  const AccdCase rounded = accd_rounded<float>(exact);
  const auto f = accd_run<float>(rounded);
  accd_check_result(rounded, f);
  if (expect == AccdExpect::hit) {
    CHECK(d.hit);
    CHECK(f.hit);
  } else if (expect == AccdExpect::miss) {
    CHECK_FALSE(d.hit);
    CHECK_FALSE(f.hit);
  }
}

AccdCase accd_point_triangle(const AccdV3& p, const AccdV3& dp, double min_distance) {
  AccdCase q;
  q.x[0] = p, q.x[1] = accd_v(0, 0, 0), q.x[2] = accd_v(1, 0, 0), q.x[3] = accd_v(0, 1, 0);
  q.dx[0] = dp, q.dx[1] = q.dx[2] = q.dx[3] = AccdV3::Zero();
  q.min_distance = min_distance;
  return q;
}

AccdCase accd_edge_edge(const AccdV3& a0, const AccdV3& a1, const AccdV3& b0, const AccdV3& b1,
                        const AccdV3& db, double min_distance) {
  AccdCase q;
  q.edge_edge = true;
  q.x[0] = a0, q.x[1] = a1, q.x[2] = b0, q.x[3] = b1;
  q.dx[0] = q.dx[1] = AccdV3::Zero();
  q.dx[2] = q.dx[3] = db;
  q.min_distance = min_distance;
  return q;
}

}  // namespace

TEST_CASE("point_triangle_ccd: the degenerate catalogue") {
  const double xi = 0.01;
  // a vertex falling onto the middle of an edge (reaches it at t = 0.5)
  accd_check_case(accd_point_triangle(accd_v(0.5, 0, 1), accd_v(0, 0, -2), xi), AccdExpect::hit);
  // a vertex moving in the triangle's plane onto an edge, and into the triangle
  accd_check_case(accd_point_triangle(accd_v(0.5, -1, 0), accd_v(0, 2, 0), xi), AccdExpect::hit);
  accd_check_case(accd_point_triangle(accd_v(-1, 0.25, 0), accd_v(2, 0, 0), xi), AccdExpect::hit);
  // a vertex hitting a triangle corner head on
  accd_check_case(accd_point_triangle(accd_v(-1, -1, 1), accd_v(2, 2, -2), xi), AccdExpect::hit);
  // the triangle moving onto a still vertex
  AccdCase moving = accd_point_triangle(accd_v(0.2, 0.2, 0.5), AccdV3::Zero(), xi);
  moving.dx[1] = moving.dx[2] = moving.dx[3] = accd_v(0, 0, 1);
  accd_check_case(moving, AccdExpect::hit);
  // the pair moving together, however far: no hit, at no cost
  AccdCase together = accd_point_triangle(accd_v(0.2, 0.2, 0.5), accd_v(5, -3, 2), xi);
  together.dx[1] = together.dx[2] = together.dx[3] = together.dx[0];
  accd_check_case(together, AccdExpect::miss);
  CHECK(accd_run<double>(together).iterations == 0);
  // separating
  accd_check_case(accd_point_triangle(accd_v(0.2, 0.2, 0.5), accd_v(0.1, 0, 1), xi),
                  AccdExpect::miss);
  // passing over the face at a height of min_distance minus 1e-9: must hit
  accd_check_case(accd_point_triangle(accd_v(-1, 0.25, xi - 1e-9), accd_v(3, 0, 0), xi),
                  AccdExpect::hit);
  // passing over the face just above min_distance: either answer, the toi valid
  accd_check_case(accd_point_triangle(accd_v(-1, 0.25, xi + 1e-9), accd_v(3, 0, 0), xi),
                  AccdExpect::either);
  accd_check_case(accd_point_triangle(accd_v(-1, 0.25, 2 * xi), accd_v(3, 0, 0), xi),
                  AccdExpect::either);
  // grazing the corner (1, 0, 0) from above
  accd_check_case(accd_point_triangle(accd_v(1, -1, xi - 1e-9), accd_v(0, 2, 0), xi),
                  AccdExpect::hit);
  accd_check_case(accd_point_triangle(accd_v(1.5, -1, 0), accd_v(0, 2, 0), xi), AccdExpect::miss);
  // starting inside min_distance: hit at toi 0, whatever the motion
  const auto inside =
      accd_run<double>(accd_point_triangle(accd_v(0.2, 0.2, 0.005), accd_v(0, 0, 1), xi));
  CHECK(inside.hit);
  CHECK(inside.toi == 0);
  CHECK(inside.iterations == 0);
  // min_distance 0: the exact crossing
  accd_check_case(accd_point_triangle(accd_v(0.2, 0.2, 1), accd_v(0, 0, -2), 0), AccdExpect::hit);
  // a degenerate (zero-area) triangle swept by a vertex
  AccdCase flat = accd_point_triangle(accd_v(0.5, 1, 0.001), accd_v(0, -2, 0), xi);
  flat.x[3] = accd_v(2, 0, 0);
  accd_check_case(flat, AccdExpect::hit);
  // NaN: a hit at 0
  const auto nan =
      accd_run<double>(accd_point_triangle(accd_v(std::nan(""), 0, 1), AccdV3::Zero(), xi));
  CHECK(nan.hit);
  CHECK(nan.toi == 0);
}

TEST_CASE("edge_edge_ccd: the degenerate catalogue") {
  const double xi = 0.01;
  const AccdV3 a0 = accd_v(0, 0, 0), a1 = accd_v(1, 0, 0);
  // parallel edges sliding onto each other, straight and sideways
  accd_check_case(accd_edge_edge(a0, a1, accd_v(0, 1, 0), accd_v(1, 1, 0), accd_v(0, -2, 0), xi),
                  AccdExpect::hit);
  accd_check_case(
      accd_edge_edge(a0, a1, accd_v(1.5, 1, 0), accd_v(2.5, 1, 0), accd_v(-1, -2, 0), xi),
      AccdExpect::hit);
  // collinear edges closing end to end
  accd_check_case(accd_edge_edge(a0, a1, accd_v(2, 0, 0), accd_v(3, 0, 0), accd_v(-1.5, 0, 0), xi),
                  AccdExpect::hit);
  // crossing edges passing through each other
  accd_check_case(
      accd_edge_edge(a0, a1, accd_v(0.5, -0.5, 1), accd_v(0.5, 0.5, 1), accd_v(0, 0, -3), xi),
      AccdExpect::hit);
  // moving together, separating
  AccdCase together =
      accd_edge_edge(a0, a1, accd_v(0.5, -0.5, 1), accd_v(0.5, 0.5, 1), accd_v(3, 1, -4), xi);
  together.dx[0] = together.dx[1] = together.dx[2];
  accd_check_case(together, AccdExpect::miss);
  CHECK(accd_run<double>(together).iterations == 0);
  accd_check_case(
      accd_edge_edge(a0, a1, accd_v(0.5, -0.5, 1), accd_v(0.5, 0.5, 1), accd_v(0, 0.5, 1), xi),
      AccdExpect::miss);
  // passing over at min_distance minus 1e-9 (must hit) and just above it (either)
  accd_check_case(accd_edge_edge(a0, a1, accd_v(-1, -0.5, xi - 1e-9), accd_v(-1, 0.5, xi - 1e-9),
                                 accd_v(3, 0, 0), xi),
                  AccdExpect::hit);
  accd_check_case(accd_edge_edge(a0, a1, accd_v(-1, -0.5, xi + 1e-9), accd_v(-1, 0.5, xi + 1e-9),
                                 accd_v(3, 0, 0), xi),
                  AccdExpect::either);
  // an endpoint touching the other edge's endpoint only at t = 1
  accd_check_case(accd_edge_edge(a0, a1, accd_v(2, 0, 1), accd_v(2, 0, 2), accd_v(-1, 0, -1), xi),
                  AccdExpect::hit);
  // a zero-length edge (a point) swept through a segment
  accd_check_case(
      accd_edge_edge(a0, a1, accd_v(0.5, 1, 0), accd_v(0.5, 1, 0), accd_v(0, -2, 0), xi),
      AccdExpect::hit);
  // start inside min_distance
  const auto inside = accd_run<double>(
      accd_edge_edge(a0, a1, accd_v(0.5, 0, 0.001), accd_v(0.5, 1, 0.001), accd_v(0, 0, 1), xi));
  CHECK(inside.hit);
  CHECK(inside.toi == 0);
}

TEST_CASE("additive CCD: no heap allocation") {
  const AccdCase pt = accd_point_triangle(accd_v(0.05, 0.25, 0.011), accd_v(0.5, 0, 0), 0.01);
  const AccdCase ee = accd_edge_edge(accd_v(0, 0, 0), accd_v(1, 0, 0), accd_v(0.5, -0.5, 1),
                                     accd_v(0.5, 0.5, 1), accd_v(0, 0, -3), 0.01);
  massspring::test::CountAllocations allocations;
  const auto a = accd_run<double>(pt);
  const auto b = accd_run<float>(ee);
  CHECK(allocations.count() == 0);
  CHECK(a.iterations > 0);
  CHECK(b.iterations > 0);
}

TEST_CASE("additive CCD: max_iterations spent is a conservative hit") {
  // sliding over the face at a constant gap of 1e-3 needs about 500 steps of 0.9 gap / L
  const AccdCase q = accd_point_triangle(accd_v(0.05, 0.25, 0.011), accd_v(0.5, 0, 0), 0.01);
  const auto full = accd_run<double>(q);
  CHECK(full.hit);
  CHECK(full.iterations == 64);
  const auto capped = accd_run<double>(q, 3);
  CHECK(capped.hit);
  CHECK(capped.iterations == 3);
  CHECK(capped.toi > 0);
  accd_check_result(q, capped);
  const auto zero = accd_run<double>(q, 0);
  CHECK(zero.hit);
  CHECK(zero.toi == 0);
}

namespace {

// Random queries, min_distance up to 0.05, half point-triangle, half edge-edge. Half are
// separate elements of size about 1 moving at random (mostly misses); half meet: at a random time
// t* a random point of one element is at a random offset of length up to 0.1 from a random point
// of the other (so the minimum distance is at most that), with random displacements around it.
// Every result is checked for its contract; misses, false positives and iterations counted.
struct AccdFuzzCounts {
  int queries = 0, must_hit = 0, must_miss = 0, missed = 0, false_positives = 0;
  long iterations = 0;
};

template <class Scalar>
AccdFuzzCounts accd_fuzz(unsigned seed, int queries) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1), positive(0, 1);
  const auto random_vector = [&](double scale) {
    return accd_v(scale * unit(rng), scale * unit(rng), scale * unit(rng));
  };
  AccdFuzzCounts counts;
  for (int k = 0; k < queries; ++k) {
    AccdCase q;
    q.edge_edge = (k % 2) == 1;
    const int first = q.edge_edge ? 2 : 1;
    const double speed = 2 * positive(rng) * positive(rng);
    for (int i = 0; i < 4; ++i) q.dx[i] = random_vector(speed);
    if (k % 5 == 0)  // a fifth move almost rigidly
      for (int i = 1; i < 4; ++i) q.dx[i] = q.dx[0] + random_vector(0.01 * speed);
    if ((k / 2) % 2 == 0) {
      const AccdV3 offset = random_vector(0.6);
      for (int i = 0; i < 4; ++i) q.x[i] = random_vector(0.5) + (i < first ? offset : -offset);
    } else {
      // the configuration at t*: both elements random, then the second shifted so that its
      // random point lands at a random offset from the first's random point
      AccdV3 y[4];
      for (int i = 0; i < 4; ++i) y[i] = random_vector(0.5);
      const auto random_point = [&](int begin, int end) {
        double w[3] = {positive(rng), positive(rng), positive(rng)}, sum = 0;
        for (int i = begin; i < end; ++i) sum += w[i - begin];
        AccdV3 r = AccdV3::Zero();
        for (int i = begin; i < end; ++i) r += (w[i - begin] / sum) * y[i];
        return r;
      };
      const AccdV3 on_first = random_point(0, first), on_second = random_point(first, 4);
      const AccdV3 shift =
          on_first - on_second + 0.1 * positive(rng) * random_vector(1).normalized();
      for (int i = first; i < 4; ++i) y[i] += shift;
      const double t_meet = positive(rng);
      for (int i = 0; i < 4; ++i) q.x[i] = y[i] - t_meet * q.dx[i];
    }
    q.min_distance = 0.05 * positive(rng);
    q = accd_rounded<Scalar>(q);
    const auto r = accd_run<Scalar>(q);
    accd_check_result(q, r);
    const AccdBounds b = accd_oracle_bounds(q, 256);
    ++counts.queries;
    counts.iterations += r.iterations;
    if (b.upper < q.min_distance) {
      ++counts.must_hit;
      if (!r.hit) ++counts.missed;
    }
    if (b.lower > q.min_distance) {
      ++counts.must_miss;
      if (r.hit) ++counts.false_positives;
    }
  }
  return counts;
}

template <class Scalar>
void accd_fuzz_check(unsigned seed) {
  const AccdFuzzCounts c = accd_fuzz<Scalar>(seed, 4000);
  const double fp_rate = double(c.false_positives) / c.must_miss;
  const double mean_iterations = double(c.iterations) / c.queries;
  MESSAGE("must hit " << c.must_hit << ", must miss " << c.must_miss << ", missed " << c.missed
                      << ", false positives " << c.false_positives << " (" << fp_rate
                      << "), mean iterations " << mean_iterations);
  CHECK(c.missed == 0);
  // both classes well represented, so a CCD that always (or never) says hit fails
  CHECK(c.must_hit > c.queries / 5);
  CHECK(c.must_miss > c.queries / 5);
  CHECK(fp_rate < 0.05);
}

}  // namespace

TEST_CASE("additive CCD: random queries against the sampled oracle, double") {
  accd_fuzz_check<double>(12345u);
}

TEST_CASE("additive CCD: random queries against the sampled oracle, float") {
  accd_fuzz_check<float>(67890u);
}
