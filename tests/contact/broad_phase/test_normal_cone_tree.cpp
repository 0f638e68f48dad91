// contact/broad_phase/normal_cone_tree.hpp. Oracles: a brute-force list of the triangle pairs
// whose swept boxes overlap (every one is listed, or lies in a patch the tree skips); the exact
// crossing count and the separation of tests/support/intersections.hpp, written apart from the
// library's contact code, at 101 times of each step for every patch the tree skips, a node's or
// the union of two (none may touch itself); and surfaces the contour rule must refuse (a ring, a
// flipped triangle).
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <massspring/contact/broad_phase/normal_cone_tree.hpp>
#include <massspring/scene/cloth.hpp>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "support/intersections.hpp"

namespace {
namespace contact = massspring::contact;
using Tree = contact::NormalConeTree<double>;
using Pts = massspring::Points<double>;
using Tri = std::array<int, 3>;

// An n x n cloth of side 0.1 m in the x-y plane, one diagonal per cell.
std::pair<Pts, std::vector<Tri>> sheet(int n) {
  massspring::ClothOptions o;
  o.columns = o.rows = n;
  o.width = o.height = 0.1;
  o.shear = massspring::ClothShear::One;
  const auto cloth = massspring::make_cloth(o);
  std::vector<Tri> t;
  for (const auto& f : cloth.faces) t.push_back({f[0], f[1], f[2]});
  return {cloth.vertices, t};
}

massspring::Triangles matrix(const std::vector<Tri>& t, const std::vector<int>& which) {
  massspring::Triangles m(Eigen::Index(which.size()), 3);
  for (std::size_t k = 0; k < which.size(); ++k)
    for (int j = 0; j < 3; ++j) m(Eigen::Index(k), j) = t[std::size_t(which[k])][std::size_t(j)];
  return m;
}

// Whether the swept boxes of triangles s and t over x0 -> x1, grown by g, overlap: apart from
// the tree's own boxes.
bool boxes_meet(const Pts& x0, const Pts& x1, const Tri& s, const Tri& t, double g) {
  Eigen::Vector3d lo[2], hi[2];
  const Tri* tri[2] = {&s, &t};
  for (int k = 0; k < 2; ++k) {
    lo[k] = hi[k] = x0.row((*tri[k])[0]).transpose();
    for (int i : *tri[k])
      for (const Pts* x : {&x0, &x1}) {
        lo[k] = lo[k].cwiseMin(x->row(i).transpose());
        hi[k] = hi[k].cwiseMax(x->row(i).transpose());
      }
  }
  return ((lo[0].array() - g) <= (hi[1].array() + g)).all() &&
         ((lo[1].array() - g) <= (hi[0].array() + g)).all();
}

// The patches the tree skips for x0 -> x1 (after refit()), as sets of triangles.
std::vector<std::set<int>> skipped(const Tree& tree, const Pts& x0, const Pts& x1) {
  std::vector<std::set<int>> out;
  for (std::size_t k = 0; k < tree.size(); ++k)
    if (tree.cannot_touch_itself(x0, x1, k)) {
      const std::vector<int> p = tree.patch(k);
      out.emplace_back(p.begin(), p.end());
    }
  return out;
}

// The unions of two nodes' patches whose pairs between the two self_pairs() reports skipped for
// x0 -> x1 (after refit()); a node it reports skipped alone must pass cannot_touch_itself(). The
// pairs it lists go to `listed` when given.
std::vector<std::set<int>> searched_skips(Tree& tree, const Pts& x0, const Pts& x1,
                                          std::set<std::pair<int, int>>* listed = nullptr) {
  std::vector<std::set<int>> out;
  tree.self_pairs(
      x0, x1,
      [&](int s, int u) {
        if (listed) listed->insert({std::min(s, u), std::max(s, u)});
      },
      [&](std::size_t i, std::size_t j) {
        if (i == j) {  // a node alone: skipped() has it
          REQUIRE(tree.cannot_touch_itself(x0, x1, i));
          return;
        }
        std::set<int> patch;
        for (std::size_t k : {i, j})
          for (int s : tree.patch(k)) patch.insert(s);
        if (i != j) REQUIRE(patch.size() == tree.patch(i).size() + tree.patch(j).size());
        out.push_back(patch);
      });
  return out;
}

// No crossing and a positive separation at 101 times of the step x0 -> x1 in the patch.
void check_patch(const Pts& x0, const Pts& x1, const std::vector<Tri>& t,
                 const std::set<int>& patch) {
  const massspring::Triangles m = matrix(t, std::vector<int>(patch.begin(), patch.end()));
  const massspring::Edges edges = massspring::test::triangle_edges(m);
  for (int s = 0; s <= 100; ++s) {
    const double u = s / 100.0;
    const Pts x = (1 - u) * x0 + u * x1;
    CAPTURE(u);
    REQUIRE(massspring::test::count_crossings(x, m, edges) == 0);
    REQUIRE(massspring::test::min_separation(x, m, edges) > 0);
  }
}

// Every patch the tree skips, each node that passes cannot_touch_itself() and each patch the
// search skips (the union of two nodes among them): checked by check_patch(). Returns how many
// patches of more than one triangle were checked.
int check_skipped(Tree& tree, const Pts& x0, const Pts& x1, const std::vector<Tri>& t) {
  int checked = 0;
  for (const std::set<int>& patch : skipped(tree, x0, x1)) {
    if (patch.size() < 2) continue;
    ++checked;
    check_patch(x0, x1, t, patch);
  }
  for (const std::set<int>& patch : searched_skips(tree, x0, x1)) {
    ++checked;
    check_patch(x0, x1, t, patch);
  }
  return checked;
}

// x moved by a smooth random bend: a height field of two random waves and a random rotation and
// translation; `amplitude` [m] sets how far it bends.
Pts bend(const Pts& x, std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-1, 1);
  const double k1 = 30 * u(rng), k2 = 30 * u(rng), k3 = 30 * u(rng), phase = 3 * u(rng);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized())
          .toRotationMatrix();
  const Eigen::Vector3d shift(0.05 * u(rng), 0.05 * u(rng), 0.05 * u(rng));
  Pts y = x;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    Eigen::Vector3d p = x.row(i).transpose();
    p.z() += amplitude * (std::sin(k1 * p.x() + phase) + std::sin(k2 * p.y() + k3 * p.x()));
    y.row(i) = (r * p + shift).transpose();
  }
  return y;
}
}  // namespace

// Built on the flat cloth, the tree's halves are disks glued along one arc; built on a crumpled
// copy, its splits cut the cloth into scattered pieces and the loops are traced from the
// triangles. Either way the whole cloth is one disk.
TEST_CASE("NormalConeTree: a rigidly moving flat cloth is skipped whole and lists no pair") {
  const auto [x0, t] = sheet(9);
  Tree tree;
  SUBCASE("built flat") { tree.build(x0, t); }
  SUBCASE("built crumpled") {
    std::mt19937 rng(17);
    std::uniform_real_distribution<double> jitter(-0.03, 0.03);
    Pts crumpled = x0;
    for (Eigen::Index i = 0; i < crumpled.rows(); ++i)
      for (int k = 0; k < 3; ++k) crumpled(i, k) += jitter(rng);
    tree.build(crumpled, t);
  }
  REQUIRE(tree.size() == 2 * t.size() - 1);
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Pts x1 = (x0 * r.transpose()).rowwise() + Eigen::RowVector3d(0.3, -0.2, 0.1);
  tree.refit(x0, x1, 0.002);
  CHECK(tree.cannot_touch_itself(x0, x1, 0));
  int listed = 0;
  tree.self_pairs(x0, x1, [&](int, int) { ++listed; });
  CHECK(listed == 0);
}

// The axis rule's reach (the file comment): normals within 53 degrees of a common direction
// always have an axis. A sheet bent into a cylindrical arc (normals on an arc of +-phi about its
// middle one) or laid on a spherical cap (normals filling a cone of half-angle phi, reached at
// its corners), turned at random and moved rigidly over the step, is skipped whole for phi up to
// 52 degrees (40 random turns each). At phi = 120 degrees the triangles' normals (taken at their
// centroids, short of the border's phi) still span more than a half circle (the arc), or the
// corner triangles' normals point away from the middle one (the cap), so no axis has a positive
// dot product with all of them, and it is not skipped.
TEST_CASE("NormalConeTree: a bent sheet with normals within 52 degrees of one is skipped") {
  const auto [flat, t] = sheet(13);
  const Eigen::RowVector3d centre = flat.colwise().mean();
  const double reach = 0.05 * std::sqrt(2.0);  // the corners' distance from the centre
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const bool cap : {false, true}) {
    for (const double degrees : {20.0, 40.0, 52.0, 120.0}) {
      const double phi = degrees * M_PI / 180;
      Pts bent = flat;
      for (Eigen::Index i = 0; i < flat.rows(); ++i) {
        const Eigen::RowVector3d d = flat.row(i) - centre;
        if (cap) {
          const double r = d.norm(), radius = reach / phi, theta = phi * r / reach;
          const double c = r > 0 ? d.x() / r : 1, s = r > 0 ? d.y() / r : 0;
          bent.row(i) << radius * std::sin(theta) * c, radius * std::sin(theta) * s,
              radius * std::cos(theta);
        } else {
          const double radius = 0.05 / phi, angle = phi * d.x() / 0.05;
          bent.row(i) << radius * std::sin(angle), d.y(), radius * std::cos(angle);
        }
      }
      for (int trial = 0; trial < 40; ++trial) {
        const Eigen::Matrix3d r =
            Eigen::AngleAxisd(M_PI * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized())
                .toRotationMatrix();
        const Pts x0 = bent * r.transpose();
        const Pts x1 =
            x0.rowwise() + Eigen::RowVector3d(0.01 * u(rng), 0.01 * u(rng), 0.01 * u(rng));
        Tree tree;
        tree.build(x0, t);
        tree.refit(x0, x1, 0.001);
        CAPTURE(cap);
        CAPTURE(degrees);
        CAPTURE(trial);
        CHECK(tree.cannot_touch_itself(x0, x1, 0) == (degrees < 90));
      }
    }
  }
}

TEST_CASE("NormalConeTree: every overlapping pair is listed once unless a skipped patch holds it") {
  std::mt19937 rng(11);
  const auto [x0, t] = sheet(9);
  Tree tree;
  tree.build(x0, t);
  int skipped_patches = 0;
  for (int trial = 0; trial < 12; ++trial) {
    CAPTURE(trial);
    // Half the trials bend smoothly (patches skipped), half crumple (few or none).
    Pts a = bend(x0, rng, 0.004 * trial), b = bend(x0, rng, 0.004 * trial);
    if (trial % 2 == 1) {
      std::uniform_real_distribution<double> jitter(-0.01, 0.01);
      for (Eigen::Index i = 0; i < b.rows(); ++i)
        for (int k = 0; k < 3; ++k) b(i, k) += jitter(rng);
    }
    const double g = 0.002;
    tree.refit(a, b, g);
    std::set<std::pair<int, int>> got;
    tree.self_pairs(a, b, [&](int s, int u) {
      REQUIRE(s != u);
      REQUIRE(got.insert({std::min(s, u), std::max(s, u)}).second);  // once
      REQUIRE(boxes_meet(a, b, t[std::size_t(s)], t[std::size_t(u)], g));
    });
    std::vector<std::set<int>> skip = skipped(tree, a, b);
    for (const std::set<int>& patch : searched_skips(tree, a, b)) skip.push_back(patch);
    skipped_patches += int(skip.size());
    for (int s = 0; s < int(t.size()); ++s)
      for (int u = s + 1; u < int(t.size()); ++u) {
        if (!boxes_meet(a, b, t[std::size_t(s)], t[std::size_t(u)], g) || got.count({s, u}))
          continue;
        bool held = false;
        for (const auto& p : skip) held = held || (p.count(s) && p.count(u));
        CAPTURE(s);
        CAPTURE(u);
        CHECK(held);
      }
    check_skipped(tree, a, b, t);
  }
  CHECK(skipped_patches > 12);
}

// A refit of the triangles around a few moved corners against a new tree refitted whole to the
// same motion: the same patches skipped, and self_pairs() and query() give exactly the fresh
// tree's pairs and triangles that involve a changed triangle (none when nothing changed), over
// bends and crumples, one partial refit after another.
TEST_CASE("NormalConeTree: a refit of the changed triangles alone agrees with a whole refit") {
  std::mt19937 rng(29);
  const auto [x0, t] = sheet(7);
  Tree tree;
  tree.build(x0, t);
  const Pts a = bend(x0, rng, 0.002);
  Pts b = bend(x0, rng, 0.004);
  const double g = 0.001;
  tree.refit(a, b, g);
  std::uniform_int_distribution<int> pick(0, int(x0.rows()) - 1);
  int pairs_seen = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const int moves = trial % 6;  // 0: nothing changed
    const double reach = trial < 15 ? 0.003 : 0.02;
    std::uniform_real_distribution<double> by(-reach, reach);
    std::set<int> points;
    for (int k = 0; k < moves; ++k) {
      const int i = pick(rng);
      points.insert(i);
      for (int c = 0; c < 3; ++c) b(i, c) += by(rng);
    }
    std::vector<char> changed(t.size(), 0);
    for (std::size_t s = 0; s < t.size(); ++s)
      for (int i : t[s]) changed[s] = changed[s] || points.count(i);
    tree.refit(a, b, g, changed);
    Tree fresh;
    fresh.build(x0, t);
    fresh.refit(a, b, g);
    CAPTURE(trial);
    REQUIRE(fresh.size() == tree.size());
    for (std::size_t k = 0; k < tree.size(); ++k)
      CHECK(tree.cannot_touch_itself(a, b, k) == fresh.cannot_touch_itself(a, b, k));
    std::set<std::pair<int, int>> got, want;
    tree.self_pairs(a, b, [&](int s, int u) {
      REQUIRE(got.insert({std::min(s, u), std::max(s, u)}).second);  // once
    });
    fresh.self_pairs(a, b, [&](int s, int u) {
      if (changed[std::size_t(s)] || changed[std::size_t(u)])
        want.insert({std::min(s, u), std::max(s, u)});
    });
    CHECK(got == want);
    pairs_seen += int(want.size());
    // Queries with each triangle's box grown by 2 mm.
    for (std::size_t s = 0; s < t.size(); s += 7) {
      contact::AlignedBox3<double> q{b.row(t[s][0]).transpose(), b.row(t[s][0]).transpose()};
      q.lo.array() -= 0.002;
      q.hi.array() += 0.002;
      std::set<int> seen, expected;
      tree.query(q, [&](int u) { REQUIRE(seen.insert(u).second); });
      fresh.query(q, [&](int u) {
        if (changed[std::size_t(u)]) expected.insert(u);
      });
      CHECK(seen == expected);
    }
    if (moves == 0) CHECK(got.empty());
  }
  CHECK(pairs_seen > 20);
}

// Bends and folds of growing size, up to a strip folded through itself: whatever the tree skips
// never touches itself at any of 101 times of the step, and a patch that crosses itself at the
// end of the step is never skipped; then crumpled ends.
TEST_CASE("NormalConeTree: a skipped patch never touches itself during the step") {
  std::mt19937 rng(13);
  const auto [x0, t] = sheet(7);
  Tree tree;
  tree.build(x0, t);
  int checked = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Pts a = bend(x0, rng, 0.002 * (trial % 5));
    // The end: bent again, or folded about the line x = 0.05 by an angle up to 1.2 pi (past pi
    // the right half passes through the left).
    Pts b = bend(x0, rng, 0.002 * (trial % 5));
    if (trial >= 10) {
      const double angle = 0.12 * M_PI * (trial - 9);
      for (Eigen::Index i = 0; i < b.rows(); ++i) {
        const double dx = x0(i, 0) - 0.05;
        if (dx <= 0) continue;
        b(i, 0) = 0.05 + dx * std::cos(angle);
        b(i, 1) = x0(i, 1);
        b(i, 2) = dx * std::sin(angle);
      }
    }
    tree.refit(a, b, 0.001);
    checked += check_skipped(tree, a, b, t);
    if (trial >= 10)  // a crossing at the end: the whole cloth is never skipped
      if (massspring::test::count_crossings(b, matrix(t, tree.patch(0))) > 0)
        CHECK_FALSE(tree.cannot_touch_itself(a, b, 0));
  }
  // Crumpled ends: random jumps of up to 1.5 cm on a 1.7 cm grid cross many small patches.
  std::uniform_real_distribution<double> jitter(-0.015, 0.015);
  for (int trial = 0; trial < 40; ++trial) {
    Pts b = x0;
    for (Eigen::Index i = 0; i < b.rows(); ++i)
      for (int k = 0; k < 3; ++k) b(i, k) += jitter(rng);
    tree.refit(x0, b, 0.001);
    checked += check_skipped(tree, x0, b, t);
  }
  CHECK(checked > 40);
}

// Every pair of disjoint nodes whose union passes union_cannot_touch_itself() (the test the
// search applies to the pairs it visits) is checked by check_patch(), on bends, folds past a half
// turn, crumples, and a point pushed across its neighbours with the border kept.
TEST_CASE("NormalConeTree: a union of two patches that passes never touches itself") {
  std::mt19937 rng(31);
  const auto [x0, t] = sheet(7);
  Tree tree;
  tree.build(x0, t);
  std::vector<std::set<int>> patches(tree.size());
  for (std::size_t k = 0; k < tree.size(); ++k) {
    const std::vector<int> p = tree.patch(k);
    patches[k] = std::set<int>(p.begin(), p.end());
  }
  std::uniform_real_distribution<double> jitter(-0.006, 0.006);
  int checked = 0;
  for (int trial = 0; trial < 16; ++trial) {
    const Pts a = bend(x0, rng, 0.002 * (trial % 4));
    Pts b = bend(x0, rng, 0.002 * (trial % 4));
    if (trial % 4 == 1) {  // folded about x = 0.04 by up to 1.2 pi
      const double angle = 0.3 * M_PI * (1 + trial / 4);
      for (Eigen::Index i = 0; i < b.rows(); ++i) {
        const double dx = x0(i, 0) - 0.04;
        if (dx <= 0) continue;
        b.row(i) << 0.04 + dx * std::cos(angle), x0(i, 1), dx * std::sin(angle);
      }
    } else if (trial % 4 == 2) {
      for (Eigen::Index i = 0; i < b.rows(); ++i)
        for (int k = 0; k < 3; ++k) b(i, k) += jitter(rng);
    } else if (trial % 4 == 3) {
      b = a;
      b(3 * 7 + 3, 0) += 0.035;  // the middle point across two cells; the border stays
    }
    tree.refit(a, b, 0.001);
    CAPTURE(trial);
    for (std::size_t i = 0; i < tree.size(); ++i)
      for (std::size_t j = i + 1; j < tree.size(); ++j) {
        bool disjoint = true;
        for (int s : patches[i]) disjoint = disjoint && !patches[j].count(s);
        if (!disjoint || !tree.union_cannot_touch_itself(a, b, i, j)) continue;
        std::set<int> patch = patches[i];
        patch.insert(patches[j].begin(), patches[j].end());
        ++checked;
        CAPTURE(i);
        CAPTURE(j);
        check_patch(a, b, t, patch);
      }
  }
  CHECK(checked > 100);
}

// A sheet folded by 135 degrees along a straight crease off the root's split: no axis holds the
// normals of a patch across the crease, and the nodes there are searched; pairs of their parts
// on one side of the crease lie in unions of two patches that pass. Against a search of the
// nodes alone (every overlapping pair that no skipped node holds), fewer pairs are listed, each
// among that search's, and every union reported skipped is checked.
TEST_CASE("NormalConeTree: unions of patches on one side of a crease are not searched") {
  const auto [flat, t] = sheet(17);
  for (const double crease : {0.03, 0.07}) {
    Pts x0 = flat;
    const double angle = 0.75 * M_PI;
    for (Eigen::Index i = 0; i < x0.rows(); ++i) {
      const double dx = flat(i, 0) - crease;
      if (dx <= 0) continue;
      x0(i, 0) = crease + dx * std::cos(angle);
      x0(i, 2) = dx * std::sin(angle);
    }
    const Pts x1 = x0.rowwise() + Eigen::RowVector3d(0.001, 0.002, 0.003);
    Tree tree;
    tree.build(flat, t);
    const double g = 0.001;
    tree.refit(x0, x1, g);
    CAPTURE(crease);
    REQUIRE_FALSE(tree.cannot_touch_itself(x0, x1, 0));
    std::set<std::pair<int, int>> listed, alone;
    const std::vector<std::set<int>> unions = searched_skips(tree, x0, x1, &listed);
    const std::vector<std::set<int>> nodes = skipped(tree, x0, x1);
    for (int s = 0; s < int(t.size()); ++s)
      for (int u = s + 1; u < int(t.size()); ++u) {
        if (!boxes_meet(x0, x1, t[std::size_t(s)], t[std::size_t(u)], g)) continue;
        bool held = false;
        for (const auto& p : nodes) held = held || (p.count(s) && p.count(u));
        if (!held) alone.insert({s, u});
      }
    for (const auto& q : listed) CHECK(alone.count(q));
    CHECK(listed.size() < alone.size());
    CHECK(!unions.empty());
    for (const std::set<int>& patch : unions) check_patch(x0, x1, t, patch);
  }
}

// Motions whose ends look harmless: each half of the test must refuse them on its own.
TEST_CASE("NormalConeTree: a turn that collapses mid-step and a fold inside a fixed border") {
  const auto [x0, t] = sheet(7);
  Tree tree;
  tree.build(x0, t);
  SUBCASE("a half turn in its plane: star-shaped at both ends, a point at mid-step") {
    const Eigen::Vector3d c(0.05, -0.05, 0);
    Pts x1 = x0;
    for (Eigen::Index i = 0; i < x0.rows(); ++i)
      x1.row(i) = (2 * c - x0.row(i).transpose()).transpose();
    tree.refit(x0, x1, 0.001);
    CHECK_FALSE(tree.cannot_touch_itself(x0, x1, 0));
    check_skipped(tree, x0, x1, t);
  }
  SUBCASE("a point pushed across two cells in the plane: the border stays, triangles turn over") {
    Pts x1 = x0;
    const int i = 3 * 7 + 3;  // the middle point
    x1(i, 0) += 0.035;
    REQUIRE(massspring::test::count_crossings(x1, matrix(t, tree.patch(0))) > 0);
    tree.refit(x0, x1, 0.001);
    CHECK_FALSE(tree.cannot_touch_itself(x0, x1, 0));
    check_skipped(tree, x0, x1, t);
  }
}

TEST_CASE("NormalConeTree: the contour rule refuses a ring and a flipped triangle") {
  SUBCASE("a flat ring (no disk) is never skipped whole") {
    // A 5 x 5 grid without its middle cell's two triangles.
    auto [x, t] = sheet(5);
    std::vector<Tri> ring;
    for (const Tri& tri : t) {
      const Eigen::Vector3d c = (x.row(tri[0]) + x.row(tri[1]) + x.row(tri[2])).transpose() / 3;
      if (std::abs(c.x() - 0.05) < 0.0125 && std::abs(c.y() + 0.05) < 0.0125) continue;
      ring.push_back(tri);
    }
    REQUIRE(ring.size() == t.size() - 2);
    Tree tree;
    tree.build(x, ring);
    tree.refit(x, x, 0.001);
    CHECK_FALSE(tree.cannot_touch_itself(x, x, 0));
  }
  SUBCASE("a disk curled in its plane until its ends overlap: not star-shaped") {
    // Column x goes to the angle 2.2 pi x / 0.1 and row y to the radius 0.03 - y: every
    // triangle keeps its orientation (the normals have an axis), the ends of the curl lie on one
    // another.
    auto [x, t] = sheet(7);
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      const double angle = 2.2 * M_PI * x(i, 0) / 0.1, radius = 0.03 - x(i, 1);
      x.row(i) << radius * std::cos(angle), radius * std::sin(angle), 0;
    }
    Tree tree;
    tree.build(x, t);
    tree.refit(x, x, 0.001);
    REQUIRE(massspring::test::count_crossings(x, matrix(t, tree.patch(0))) > 0);
    CHECK_FALSE(tree.cannot_touch_itself(x, x, 0));
    check_skipped(tree, x, x, t);
  }
  SUBCASE("a flipped triangle leaves no axis") {
    auto [x, t] = sheet(5);
    std::swap(t[7][1], t[7][2]);
    Tree tree;
    tree.build(x, t);
    tree.refit(x, x, 0.001);
    CHECK_FALSE(tree.cannot_touch_itself(x, x, 0));
    for (std::size_t k = 0; k < tree.size(); ++k) {
      const std::vector<int> p = tree.patch(k);
      if (p.size() > 1 && std::count(p.begin(), p.end(), 7))
        CHECK_FALSE(tree.cannot_touch_itself(x, x, k));
    }
  }
}
