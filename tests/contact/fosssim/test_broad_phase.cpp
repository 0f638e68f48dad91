// contact/fosssim/broad_phase.hpp: the grid ("contest") gives exactly the contacts that all pairs
// give, on random scenes of particles, edges (some long) and planes, for static and swept boxes;
// its candidates are exactly the pairs whose boxes overlap (brute force); the visiting order is
// FOSSSim's.
#include <doctest/doctest.h>

#include <algorithm>
#include <massspring/contact/distance/point_segment.hpp>
#include <massspring/contact/fosssim/broad_phase.hpp>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "contact/support.hpp"

namespace contact = massspring::contact;
using massspring::test::Pts;
using massspring::test::v3;
using Key = std::tuple<int, int, int>;  // (particle, kind, other)

namespace {

contact::ContactGeometry<double> random_geometry(std::mt19937& rng, int n, int E, Pts& x) {
  std::uniform_real_distribution<double> u(0, 1);
  contact::ContactGeometry<double> g;
  x.resize(n, 3);
  for (int i = 0; i < n; ++i) x.row(i) << 4 * u(rng), 4 * u(rng), (i % 3 == 0 ? 0.0 : u(rng));
  g.radii = massspring::Vector<double>::NullaryExpr(n, [&] { return 0.02 + 0.15 * u(rng); });
  g.edges.resize(E, 2);
  g.edge_radii.resize(E);
  for (int e = 0; e < E; ++e) {
    const int a = int(u(rng) * n) % n;
    int b = int(u(rng) * n) % n;
    if (b == a) b = (a + 1) % n;
    g.edges.row(e) << a, b;
    g.edge_radii(e) = 0.01 + 0.05 * u(rng);
  }
  g.planes.push_back({v3(0, 0.5), v3(0, 2)});
  return g;
}

// every pair whose narrow phase says "within radii + margin" at x
std::set<Key> contacts(contact::FosssimBroadPhase<double>& bp,
                       const contact::ContactGeometry<double>& g, const Pts& x, double margin) {
  std::set<Key> out;
  bp.visit(g, x, x, margin, [&](contact::ParticlePairKind k, int i, int j) {
    const massspring::Vector3<double> p = x.row(i).transpose();
    double d = 0, s = g.radii(i) + margin;
    if (k == contact::ParticlePairKind::PointPoint) {
      d = (x.row(j) - x.row(i)).norm();
      s += g.radii(j);
    } else if (k == contact::ParticlePairKind::PointEdge) {
      d = contact::point_segment_distance<double>(p, x.row(g.edges(j, 0)).transpose(),
                                                  x.row(g.edges(j, 1)).transpose())
              .distance;
      s += g.edge_radii(j);
    } else {
      return;  // planes: every particle is a candidate in both
    }
    if (d < s) out.insert({i, int(k), j});
  });
  return out;
}

}  // namespace

TEST_CASE(
    "FosssimBroadPhase: the grid finds exactly the contacts all pairs find, on random scenes") {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    CAPTURE(seed);
    std::mt19937 rng(seed);
    Pts x;
    const auto g = random_geometry(rng, 300, 150, x);
    contact::FosssimBroadPhase<double> all(contact::BroadPhaseKind::AllPairs),
        grid(contact::BroadPhaseKind::Grid);
    for (double margin : {0.0, 0.05}) {
      const auto a = contacts(all, g, x, margin), b = contacts(grid, g, x, margin);
      CHECK(a.size() > 20);  // the scene has contacts to find
      CHECK(a == b);
    }
  }
}

TEST_CASE(
    "FosssimBroadPhase: grid candidates are exactly the pairs whose boxes overlap, also swept") {
  std::mt19937 rng(7);
  Pts xs;
  const auto g = random_geometry(rng, 200, 120, xs);
  Pts xe = xs;
  std::normal_distribution<double> step(0, 0.3);
  for (int i = 0; i < xe.rows(); ++i) xe.row(i) += v3(step(rng), step(rng), 0).transpose();
  // brute force: boxes of the motion grown by radius + margin
  const double margin = 0.01;
  auto box = [&](int k, massspring::Vector3<double>& lo, massspring::Vector3<double>& hi) {
    const int n = g.num_particles();
    std::vector<int> pts =
        k < n ? std::vector<int>{k} : std::vector<int>{g.edges(k - n, 0), g.edges(k - n, 1)};
    const double r = (k < n ? g.radii(k) : g.edge_radii(k - n)) + margin;
    lo.setConstant(1e300);
    hi.setConstant(-1e300);
    for (int p : pts) {
      lo = lo.cwiseMin(xs.row(p).transpose()).cwiseMin(xe.row(p).transpose());
      hi = hi.cwiseMax(xs.row(p).transpose()).cwiseMax(xe.row(p).transpose());
    }
    lo.array() -= r;
    hi.array() += r;
  };
  std::set<Key> expected;
  const int n = g.num_particles(), N = n + g.num_edges();
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < N; ++b) {
      if (b >= n && (g.edges(b - n, 0) == a || g.edges(b - n, 1) == a)) continue;
      massspring::Vector3<double> la, ha, lb, hb;
      box(a, la, ha);
      box(b, lb, hb);
      if ((la.array() <= hb.array()).all() && (lb.array() <= ha.array()).all())
        expected.insert(b < n ? Key{a, 0, b} : Key{a, 1, b - n});
    }
  // edges whose particle comes after them in item order: the pair (particle, edge) as well
  contact::FosssimBroadPhase<double> grid(contact::BroadPhaseKind::Grid);
  std::set<Key> found;
  std::vector<Key> order;
  grid.visit(g, xs, xe, margin, [&](contact::ParticlePairKind k, int i, int j) {
    if (k != contact::ParticlePairKind::PointPlane) found.insert({i, int(k), j});
    order.push_back({i, int(k), j});
  });
  // the grid's boxes are a few ulps wider: a pair may only be found in addition when its boxes
  // touch within rounding, which random data never does
  CHECK(found == expected);
  // FOSSSim's order: by particle, then particle-particle, particle-edge, particle-plane
  CHECK(std::is_sorted(order.begin(), order.end()));
  CHECK(found.size() > 50);
}

TEST_CASE("FosssimBroadPhase: all pairs visits in FOSSSim's order and skips incident edges") {
  contact::ContactGeometry<double> g = massspring::test::particles(3, 0.1);
  g.edges.resize(1, 2);
  g.edges << 0, 1;
  g.edge_radii = massspring::Vector<double>::Constant(1, 0.1);
  g.planes.push_back({v3(0, 0), v3(0, 1)});
  Pts x = Pts::Zero(3, 3);
  std::vector<Key> order;
  contact::FosssimBroadPhase<double> all;
  all.visit(g, x, x, 0.0, [&](contact::ParticlePairKind k, int i, int j) {
    order.push_back({i, int(k), j});
  });
  const std::vector<Key> expected = {{0, 0, 1}, {0, 0, 2}, {0, 2, 0}, {1, 0, 2},
                                     {1, 2, 0}, {2, 1, 0}, {2, 2, 0}};
  CHECK(order == expected);
}
