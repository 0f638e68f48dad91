#pragma once
/// @file
/// @brief BoxTree: the one bounding-volume hierarchy of contact/, a binary tree of axis-aligned
/// boxes over m primitives (triangles, in its two users): built once, refitted when the
/// primitives move, queried by a pruned descent. A mesh collider's hierarchy
/// (colliders/triangle_mesh.hpp) fits it once to its static triangles; self-collision's
/// normal-cone tree (broad_phase/normal_cone_tree.hpp) refits it every step to the triangles'
/// swept boxes and adds its normal bounds and contours to the same nodes.
///
/// **Build.** A node over more than `leaf_size` primitives splits them in two at the middle of
/// the longest side of the box of their centres, or at the median along that side when the
/// middle leaves fewer than max(1, count / 8) on one side; so each child holds at most 7/8 of its
/// parent's primitives and the depth is at most log(m) / log(8/7) + 1 (about 5.2 log2 m). Cost
/// O(m log m). Nodes are stored in preorder (a parent before its children), so a sweep from the
/// last node to the first meets a node after both of its children.
///
/// **Refit.** A leaf's box is the smallest box holding its primitives' boxes, an inner node's
/// the smallest holding its children's. Cost O(m); the overload with change flags refits only
/// the nodes above a changed primitive, after O(m) flag tests.
///
/// **Descent.** Depth first, left child before right, entering only the nodes the caller's test
/// accepts; it allocates nothing, and its recursion is as deep as the tree.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <vector>

#include "massspring/contact/aligned_box.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief A bounding-volume hierarchy of axis-aligned boxes (see the file comment).
template <class Scalar>
class BoxTree {
 public:
  using V3 = Vector3<Scalar>;
  using Box = AlignedBox3<Scalar>;

  /// @brief A node: its children (-1 for a leaf), its primitives (slots [begin, end), see
  /// primitive()) and its box from the last refit.
  struct Node {
    int left = -1, right = -1;
    int begin = 0, end = 0;
    Box box;
    [[nodiscard]] bool is_leaf() const { return left < 0; }
    [[nodiscard]] int count() const { return end - begin; }
  };

  /// @brief Builds the tree over primitives 0 .. centres.size() - 1, split by their centres
  /// [m]; a leaf holds at most leaf_size (>= 1) of them. Boxes are empty until refit().
  void build(const std::vector<V3>& centres, int leaf_size) {
    if (leaf_size < 1) throw Error("BoxTree: leaf_size must be at least 1");
    const int m = int(centres.size());
    nodes_.clear();
    order_.resize(std::size_t(m));
    leaf_of_.assign(std::size_t(m), -1);
    for (int p = 0; p < m; ++p) order_[std::size_t(p)] = p;
    nodes_.reserve(std::size_t(std::max(0, 2 * m - 1)));
    if (m > 0) split(centres, leaf_size, 0, m);
    changed_.assign(nodes_.size(), 1);
  }

  /// @brief The number of nodes (at most 2 m - 1; node 0 is the root).
  [[nodiscard]] std::size_t size() const { return nodes_.size(); }
  [[nodiscard]] bool empty() const { return nodes_.empty(); }
  [[nodiscard]] const Node& node(std::size_t k) const { return nodes_[k]; }
  /// @brief The primitive in slot s: node k holds primitive(s) for s in [begin, end).
  [[nodiscard]] int primitive(int s) const { return order_[std::size_t(s)]; }
  /// @brief The leaf that holds primitive p.
  [[nodiscard]] int leaf_of(int p) const { return leaf_of_[std::size_t(p)]; }
  /// @brief Whether the last refit() fitted node k (always, after the overload without flags).
  [[nodiscard]] bool changed(std::size_t k) const { return changed_[k] != 0; }

  /// @brief Fits every node; box_of(p) gives primitive p's box.
  template <class BoxOf>
  void refit(BoxOf&& box_of) {
    changed_.assign(nodes_.size(), 1);
    for (std::size_t k = nodes_.size(); k-- > 0;) fit(box_of, k);
  }

  /// @brief Fits the nodes that hold a primitive p with changed[p] != 0 (one flag per primitive;
  /// entries past them are not read). The other nodes keep their boxes from the last refit,
  /// which must still hold their primitives' boxes.
  template <class BoxOf>
  void refit(BoxOf&& box_of, const std::vector<char>& changed) {
    changed_.assign(nodes_.size(), 0);
    for (std::size_t p = 0; p < leaf_of_.size(); ++p)
      if (changed[p]) changed_[std::size_t(leaf_of_[p])] = 1;
    for (std::size_t k = nodes_.size(); k-- > 0;) {
      const Node& n = nodes_[k];
      if (!n.is_leaf())
        changed_[k] = changed_[std::size_t(n.left)] || changed_[std::size_t(n.right)];
      if (changed_[k]) fit(box_of, k);
    }
  }

  /// @brief From the root, depth first and left before right: enters node k when enter(k) is
  /// true, and then calls visit(p) for each primitive p of an entered leaf.
  template <class Enter, class Visit>
  void descend(Enter&& enter, Visit&& visit) const {
    if (!nodes_.empty()) descend(0, enter, visit);
  }

 private:
  // Splits order_[b, e) into a node and its subtrees; returns the node's index.
  int split(const std::vector<V3>& centres, int leaf_size, int b, int e) {
    const int id = int(nodes_.size());
    nodes_.emplace_back();
    nodes_[std::size_t(id)].begin = b;
    nodes_[std::size_t(id)].end = e;
    const auto centre = [&](int p) -> const V3& { return centres[std::size_t(p)]; };
    if (e - b <= leaf_size) {
      for (int s = b; s < e; ++s) leaf_of_[std::size_t(order_[std::size_t(s)])] = id;
      return id;
    }
    V3 lo = centre(order_[std::size_t(b)]), hi = lo;
    for (int s = b; s < e; ++s) {
      lo = lo.cwiseMin(centre(order_[std::size_t(s)]));
      hi = hi.cwiseMax(centre(order_[std::size_t(s)]));
    }
    int axis = 0;
    (hi - lo).maxCoeff(&axis);
    const Scalar middle = (lo(axis) + hi(axis)) / 2;
    const auto first = order_.begin() + b, last = order_.begin() + e;
    int m = int(std::partition(first, last, [&](int p) { return centre(p)(axis) < middle; }) -
                order_.begin());
    if (std::min(m - b, e - m) < std::max(1, (e - b) / 8)) {
      m = b + (e - b) / 2;
      std::nth_element(first, order_.begin() + m, last,
                       [&](int p, int q) { return centre(p)(axis) < centre(q)(axis); });
    }
    const int left = split(centres, leaf_size, b, m);
    const int right = split(centres, leaf_size, m, e);
    nodes_[std::size_t(id)].left = left;
    nodes_[std::size_t(id)].right = right;
    return id;
  }

  template <class BoxOf>
  void fit(BoxOf& box_of, std::size_t k) {
    Node& n = nodes_[k];
    if (n.is_leaf()) {
      n.box = box_of(order_[std::size_t(n.begin)]);
      for (int s = n.begin + 1; s < n.end; ++s)
        n.box = n.box.merged(box_of(order_[std::size_t(s)]));
    } else {
      n.box = nodes_[std::size_t(n.left)].box.merged(nodes_[std::size_t(n.right)].box);
    }
  }

  template <class Enter, class Visit>
  void descend(int k, Enter& enter, Visit& visit) const {
    if (!enter(std::size_t(k))) return;
    const Node& n = nodes_[std::size_t(k)];
    if (n.is_leaf()) {
      for (int s = n.begin; s < n.end; ++s) visit(order_[std::size_t(s)]);
      return;
    }
    descend(n.left, enter, visit);
    descend(n.right, enter, visit);
  }

  std::vector<Node> nodes_;
  std::vector<int> order_;     // primitives by slot
  std::vector<int> leaf_of_;   // a primitive's leaf
  std::vector<char> changed_;  // nodes the last refit() fitted
};

}  // namespace massspring::contact
