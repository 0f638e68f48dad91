// contact/response/surface_candidates.hpp against a brute-force list: every point-triangle and
// edge-edge pair whose grown swept boxes overlap (and that shares no point) is listed once: by
// full() exactly the pairs of the boxes grown by the margin too, and by refresh() and
// next_step() after rounds and steps that move end positions by small steps, by large ones
// (escaping the stored boxes) and by very many (falling back to full()), always in the same
// order.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <algorithm>
#include <massspring/contact/response/surface_candidates.hpp>
#include <massspring/scene/cloth.hpp>
#include <optional>
#include <random>
#include <set>
#include <tuple>
#include <vector>

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
    const bool fresh = out.insert({q.kind, q.a, q.b}).second;
    REQUIRE(fresh);  // each pair once
    if (k > 0) {
      const auto& p = pairs[k - 1];
      REQUIRE(std::make_tuple(p.kind, p.a, p.b) < std::make_tuple(q.kind, q.a, q.b));
    }
  }
  return out;
}

struct Crumpled {
  massspring::Points<double> x0, x1, v;
  massspring::Vector<double> masses;
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

TEST_CASE("SurfaceCandidates: full() and refresh() list every overlapping pair once") {
  std::mt19937 rng(3);
  Crumpled c = crumpled(rng);
  REQUIRE(c.triangles.rows() > 0);
  const massspring::Edges& edges = c.edges;
  const std::vector<int> pinned;
  const std::optional<contact::SelfCollision<double>> self = contact::SelfCollision<double>{};
  const contact::ColliderSet<double> colliders;
  const contact::SurfaceContactInput<double> in{c.x0,   c.x1,        c.v,   1.0 / 30, c.masses,
                                                pinned, c.triangles, edges, self,     colliders};
  contact::SurfaceElements<double> e;
  e.setup(in);
  const double grow = 0.002, margin = 0.002;
  contact::SurfaceCandidates<double> broad;
  broad.full(e, grow, margin);
  CHECK(listed(broad.pairs()) == brute_force(e, grow, margin));
  REQUIRE(broad.full_count() == 1);

  std::vector<char> moved(std::size_t(e.x1.rows()), 0);
  const auto round = [&](int count, double step) {
    std::fill(moved.begin(), moved.end(), char(0));
    std::uniform_int_distribution<int> pick(0, int(e.x1.rows()) - 1);
    std::uniform_real_distribution<double> by(-step, step);
    for (int k = 0; k < count; ++k) {
      const int i = pick(rng);
      for (int a = 0; a < 3; ++a) e.x1(i, a) += by(rng);
      moved[std::size_t(i)] = 1;
    }
    broad.refresh(e, moved);
    // A superset of the pairs of the true boxes (the stored boxes list some farther apart).
    const PairSet got = listed(broad.pairs());
    const PairSet want = brute_force(e, grow);
    CHECK(std::includes(got.begin(), got.end(), want.begin(), want.end()));
  };
  SUBCASE("small steps stay in the stored boxes: no new full()") {
    for (int r = 0; r < 4; ++r) round(5, margin / 4);
    CHECK(broad.full_count() == 1);
  }
  SUBCASE("large steps escape: listed directly, still every pair") {
    for (int r = 0; r < 4; ++r) round(3, 0.03);
    CHECK(broad.full_count() == 1);
  }
  SUBCASE("most points escape: full() again") {
    round(400, 0.03);
    CHECK(broad.full_count() == 2);
    round(2, 0.03);
  }
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
  const contact::SurfaceContactInput<double> in{c.x0,   c.x1,        c.v,   1.0 / 30, c.masses,
                                                pinned, c.triangles, edges, off,      colliders};
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
    std::uniform_real_distribution<double> by(-step, step);
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
}

// Steps after steps of the same elements: next_step() keeps the pairs of the elements that stay
// in their stored boxes and lists the escaped ones again, so each step's list holds every pair
// of its true boxes; other elements (self-collision switched off) make it start over.
TEST_CASE("SurfaceCandidates: next_step() over steps keeps every overlapping pair") {
  std::mt19937 rng(7);
  Crumpled c = crumpled(rng);
  const massspring::Edges& edges = c.edges;
  const std::vector<int> pinned;
  std::optional<contact::SelfCollision<double>> self = contact::SelfCollision<double>{};
  contact::ColliderSet<double> colliders;
  colliders.add(contact::Collider<double>::capsule(Eigen::Vector3d(-0.02, -0.05, 0),
                                                   Eigen::Vector3d(0.12, -0.03, 0.002), 0.004));
  const double grow = 0.002, margin = 0.002;
  contact::SurfaceElements<double> e;
  contact::SurfaceCandidates<double> broad;
  // One step: the last end positions start it, and every point moves by up to `step` [m].
  const auto step = [&](double by_most) {
    const contact::SurfaceContactInput<double> in{c.x0,   c.x1,        c.v,   1.0 / 30, c.masses,
                                                  pinned, c.triangles, edges, self,     colliders};
    e.setup(in);
    broad.next_step(e, grow, margin);
    const PairSet got = listed(broad.pairs());
    const PairSet want = brute_force(e, grow);
    REQUIRE(!want.empty());
    CHECK(std::includes(got.begin(), got.end(), want.begin(), want.end()));
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
  SUBCASE("self-collision switched off: other pairs, full() again") {
    self.reset();
    step(margin / 8);
    CHECK(broad.full_count() == 2);
  }
}
