// contact/broad_phase/box_tree.hpp. Oracles: the tree's invariants checked node by node (each
// primitive in one leaf, children splitting their parent's primitives, the depth bound of the
// file comment), every node's box against the box of its primitives computed here by brute
// force, a refit of the changed primitives against a whole refit, and a descent against the
// brute-force list of the boxes that overlap a query.
#include <doctest/doctest.h>

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <massspring/contact/broad_phase/box_tree.hpp>
#include <massspring/error.hpp>
#include <random>
#include <vector>

namespace {
using TreeBox = massspring::contact::AlignedBox3<double>;
using BoxTree = massspring::contact::BoxTree<double>;

std::vector<TreeBox> scattered_boxes(std::mt19937& rng, int m, double spread, double size) {
  std::uniform_real_distribution<double> at(-spread, spread), extent(0, size);
  std::vector<TreeBox> boxes;
  for (int i = 0; i < m; ++i) {
    TreeBox b;
    b.lo = Eigen::Vector3d(at(rng), at(rng), at(rng));
    b.hi = b.lo + Eigen::Vector3d(extent(rng), extent(rng), extent(rng));
    boxes.push_back(b);
  }
  return boxes;
}

std::vector<Eigen::Vector3d> centres_of(const std::vector<TreeBox>& boxes) {
  std::vector<Eigen::Vector3d> c;
  for (const TreeBox& b : boxes) c.push_back(b.centre());
  return c;
}

bool same_box(const TreeBox& a, const TreeBox& b) { return a.lo == b.lo && a.hi == b.hi; }

// The tree's invariants and each node's box against its primitives' boxes; returns the depth.
int check_tree(const BoxTree& tree, const std::vector<TreeBox>& boxes, int leaf_size) {
  const int m = int(boxes.size());
  REQUIRE(int(tree.size()) <= std::max(0, 2 * m - 1));
  std::vector<int> leaves_holding(std::size_t(m), 0);
  int depth = 0;
  std::function<void(std::size_t, int)> walk = [&](std::size_t k, int level) {
    const BoxTree::Node& n = tree.node(k);
    depth = std::max(depth, level);
    REQUIRE(n.count() >= 1);
    auto expected = TreeBox::empty();
    for (int s = n.begin; s < n.end; ++s)
      expected = expected.merged(boxes[std::size_t(tree.primitive(s))]);
    CHECK(same_box(n.box, expected));
    if (n.is_leaf()) {
      CHECK(n.count() <= leaf_size);
      for (int s = n.begin; s < n.end; ++s) {
        ++leaves_holding[std::size_t(tree.primitive(s))];
        CHECK(tree.leaf_of(tree.primitive(s)) == int(k));
      }
      return;
    }
    const BoxTree::Node& l = tree.node(std::size_t(n.left));
    const BoxTree::Node& r = tree.node(std::size_t(n.right));
    // Preorder, and the children split the parent's slots, each with at most 7/8 of them.
    CHECK(std::size_t(n.left) > k);
    CHECK(std::size_t(n.right) > k);
    CHECK(l.begin == n.begin);
    CHECK(l.end == r.begin);
    CHECK(r.end == n.end);
    CHECK(8 * std::max(l.count(), r.count()) <= 7 * n.count() + 8);
    walk(std::size_t(n.left), level + 1);
    walk(std::size_t(n.right), level + 1);
  };
  if (m > 0) walk(0, 1);
  for (int p = 0; p < m; ++p) CHECK(leaves_holding[std::size_t(p)] == 1);
  if (m > 0) CHECK(depth <= std::log(double(m)) / std::log(8.0 / 7.0) + 1 + 1e-9);
  return depth;
}
}  // namespace

TEST_CASE("BoxTree: each primitive in one leaf, every box the box of its primitives") {
  std::mt19937 rng(3);
  for (const int leaf_size : {1, 4}) {
    for (const int m : {0, 1, 2, 5, 37, 500}) {
      CAPTURE(leaf_size);
      CAPTURE(m);
      const auto boxes = scattered_boxes(rng, m, 1.0, 0.2);
      BoxTree tree;
      tree.build(centres_of(boxes), leaf_size);
      tree.refit([&](int p) { return boxes[std::size_t(p)]; });
      check_tree(tree, boxes, leaf_size);
    }
  }
}

TEST_CASE("BoxTree: equal centres split at the median and keep the depth bound") {
  // The middle of a zero-length side leaves every primitive on one side.
  const std::vector<TreeBox> boxes(300, TreeBox{Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()});
  BoxTree tree;
  tree.build(centres_of(boxes), 1);
  tree.refit([&](int p) { return boxes[std::size_t(p)]; });
  const int depth = check_tree(tree, boxes, 1);
  CHECK(depth <= 10);  // halves: ceil(log2 300) + 1
}

TEST_CASE("BoxTree: a refit of the changed primitives gives the boxes of a whole refit") {
  std::mt19937 rng(5);
  auto boxes = scattered_boxes(rng, 200, 1.0, 0.1);
  BoxTree tree;
  tree.build(centres_of(boxes), 2);
  tree.refit([&](int p) { return boxes[std::size_t(p)]; });
  std::vector<char> changed(boxes.size() + 3, 0);  // entries past the primitives are not read
  std::uniform_real_distribution<double> shift(-0.3, 0.3);
  for (std::size_t p = 0; p < boxes.size(); p += 17) {
    changed[p] = 1;
    const Eigen::Vector3d d(shift(rng), shift(rng), shift(rng));
    boxes[p].lo += d;
    boxes[p].hi += d;
  }
  changed.back() = 1;
  tree.refit([&](int p) { return boxes[std::size_t(p)]; }, changed);
  check_tree(tree, boxes, 2);
  // Exactly the nodes above a changed primitive were fitted.
  for (std::size_t k = 0; k < tree.size(); ++k) {
    const BoxTree::Node& n = tree.node(k);
    bool holds = false;
    for (int s = n.begin; s < n.end; ++s) holds = holds || changed[std::size_t(tree.primitive(s))];
    CHECK(tree.changed(k) == holds);
  }
}

TEST_CASE(
    "BoxTree: a descent by box overlap visits each overlapping primitive once (brute force)") {
  std::mt19937 rng(9);
  const auto boxes = scattered_boxes(rng, 400, 1.0, 0.3);
  for (const int leaf_size : {1, 3, 8}) {
    BoxTree tree;
    tree.build(centres_of(boxes), leaf_size);
    tree.refit([&](int p) { return boxes[std::size_t(p)]; });
    const auto queries = scattered_boxes(rng, 100, 1.2, 0.4);
    int hits = 0;
    for (const TreeBox& query : queries) {
      std::vector<int> seen(boxes.size(), 0);
      tree.descend([&](std::size_t k) { return tree.node(k).box.overlaps(query); },
                   [&](int p) {
                     if (boxes[std::size_t(p)].overlaps(query)) ++seen[std::size_t(p)];
                   });
      for (std::size_t p = 0; p < boxes.size(); ++p) {
        const bool overlap = (boxes[p].lo.array() <= query.hi.array()).all() &&
                             (query.lo.array() <= boxes[p].hi.array()).all();
        REQUIRE(seen[p] == int(overlap));
        hits += overlap;
      }
    }
    CHECK(hits > 50);  // about one overlap a query
  }
}

TEST_CASE("BoxTree: a leaf size below 1 is refused") {
  BoxTree tree;
  CHECK_THROWS_AS(tree.build({Eigen::Vector3d::Zero()}, 0), massspring::Error);
}
