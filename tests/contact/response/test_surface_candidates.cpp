// contact/response/surface_candidates.hpp against a brute-force list: every point-triangle and
// edge-edge pair whose grown swept boxes overlap (and that shares no point) is listed once, in
// one order. Without self-collision (the obstacles' pairs) by full() exactly the pairs of the
// boxes grown by the margin too, and by refresh() and next_step() after rounds and steps that
// move end positions by small steps, by large ones (escaping the stored boxes) and by very many
// (falling back to full()). With self-collision a pair may be left out only when it cannot meet
// over the step: the oracle is the distance of tests/support/intersections.hpp at 101 times.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <massspring/contact/response/surface_candidates.hpp>
#include <massspring/scene/cloth.hpp>
#include <optional>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "support/intersections.hpp"

namespace {
namespace contact = massspring::contact;
using Box = contact::AlignedBox3<double>;
using PairSet = std::set<std::tuple<int, int, int>>;

// The swept box of points `ids` over x0 -> x1 (with `ahead`, also over x1 -> 2 x1 - x0, a next
// step at the same velocity), grown by g: written apart from SurfaceElements.
Box swept(const massspring::Points<double>& x0, const massspring::Points<double>& x1,
          std::initializer_list<int> ids, double g, bool ahead = false) {
  Box b{x0.row(*ids.begin()).transpose(), x0.row(*ids.begin()).transpose()};
  for (int i : ids) {
    b.lo = b.lo.cwiseMin(x0.row(i).transpose()).cwiseMin(x1.row(i).transpose());
    b.hi = b.hi.cwiseMax(x0.row(i).transpose()).cwiseMax(x1.row(i).transpose());
    if (ahead) {
      const Eigen::Vector3d next = (2 * x1.row(i) - x0.row(i)).transpose();
      b.lo = b.lo.cwiseMin(next);
      b.hi = b.hi.cwiseMax(next);
    }
  }
  b.lo.array() -= g;
  b.hi.array() += g;
  return b;
}

// Every pair SurfaceElements::pair_gap() tests (cloth-cloth only with self-collision; never
// obstacle-obstacle) whose boxes overlap, each element's box grown as SurfaceElements::grow_of()
// says (the cloth's by g, an obstacle's by its gap) and by `extra`, sharing no point. With a
// positive `extra`, the boxes SurfaceCandidates stores: over the next step at the same velocity
// too.
PairSet brute_force(const contact::SurfaceElements<double>& e, double g, double extra = 0) {
  const bool ahead = extra > 0;
  PairSet out;
  const auto& x0 = e.x0;
  const auto& x1 = e.x1;
  for (std::size_t v = 0; v < e.points.size(); ++v) {
    const auto& pv = e.points[v];
    const int i = pv.p[0];
    const Box bp = swept(x0, x1, {i}, e.grow_of(pv, g) + extra, ahead);
    for (std::size_t t = 0; t < e.triangles.size(); ++t) {
      const auto& tt = e.triangles[t];
      const auto& c = tt.p;
      if (e.pair_gap(pv.owner, tt.owner) < 0) continue;
      if (i == c[0] || i == c[1] || i == c[2]) continue;
      if (bp.overlaps(swept(x0, x1, {c[0], c[1], c[2]}, e.grow_of(tt, g) + extra, ahead)))
        out.insert({0, int(v), int(t)});
    }
  }
  for (std::size_t a = 0; a < e.edges.size(); ++a)
    for (std::size_t b = a + 1; b < e.edges.size(); ++b) {
      const auto& p = e.edges[a].p;
      const auto& q = e.edges[b].p;
      if (e.pair_gap(e.edges[a].owner, e.edges[b].owner) < 0) continue;
      if (p[0] == q[0] || p[0] == q[1] || p[1] == q[0] || p[1] == q[1]) continue;
      if (swept(x0, x1, {p[0], p[1]}, e.grow_of(e.edges[a], g) + extra, ahead)
              .overlaps(swept(x0, x1, {q[0], q[1]}, e.grow_of(e.edges[b], g) + extra, ahead)))
        out.insert({1, int(a), int(b)});
    }
  return out;
}

// The listed pairs as a set; each must be listed once, in ascending order of (kind, a, b).
PairSet listed(const std::vector<contact::ElementPair>& pairs) {
  PairSet out;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto& q = pairs[k];
    const bool fresh = out.insert({int(q.kind), q.a, q.b}).second;
    REQUIRE(fresh);  // each pair once
    if (k > 0) {
      const auto& p = pairs[k - 1];
      REQUIRE(std::make_tuple(int(p.kind), p.a, p.b) < std::make_tuple(int(q.kind), q.a, q.b));
    }
  }
  return out;
}

// The pair's smallest distance [m] at 101 times of the straight-line motion x0 -> x1, by the
// independent distances of tests/support/intersections.hpp.
double closest(const contact::SurfaceElements<double>& e, int kind, int a, int b) {
  namespace d = massspring::test::intersections_detail;
  const std::array<int, 4> p =
      kind == 0
          ? std::array<int, 4>{e.points[std::size_t(a)].p[0], e.triangles[std::size_t(b)].p[0],
                               e.triangles[std::size_t(b)].p[1], e.triangles[std::size_t(b)].p[2]}
          : std::array<int, 4>{e.edges[std::size_t(a)].p[0], e.edges[std::size_t(a)].p[1],
                               e.edges[std::size_t(b)].p[0], e.edges[std::size_t(b)].p[1]};
  double best = std::numeric_limits<double>::infinity();
  for (int s = 0; s <= 100; ++s) {
    const double u = s / 100.0;
    std::array<Eigen::Vector3d, 4> x;
    for (int k = 0; k < 4; ++k)
      x[std::size_t(k)] =
          ((1 - u) * e.x0.row(p[std::size_t(k)]) + u * e.x1.row(p[std::size_t(k)])).transpose();
    best = std::min(best, kind == 0 ? d::point_triangle_distance(x[0], x[1], x[2], x[3])
                                    : d::segment_segment_distance(x[0], x[1], x[2], x[3]));
  }
  return best;
}

// With self-collision: the listed pairs are brute-force pairs (each once, in order); every
// brute-force pair left out is one of the cloth's own, lies in a patch that the tree (tested in
// tests/contact/broad_phase/test_normal_cone_tree.cpp) skips for this motion, or for an `earlier`
// one (end positions since the last full()) in which its points ended where they end now, and
// stays apart over the step. Returns how many were left out.
int check_self(const contact::SurfaceElements<double>& e,
               const std::vector<contact::ElementPair>& pairs, double grow,
               const std::vector<massspring::Points<double>>& earlier = {}) {
  const PairSet got = listed(pairs);
  const PairSet want = brute_force(e, grow);
  CHECK(std::includes(want.begin(), want.end(), got.begin(), got.end()));
  // The skipped patches, each as its set of points.
  std::vector<std::array<int, 3>> cloth;
  for (const auto& t : e.triangles)
    if (t.owner < 0) cloth.push_back(t.p);
  // Each motion's skipped patches, as sets of points and of triangles.
  struct Skipped {
    massspring::Points<double> x1;
    std::vector<std::set<int>> points, triangles;
  };
  std::vector<Skipped> motions;
  motions.push_back({e.x1, {}, {}});
  for (const auto& x1 : earlier) motions.push_back({x1, {}, {}});
  for (Skipped& m : motions) {
    contact::NormalConeTree<double> tree;
    tree.build(e.x0, cloth);
    tree.refit(e.x0, m.x1, grow);
    const auto skip = [&](std::size_t i, std::size_t j) {
      std::set<int> points, triangles;
      for (std::size_t k : {i, j})
        for (int t : tree.patch(k)) {
          points.insert(cloth[std::size_t(t)].begin(), cloth[std::size_t(t)].end());
          triangles.insert(t);
        }
      m.points.push_back(points);
      m.triangles.push_back(triangles);
    };
    for (std::size_t k = 0; k < tree.size(); ++k)
      if (tree.cannot_touch_itself(e.x0, m.x1, k)) skip(k, k);
    // The unions of two nodes the search skips.
    tree.self_pairs(
        e.x0, m.x1, [](int, int) {},
        [&](std::size_t i, std::size_t j) {
          if (i != j) skip(i, j);
        });
  }
  // Whether a skipped patch of a motion that ends these points where they end now has them all
  // (and triangle t, when t >= 0; its corners are among the points then).
  const auto held = [&](std::vector<int> ids, int t) {
    if (t >= 0) ids.insert(ids.end(), cloth[std::size_t(t)].begin(), cloth[std::size_t(t)].end());
    for (const Skipped& m : motions) {
      bool same = true;
      for (int i : ids) same = same && m.x1.row(i) == e.x1.row(i);
      for (std::size_t k = 0; same && k < m.points.size(); ++k) {
        bool all = t < 0 || m.triangles[k].count(t);
        for (int i : ids) all = all && m.points[k].count(i);
        if (all) return true;
      }
    }
    return false;
  };
  int left_out = 0;
  for (const auto& [kind, a, b] : want) {
    if (got.count({kind, a, b})) continue;
    ++left_out;
    const bool is_cloth =
        kind == 0 ? e.points[std::size_t(a)].owner < 0 && e.triangles[std::size_t(b)].owner < 0
                  : e.edges[std::size_t(a)].owner < 0 && e.edges[std::size_t(b)].owner < 0;
    CAPTURE(kind);
    CAPTURE(a);
    CAPTURE(b);
    REQUIRE(is_cloth);
    if (kind == 0) {
      REQUIRE(held({e.points[std::size_t(a)].p[0]}, b));
    } else {
      REQUIRE(held({e.edges[std::size_t(a)].p[0], e.edges[std::size_t(a)].p[1],
                    e.edges[std::size_t(b)].p[0], e.edges[std::size_t(b)].p[1]},
                   -1));
    }
    REQUIRE(closest(e, kind, a, b) > 0);
  }
  return left_out;
}

struct Crumpled {
  massspring::Points<double> x0, x1, v;
  massspring::Vector<double> masses, inverse_masses;  // nothing pinned
  massspring::Triangles triangles;
  massspring::Edges edges;
};

// A 9 x 9 cloth of 10 cm crumpled by random end positions, with its triangles' edges.
Crumpled crumpled(std::mt19937& rng) {
  massspring::ClothOptions o;
  o.columns = o.rows = 9;
  o.width = o.height = 0.1;
  o.shear = massspring::ClothShear::One;
  const auto cloth = massspring::make_cloth(o);
  Crumpled c;
  c.x0 = cloth.vertices;
  c.x1 = cloth.vertices;
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (Eigen::Index i = 0; i < c.x1.rows(); ++i)
    for (int k = 0; k < 3; ++k) c.x1(i, k) += jitter(rng);
  c.v = massspring::Points<double>::Zero(c.x0.rows(), 3);
  c.masses = massspring::Vector<double>::Ones(c.x0.rows());
  c.inverse_masses = c.masses;
  c.triangles.resize(Eigen::Index(cloth.faces.size()), 3);
  for (std::size_t f = 0; f < cloth.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) c.triangles(Eigen::Index(f), k) = cloth.faces[f][std::size_t(k)];
  std::vector<std::pair<int, int>> list;  // the triangles' edges
  massspring::detail::triangle_edges(c.triangles, list);
  c.edges.resize(Eigen::Index(list.size()), 2);
  for (std::size_t k = 0; k < list.size(); ++k)
    c.edges.row(Eigen::Index(k)) << list[k].first, list[k].second;
  return c;
}
}  // namespace

// With self-collision every call lists the pairs of the current motion afresh; the pairs it
// leaves out lie in patches that cannot touch themselves. A crumpled cloth (few such patches),
// the same cloth bending smoothly (many), a capsule through it (its pairs all listed), and rounds
// that move some end positions.
TEST_CASE("SurfaceCandidates: with self-collision, every pair that can meet is listed once") {
  std::mt19937 rng(3);
  Crumpled c = crumpled(rng);
  REQUIRE(c.triangles.rows() > 0);
  const massspring::Edges& edges = c.edges;
  const std::vector<int> pinned;
  const std::optional<contact::SelfCollision<double>> self = contact::SelfCollision<double>{};
  contact::ColliderSet<double> colliders;
  colliders.add(contact::Collider<double>::capsule(Eigen::Vector3d(-0.02, -0.05, 0),
                                                   Eigen::Vector3d(0.12, -0.03, 0.002), 0.004));
  bool smooth = false;
  SUBCASE("crumpled") {}
  SUBCASE("bending smoothly") {  // a wave and a turn instead of the jitter
    smooth = true;
    for (Eigen::Index i = 0; i < c.x1.rows(); ++i) {
      const Eigen::Vector3d p = c.x0.row(i).transpose();
      c.x1.row(i) = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()) *
                     Eigen::Vector3d(p.x(), p.y(),
                                     0.01 * std::sin(40 * p.x()) + 0.005 * std::cos(30 * p.y())))
                        .transpose();
    }
  }
  const contact::CollisionStep<double> one{
      c.x0, c.v, c.x1, c.v, 1.0 / 30, c.masses, c.inverse_masses, pinned};
  const contact::SurfaceContactInput<double> in{one, c.triangles, edges, self, colliders};
  contact::SurfaceElements<double> e;
  e.setup(in);
  const double grow = 0.002, margin = 0.002;
  contact::SurfaceCandidates<double> broad;
  broad.full(e, grow, margin);
  const int left_out = check_self(e, broad.pairs(), grow);
  REQUIRE(broad.full_count() == 1);
  CAPTURE(smooth);
  if (smooth)
    CHECK(left_out > int(broad.pairs().size()));  // most are left out
  else
    CHECK(left_out < int(broad.pairs().size()));

  // Rounds that move a few cloth points: refresh() lists again the pairs of the elements they
  // are on, which must be exactly those a new full() lists, and keeps the others.
  std::vector<char> moved(std::size_t(e.x1.rows()), 0);
  std::uniform_int_distribution<int> pick(0, int(c.x1.rows()) - 1);  // cloth points only
  std::vector<massspring::Points<double>> earlier = {e.x1};
  for (const double step : {margin / 4, 0.03, 0.0, 0.03, margin / 4}) {
    std::fill(moved.begin(), moved.end(), char(0));
    std::uniform_real_distribution<double> by(-step, std::max(step, 1e-9));
    for (int k = 0; k < 5; ++k) {
      const int i = pick(rng);
      if (step > 0)  // step 0: flagged, not moved
        for (int a = 0; a < 3; ++a) e.x1(i, a) += by(rng);
      moved[std::size_t(i)] = 1;
    }
    const std::vector<contact::ElementPair> before = broad.pairs();
    broad.refresh(e, moved);
    CAPTURE(step);
    check_self(e, broad.pairs(), grow, earlier);
    earlier.push_back(e.x1);
    if (step == 0) CHECK(listed(broad.pairs()) == listed(before));
    contact::SurfaceCandidates<double> fresh;
    fresh.full(e, grow, margin);
    const auto on_moved = [&](const PairSet& all) {
      PairSet out;
      for (const auto& [kind, a, b] : all) {
        const auto& first = kind == 0 ? e.points[std::size_t(a)] : e.edges[std::size_t(a)];
        const auto& second = kind == 0 ? e.triangles[std::size_t(b)] : e.edges[std::size_t(b)];
        bool any = false;
        for (int k = 0; k < (kind == 0 ? 1 : 2); ++k)
          any = any || moved[std::size_t(first.p[std::size_t(k)])];
        for (int k = 0; k < (kind == 0 ? 3 : 2); ++k)
          any = any || moved[std::size_t(second.p[std::size_t(k)])];
        if (any) out.insert({kind, a, b});
      }
      return out;
    };
    if (step > 0) CHECK(on_moved(listed(broad.pairs())) == on_moved(listed(fresh.pairs())));
  }
  CHECK(broad.full_count() == 1);  // no refresh() listed afresh

  // An obstacle's point that moves (the capsule's end; no impulse moves one) makes refresh()
  // list every pair afresh.
  std::fill(moved.begin(), moved.end(), char(0));
  const Eigen::Index end = e.x1.rows() - 1;
  REQUIRE(e.owner[std::size_t(end)] >= 0);
  e.x1(end, 2) += 0.01;
  moved[std::size_t(end)] = 1;
  broad.refresh(e, moved);
  CHECK(broad.full_count() == 2);
  check_self(e, broad.pairs(), grow);
}

// Without self-collision full() queries only the obstacles' elements: it must still list every
// pair that has one (a capsule's axis and ends, a ball's centre, a mesh's points, edges and
// triangles, all among the crumpled cloth), and refresh() must keep every one.
TEST_CASE("SurfaceCandidates: without self-collision, every pair with an obstacle's element") {
  std::mt19937 rng(5);
  Crumpled c = crumpled(rng);
  const massspring::Edges& edges = c.edges;
  const std::vector<int> pinned;
  const std::optional<contact::SelfCollision<double>> off;
  contact::ColliderSet<double> colliders;
  using Collider = contact::Collider<double>;
  using Point = Eigen::Vector3d;
  colliders.add(Collider::capsule(Point(-0.02, -0.05, 0), Point(0.12, -0.03, 0.002), 0.004));
  colliders.add(Collider::sphere(Point(0.05, -0.02, 0.003), 0.01));
  massspring::Points<double> mesh(4, 3);
  mesh << 0.02, -0.07, -0.01, 0.08, -0.07, -0.01, 0.05, -0.02, -0.01, 0.05, -0.05, 0.02;
  massspring::Triangles faces(4, 3);
  faces << 0, 1, 2, 0, 1, 3, 1, 2, 3, 2, 0, 3;
  colliders.add(Collider::mesh(mesh, faces));
  const contact::CollisionStep<double> one{
      c.x0, c.v, c.x1, c.v, 1.0 / 30, c.masses, c.inverse_masses, pinned};
  const contact::SurfaceContactInput<double> in{one, c.triangles, edges, off, colliders};
  contact::SurfaceElements<double> e;
  e.setup(in);
  const double grow = 0.002, margin = 0.002;
  contact::SurfaceCandidates<double> broad;
  broad.full(e, grow, margin);
  const PairSet want = brute_force(e, grow);
  REQUIRE(want.size() > 20);  // the obstacles meet the cloth
  CHECK(listed(broad.pairs()) == brute_force(e, grow, margin));

  // Rounds that move some cloth points, small and large: still every pair.
  std::vector<char> moved(std::size_t(e.x1.rows()), 0);
  std::uniform_int_distribution<int> pick(0, int(c.x1.rows()) - 1);  // cloth points only
  for (const double step : {margin / 4, 0.03}) {
    std::fill(moved.begin(), moved.end(), char(0));
    std::uniform_real_distribution<double> by(-step, std::max(step, 1e-9));
    for (int k = 0; k < 5; ++k) {
      const int i = pick(rng);
      for (int a = 0; a < 3; ++a) e.x1(i, a) += by(rng);
      moved[std::size_t(i)] = 1;
    }
    broad.refresh(e, moved);
    const PairSet got = listed(broad.pairs());
    const PairSet now = brute_force(e, grow);
    CHECK(std::includes(got.begin(), got.end(), now.begin(), now.end()));
  }

  // A round that moves the obstacles' points (a moving collider) out of their boxes, and cloth
  // points with them: an escaped obstacle element is queried against every element, an escaped
  // cloth element against the escaped obstacles' too; still every pair, each once.
  std::fill(moved.begin(), moved.end(), char(0));
  for (Eigen::Index i = c.x1.rows(); i < e.x1.rows(); ++i) {
    e.x1(i, 0) += 0.01;  // five margins
    moved[std::size_t(i)] = 1;
  }
  for (int k = 0; k < 3; ++k) {
    const int i = pick(rng);
    e.x1(i, 0) += 0.01;
    moved[std::size_t(i)] = 1;
  }
  const long fulls = broad.full_count();
  broad.refresh(e, moved);
  REQUIRE(broad.full_count() == fulls);  // listed again by refresh(), not afresh by full()
  const PairSet got = listed(broad.pairs());
  const PairSet now = brute_force(e, grow);
  REQUIRE(now != want);  // the obstacles' pairs changed
  CHECK(std::includes(got.begin(), got.end(), now.begin(), now.end()));
  const auto same = [](const contact::ElementPair& p, const contact::ElementPair& q) {
    return p.kind == q.kind && p.a == q.a && p.b == q.b;
  };
  CHECK(std::adjacent_find(broad.pairs().begin(), broad.pairs().end(), same) ==
        broad.pairs().end());
}

// Steps after steps of the same elements: next_step() keeps the pairs of the elements that stay
// in their stored boxes and lists the escaped ones again, so each step's list holds every pair
// of its true boxes; other elements (self-collision switched off) make it start over.
TEST_CASE("SurfaceCandidates: next_step() over steps keeps every overlapping pair") {
  std::mt19937 rng(7);
  Crumpled c = crumpled(rng);
  const massspring::Edges& edges = c.edges;
  const std::vector<int> pinned;
  std::optional<contact::SelfCollision<double>> self;
  contact::ColliderSet<double> colliders;
  colliders.add(contact::Collider<double>::capsule(Eigen::Vector3d(-0.02, -0.05, 0),
                                                   Eigen::Vector3d(0.12, -0.03, 0.002), 0.004));
  const double grow = 0.002, margin = 0.002;
  contact::SurfaceElements<double> e;
  contact::SurfaceCandidates<double> broad;
  // One step: the last end positions start it, and every point moves by up to `step` [m].
  const auto step = [&](double by_most) {
    const contact::CollisionStep<double> one{
        c.x0, c.v, c.x1, c.v, 1.0 / 30, c.masses, c.inverse_masses, pinned};
    const contact::SurfaceContactInput<double> in{one, c.triangles, edges, self, colliders};
    e.setup(in);
    broad.next_step(e, grow, margin);
    const PairSet want = brute_force(e, grow);
    REQUIRE(!want.empty());
    if (self) {
      check_self(e, broad.pairs(), grow);
    } else {
      const PairSet got = listed(broad.pairs());
      CHECK(std::includes(got.begin(), got.end(), want.begin(), want.end()));
    }
    c.x0 = c.x1;
    std::uniform_real_distribution<double> by(-by_most, by_most);
    for (Eigen::Index i = 0; i < c.x1.rows(); ++i)
      for (int a = 0; a < 3; ++a) c.x1(i, a) += by(rng);
  };
  step(margin / 8);  // the first: full()
  REQUIRE(broad.full_count() == 1);
  SUBCASE("a cloth that barely moves keeps its list") {
    for (int k = 0; k < 3; ++k) step(margin / 8);
    CHECK(broad.full_count() == 1);
  }
  SUBCASE("a few points jump: they are listed again, still every pair") {
    for (int k = 0; k < 4; ++k) {
      step(margin / 8);
      for (int i : {3, 40, 77}) c.x1(i, 1) += 0.03;
    }
    CHECK(broad.full_count() == 1);
  }
  SUBCASE("every point jumps: full() again") {
    step(0.03);
    step(0.03);
    CHECK(broad.full_count() == 2);
  }
  SUBCASE("self-collision switched on: other pairs, listed afresh every step") {
    self = contact::SelfCollision<double>{};
    step(margin / 8);
    step(margin / 8);
    CHECK(broad.full_count() == 3);
  }
  // SurfaceElements keeps its lists while their sources stay the same (its `layout`); each
  // change below makes other lists, and the candidates start over from them.
  SUBCASE("the surface's triangles in another order: other elements, full() again") {
    const auto layout = e.layout;
    step(margin / 8);
    CHECK(e.layout == layout);
    c.triangles = c.triangles.colwise().reverse().eval();
    step(margin / 8);
    CHECK(e.layout != layout);
    CHECK(broad.full_count() == 2);
  }
  SUBCASE("a second collider: other elements, full() again") {
    colliders.add(contact::Collider<double>::sphere(Eigen::Vector3d(0.05, -0.05, 0.02), 0.01));
    step(margin / 8);
    CHECK(broad.full_count() == 2);
  }
  SUBCASE("self-collision on, then the triangles in another order: a tree for the new order") {
    self = contact::SelfCollision<double>{};
    step(margin / 8);
    c.triangles = c.triangles.colwise().reverse().eval();
    step(margin / 8);  // check_self() on the elements of the new order
    step(margin / 8);
  }
}
