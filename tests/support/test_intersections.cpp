// tests/support/intersections.hpp, the oracle of the contact tests: hand-made crossing and
// non-crossing cases decided exactly, invariance under rigid motions, and flat, stacked and folded
// grids whose separation is known in closed form.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "support/intersections.hpp"

namespace {

using massspring::Edges;
using massspring::Points;
using massspring::Triangles;
using massspring::test::count_crossings;
using massspring::test::count_segment_crossings;
using massspring::test::min_separation;
using massspring::test::triangle_edges;
using V3 = Eigen::Vector3d;

// The triangle (0,0,0), (1,0,0), (0,1,0) as points 0-2, and one edge (3, 4) from p to q.
int crossings_of(const V3& p, const V3& q) {
  Points<double> x(5, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0, p.transpose(), q.transpose();
  Triangles t(1, 3);
  t << 0, 1, 2;
  Edges e(1, 2);
  e << 3, 4;
  return count_crossings(x, t, e);
}

// A grid of columns x rows points in the plane y = height, point (r, c) at (c dx, height, r dz),
// one diagonal per cell: triangles (a, b, cc) and (a, cc, d) with a = (r, c), b = (r, c + 1),
// cc = (r + 1, c + 1), d = (r + 1, c). Indices start at `first`.
struct Grid {
  Points<double> x;
  Triangles triangles;
};

Grid grid(int columns, int rows, double dx, double dz, double height = 0) {
  Grid g;
  g.x.resize(columns * rows, 3);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) g.x.row(r * columns + c) << c * dx, height, r * dz;
  g.triangles.resize(2 * (columns - 1) * (rows - 1), 3);
  int t = 0;
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < columns; ++c) {
      const int a = r * columns + c, b = a + 1, cc = a + columns + 1, d = a + columns;
      g.triangles.row(t++) << a, b, cc;
      g.triangles.row(t++) << a, cc, d;
    }
  return g;
}

// Two meshes as one (the second's indices shifted).
Grid join(const Grid& l, const Grid& r) {
  Grid g;
  g.x.resize(l.x.rows() + r.x.rows(), 3);
  g.x << l.x, r.x;
  g.triangles.resize(l.triangles.rows() + r.triangles.rows(), 3);
  g.triangles << l.triangles, (r.triangles.array() + int(l.x.rows())).matrix();
  return g;
}

// x rotated by a random rotation and shifted by a random translation (the same for every point).
Points<double> random_rigid_motion(const Points<double>& x, std::mt19937& rng) {
  std::normal_distribution<double> n(0, 1);
  const Eigen::Quaterniond q = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
  const Eigen::RowVector3d shift(n(rng), n(rng), n(rng));
  Points<double> y(x.rows(), 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    y.row(i) = (q * V3(x.row(i).transpose())).transpose() + shift;
  return y;
}

}  // namespace

TEST_CASE("intersections: an edge through a triangle's inside, side or corner crosses it") {
  CHECK(crossings_of({0.25, 0.25, -1}, {0.25, 0.25, 1}) == 1);  // through the middle
  CHECK(crossings_of({0.25, 0.25, 1}, {0.25, 0.25, -1}) == 1);  // either direction
  CHECK(crossings_of({0.1, 0.2, -1}, {0.3, 0.1, 2}) == 1);      // slanted
  CHECK(crossings_of({0.5, 0, -1}, {0.5, 0, 1}) == 1);          // through a side
  CHECK(crossings_of({0.5, 0.5, -1}, {0.5, 0.5, 1}) == 1);      // through the hypotenuse
  CHECK(crossings_of({1, 0, -1}, {1, 0, 1}) == 1);              // through a corner
  CHECK(crossings_of({0.25, 0.25, 0}, {0.25, 0.25, 1}) == 1);   // one end on the triangle
}

TEST_CASE("intersections: exact decisions a rounding error away from touching") {
  const double above_half = std::nextafter(0.5, 1.0);  // x + y = 1 + 2^-53 > 1: outside
  CHECK(crossings_of({0.5, above_half, -1}, {0.5, above_half, 1}) == 0);
  CHECK(crossings_of({0.5, 0.5, -1}, {0.5, 0.5, 1}) == 1);
  const double tiny = 1e-80;  // an end just above the plane, the other far above
  CHECK(crossings_of({0.25, 0.25, tiny}, {0.25, 0.25, 1}) == 0);
  CHECK(crossings_of({0.25, 0.25, -tiny}, {0.25, 0.25, 1}) == 1);
  // Through the next doubles on either side of the corner (1, 0, 0), along its side y = 0.
  CHECK(crossings_of({std::nextafter(1.0, 2.0), 0, -1}, {std::nextafter(1.0, 2.0), 0, 1}) == 0);
  CHECK(crossings_of({std::nextafter(1.0, 0.0), 0, -1}, {std::nextafter(1.0, 0.0), 0, 1}) == 1);
}

TEST_CASE("intersections: edges that miss the triangle do not cross it") {
  CHECK(crossings_of({0.1, 0.1, 1e-12}, {0.5, 0.2, 1e-12}) == 0);  // parallel, just above
  CHECK(crossings_of({0.1, 0.1, 0.5}, {0.2, 0.1, 2}) == 0);        // entirely above
  CHECK(crossings_of({0.8, 0.8, -1}, {0.8, 0.8, 1}) == 0);         // through the plane outside
  CHECK(crossings_of({0.25, 0.25, 1}, {0.25, 0.25, 0.5}) == 0);    // its line would cross
}

TEST_CASE("intersections: coplanar segments, by projection onto the triangle's plane") {
  CHECK(crossings_of({0.1, 0.1, 0}, {0.2, 0.2, 0}) == 1);     // inside
  CHECK(crossings_of({-0.5, 0.25, 0}, {0.5, 0.25, 0}) == 1);  // across a side
  CHECK(crossings_of({-1, 0.5, 0}, {2, 0.5, 0}) == 1);        // across two sides
  CHECK(crossings_of({0.5, 0, 0}, {2, 0, 0}) == 1);           // overlapping a side
  CHECK(crossings_of({-1, 2, 0}, {2, -1, 0}) == 1);           // along the hypotenuse's line
  CHECK(crossings_of({2, 2, 0}, {3, 3, 0}) == 0);             // disjoint
  CHECK(crossings_of({2, 0, 0}, {3, 0, 0}) == 0);             // on a side's line, beyond it
  CHECK(crossings_of({0.6, 0.6, 0}, {2, -0.5, 0}) == 0);      // beside the hypotenuse
  // In the plane x + y + z = 1, which is no coordinate plane (every coordinate below is exact).
  Points<double> x(6, 3);
  x << 1, 0, 0, 0, 1, 0, 0, 0, 1, -0.5, 0.75, 0.75, 0.5, 0.25, 0.25, -1, 1, 1;
  Triangles t(1, 3);
  t << 0, 1, 2;
  Edges e(2, 2);
  e << 3, 4, 5, 3;  // into the triangle across the side x = 0; beside it, x < 0
  CHECK(count_crossings(x, t, e) == 1);
}

TEST_CASE("intersections: an edge sharing a point with the triangle is not counted") {
  // Points 0-2 the triangle, 3 below its middle: the edge (0, 3) touches the triangle at 0, and
  // the edge (1, 3) too; neither counts. The edge (3, 4) through the middle does.
  Points<double> x(5, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, -1, 0.25, 0.25, 1;
  Triangles t(1, 3);
  t << 0, 1, 2;
  Edges e(3, 2);
  e << 0, 3, 1, 3, 3, 4;
  CHECK(count_crossings(x, t, e) == 1);
  Edges coplanar(1, 2);  // a side of the triangle itself
  coplanar << 0, 1;
  CHECK(count_crossings(x, t, coplanar) == 0);
}

TEST_CASE("intersections: a degenerate triangle met by a coplanar segment is refused") {
  Points<double> x(5, 3);
  x << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0.5, -1, 0, 0.5, 1, 0;
  Triangles t(1, 3);
  t << 0, 1, 2;
  Edges e(1, 2);
  e << 3, 4;
  CHECK_THROWS_AS(count_crossings(x, t, e), std::invalid_argument);
  e << 3, 5;
  CHECK_THROWS_AS(count_crossings(x, t, e), std::invalid_argument);  // index out of range
}

TEST_CASE("intersections: crossing and separation are invariant under rigid motions") {
  // A horizontal 11 x 11 grid over [0, 1]^2 (h = 0.1) and a vertical strip in the plane
  // z = 0.4321, 9 columns at x = 0.013 + 0.1 k, y = +-0.05, one diagonal per cell. By hand:
  // the strip's 9 vertical edges and 8 diagonals each pierce one triangle of the grid (17); the
  // grid's 8 edges along z at x = 0.1 ... 0.8 of row 4 and its 8 diagonals of row 4 crossing
  // z = 0.4321 at x = 0.1 c + 0.0321, c = 0 ... 7, each pierce one triangle of the strip (16).
  // No crossing point is within 0.01 of a side, so rounding cannot change the count.
  const Grid flat = grid(11, 11, 0.1, 0.1);
  Grid strip = grid(9, 2, 0.1, 0.1);
  for (Eigen::Index i = 0; i < strip.x.rows(); ++i) {
    const double x0 = strip.x(i, 0), z0 = strip.x(i, 2);
    strip.x.row(i) << 0.013 + x0, z0 == 0 ? -0.05 : 0.05, 0.4321;
  }
  const Grid both = join(flat, strip);
  CHECK(count_crossings(both.x, both.triangles) == 33);
  // Where edges cross triangles the point-triangle and edge-edge distances need not be 0.
  const double crossed_separation = min_separation(both.x, both.triangles);
  // The strip lifted clear of the grid: no crossing, separation 0.06 - 0.05 ... by hand 0.01.
  Grid lifted = both;
  lifted.x.bottomRows(strip.x.rows()).col(1).array() += 0.06;
  CHECK(count_crossings(lifted.x, lifted.triangles) == 0);
  CHECK(min_separation(lifted.x, lifted.triangles) == doctest::Approx(0.01).epsilon(1e-12));

  std::mt19937 rng(20240601);
  for (int trial = 0; trial < 20; ++trial) {
    CAPTURE(trial);
    const Points<double> y = random_rigid_motion(both.x, rng);
    CHECK(count_crossings(y, both.triangles) == 33);
    CHECK(min_separation(y, both.triangles) == doctest::Approx(crossed_separation).epsilon(1e-9));
    const Points<double> z = random_rigid_motion(lifted.x, rng);
    CHECK(count_crossings(z, lifted.triangles) == 0);
    CHECK(min_separation(z, lifted.triangles) == doctest::Approx(0.01).epsilon(1e-9));
  }
  // The single-triangle cases too, each moved 50 times.
  for (int trial = 0; trial < 50; ++trial) {
    Points<double> x(8, 3);
    x << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.25, 0.25, -1, 0.25, 0.25, 1, 0.1, 0.1, 0.1, 0.5, 0.2, 0.1,
        0.1, 0.2, 0.4;
    Triangles t(1, 3);
    t << 0, 1, 2;
    Edges e(1, 2);
    e << 3, 4;
    const Points<double> y = random_rigid_motion(x, rng);
    CHECK(count_crossings(y, t, e) == 1);
    e << 5, 6;  // parallel, 0.1 above
    CHECK(count_crossings(y, t, e) == 0);
  }
}

TEST_CASE("intersections: a flat grid has no crossing, separation dx dz / sqrt(dx^2 + dz^2)") {
  // In a cell the diagonal (a, cc) is at distance dx dz / sqrt(dx^2 + dz^2) from the corners b
  // and d, which are not on its triangle on the other side; every other non-adjacent pair is
  // at least min(dx, dz) apart, which is larger.
  struct Case {
    int columns, rows;
    double dx, dz;
  };
  for (const Case& c : {Case{2, 2, 0.1, 0.1}, Case{5, 7, 0.1, 0.3}, Case{9, 4, 0.25, 0.05},
                        Case{81, 81, 0.025, 0.025}}) {
    CAPTURE(c.columns);
    CAPTURE(c.rows);
    const Grid g = grid(c.columns, c.rows, c.dx, c.dz, 0.3);
    const Edges edges = triangle_edges(g.triangles);
    CHECK(edges.rows() ==
          (c.columns - 1) * c.rows + c.columns * (c.rows - 1) + (c.columns - 1) * (c.rows - 1));
    CHECK(count_crossings(g.x, g.triangles, edges) == 0);
    CHECK(min_separation(g.x, g.triangles, edges) ==
          doctest::Approx(c.dx * c.dz / std::hypot(c.dx, c.dz)).epsilon(1e-12));
  }
}

TEST_CASE("intersections: stacked grids are g apart, a folded grid by hand") {
  const double h = 0.1, g = 0.02;
  // Two separate grids, one g above the other: a point of one above a triangle of the other.
  const Grid stacked = join(grid(6, 6, h, h), grid(6, 6, h, h, g));
  CHECK(count_crossings(stacked.x, stacked.triangles) == 0);
  CHECK(min_separation(stacked.x, stacked.triangles) == doctest::Approx(g).epsilon(1e-12));

  // One grid folded onto itself: rows 0 ... 4 at y = 0, z = r h; rows 5 ... 9 at y = g,
  // z = (9 - r) h. Row 5 is above row 4, and the cells between them are vertical rectangles
  // h wide and g high. The closest pair is skew: a fold cell's diagonal, direction (h, g, 0) from
  // (c h, 0, 4 h), and the diagonal below it of row 3, direction (h, 0, h) from (c h, 0, 3 h),
  // which share no point. Their lines are |r . n| / |n| apart with r = (0, 0, h) and
  // n = (h, g, 0) x (h, 0, h) = (g h, -h^2, -g h): g h / sqrt(h^2 + 2 g^2), less than the fold
  // cell's altitude g h / sqrt(h^2 + g^2) and than g; the closest points are inside both.
  Grid folded = grid(6, 10, h, h);
  for (int r = 5; r < 10; ++r)
    for (int c = 0; c < 6; ++c) folded.x.row(r * 6 + c) << c * h, g, (9 - r) * h;
  CHECK(count_crossings(folded.x, folded.triangles) == 0);
  CHECK(min_separation(folded.x, folded.triangles) ==
        doctest::Approx(g * h / std::sqrt(h * h + 2 * g * g)).epsilon(1e-12));
}

TEST_CASE("intersections: an obstacle's segment through a grid, by hand") {
  const Grid g = grid(5, 5, 0.1, 0.1);
  auto through = [&](double x, double z) {
    return count_segment_crossings(g.x, g.triangles, V3(x, -1, z), V3(x, 1, z));
  };
  CHECK(through(0.13, 0.27) == 1);  // inside a triangle
  CHECK(through(0.15, 0.2) == 2);   // a side's midpoint: the two triangles on it
  CHECK(through(0.15, 0.15) == 2);  // a diagonal's midpoint
  CHECK(through(0.2, 0.2) == 6);    // an interior point: its six triangles
  CHECK(through(0.0, 0.0) == 2);    // the corner on the diagonal: its two triangles
  CHECK(through(0.5, 0.5) == 0);    // beside the grid
  // Along the grid, 1e-9 above it, and in it.
  CHECK(count_segment_crossings(g.x, g.triangles, V3(-1, 1e-9, 0.21), V3(2, 1e-9, 0.21)) == 0);
  CHECK(count_segment_crossings(g.x, g.triangles, V3(-1, 0, 0.21), V3(2, 0, 0.21)) == 8);
}

TEST_CASE("intersections: the distances agree with dense sampling of the elements") {
  namespace d = massspring::test::intersections_detail;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random_point = [&] { return V3(u(rng), u(rng), u(rng)); };
  constexpr int n = 100;  // samples per parameter
  for (int trial = 0; trial < 200; ++trial) {
    const V3 p = random_point(), a = random_point(), b = random_point(), c = random_point();
    double sampled = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        sampled = std::min(sampled, (p - (a + (b - a) * i / n + (c - a) * j / n)).norm());
    const double computed = d::point_triangle_distance(p, a, b, c);
    // The samples are points of the triangle, and every point is within a sample spacing of one.
    const double spacing = ((b - a).norm() + (c - a).norm()) / n;
    CHECK(computed <= sampled + 1e-12);
    CHECK(computed >= sampled - spacing);

    const V3 q = random_point();
    double sampled_ss = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        sampled_ss = std::min(sampled_ss, ((p + (q - p) * i / n) - (a + (b - a) * j / n)).norm());
    const double computed_ss = d::segment_segment_distance(p, q, a, b);
    CHECK(computed_ss <= sampled_ss + 1e-12);
    CHECK(computed_ss >= sampled_ss - ((q - p).norm() + (b - a).norm()) / n);
  }
}

TEST_CASE("intersections: the sweep's pruning changes nothing against all pairs") {
  // Crumpled grids (each point moved at random by up to 0.6 h): the pruned searches against a
  // loop over every pair.
  namespace d = massspring::test::intersections_detail;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.06, 0.06);
  int crossed = 0;  // trials with crossings, so that the comparison is not only of zeros
  for (int trial = 0; trial < 10; ++trial) {
    CAPTURE(trial);
    Grid g = grid(8, 8, 0.1, 0.1);
    for (Eigen::Index i = 0; i < g.x.rows(); ++i)
      g.x.row(i) += Eigen::RowVector3d(u(rng), 4 * u(rng), u(rng));
    const Edges edges = triangle_edges(g.triangles);
    int crossings = 0;
    double separation = std::numeric_limits<double>::infinity();
    auto pt = [&](int i) { return V3(g.x.row(i).transpose()); };
    for (Eigen::Index t = 0; t < g.triangles.rows(); ++t) {
      const int a = g.triangles(t, 0), b = g.triangles(t, 1), c = g.triangles(t, 2);
      for (Eigen::Index e = 0; e < edges.rows(); ++e) {
        const int p = edges(e, 0), q = edges(e, 1);
        if (p == a || p == b || p == c || q == a || q == b || q == c) continue;
        crossings += d::segment_meets_triangle(pt(p), pt(q), pt(a), pt(b), pt(c));
      }
      for (int p = 0; p < int(g.x.rows()); ++p)
        if (p != a && p != b && p != c)
          separation = std::min(separation, d::point_triangle_distance(pt(p), pt(a), pt(b), pt(c)));
    }
    for (Eigen::Index e = 0; e < edges.rows(); ++e)
      for (Eigen::Index f = e + 1; f < edges.rows(); ++f) {
        const int p = edges(e, 0), q = edges(e, 1), r = edges(f, 0), s = edges(f, 1);
        if (p == r || p == s || q == r || q == s) continue;
        separation = std::min(separation, d::segment_segment_distance(pt(p), pt(q), pt(r), pt(s)));
      }
    CHECK(count_crossings(g.x, g.triangles, edges) == crossings);
    CHECK(min_separation(g.x, g.triangles, edges) == separation);
    crossed += crossings > 0;
  }
  CHECK(crossed >= 5);
}
