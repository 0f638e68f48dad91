#pragma once
/// @file
/// @brief NormalConeTree: a bounding-volume hierarchy over a triangle surface that lists the pairs
/// of triangles whose swept boxes overlap, skipping whole patches that cannot touch themselves
/// over the step (the broad phase of self-collision, contact/response/surface_candidates.hpp).
///
/// The tree is a BoxTree (broad_phase/box_tree.hpp) over the triangles, split by the centres of
/// their boxes in the positions given to build(), one triangle a leaf. Each node is a patch of
/// the surface. Per step, refit() gives each node the box of its triangles' straight-line sweeps
/// x0 -> x1, grown by g, and the range of its triangles' normals over the whole step along seven
/// fixed directions.
///
/// **Why a patch may be skipped** (Volino and Magnenat-Thalmann 1994, "Efficient self-collision
/// detection on smoothly discretized surface animations using geometrical shape regularity";
/// over a time step, Tang et al. 2009, "Interactive continuous collision detection between
/// deformable models using connectivity-based culling"; the contour test, Schvartzman, Perez and
/// Otaduy 2010, "Star-contours for efficient hierarchical self-collision detection"). With the
/// corners moving linearly, a triangle's normal is a combination with non-negative weights of
/// its three Bernstein coefficients Bk (contact/broad_phase/normal_bounds.hpp). If a unit axis a
/// has a . Bk > 0 for every triangle of a patch, each triangle keeps its orientation when
/// projected along a, at every t in [0, 1]. If moreover the
/// patch is a topological disk whose boundary loop, projected, stays star-shaped about the
/// centroid c(t) of one of its triangles (a . ((p(t) - c(t)) x (q(t) - c(t))) > 0 for each
/// boundary edge p -> q, again a
/// quadratic checked on its Bernstein coefficients), the projection is one-to-one at every t, so
/// no two points of the patch ever meet: no point crosses a triangle and no edge crosses an edge
/// of the patch during the step. Such a patch is not searched inside.
///
/// **Pairs of patches.** The search between two disjoint patches whose boxes overlap is skipped
/// when their union passes the same test: two disks glued along one arc of their boundary loops
/// (traversed in opposite directions, no other vertex shared) form a disk whose loop is the two
/// loops' other arcs; its normal bounds are the two patches' least and greatest, and the centre is
/// the larger patch's. Patches that meet across the border between two siblings are mostly of
/// this kind (neighbours on one layer of a node that bends too much as a whole), so the search
/// of a smoothly bent cloth stops along those borders instead of descending to every pair of
/// triangles that touch there.
///
/// **The axis** comes from each node's NormalBounds (the ranges of its triangles' Bk along seven
/// fixed directions; a patch whose Bk lie within 53 degrees of a common direction always has
/// one). The star coefficients must exceed 1e-9 of their scale, which keeps rounding on the safe
/// side.
///
/// Cost: build (once per surface) O(m log m) where a node's loop comes from gluing its
/// children's, up to O(m log^2 m) where it is traced from the triangles (a tree split in a
/// crumpled shape); refit O(m); a search O(nodes visited), which for a cloth that bends smoothly
/// grows with the length of the borders between its skipped patches, not with its area. After
/// some corners move again, a refit of the triangles that hold them and a search of the pairs
/// that involve one cost O(m) flag tests plus the changed nodes, and the nodes visited above them.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "massspring/contact/aligned_box.hpp"
#include "massspring/contact/broad_phase/box_tree.hpp"
#include "massspring/contact/broad_phase/normal_bounds.hpp"
#include "massspring/contact/broad_phase/star_contour.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The tree of one triangle surface (see the file comment).
template <class Scalar>
class NormalConeTree {
 public:
  using V3 = Vector3<Scalar>;
  using Box = AlignedBox3<Scalar>;
  using Triangle = std::array<int, 3>;

  /// @brief Builds the tree of `triangles` (corner indices into x's rows, consistently oriented
  /// for patches to be skipped), split by their positions in x.
  void build(const Points<Scalar>& x, const std::vector<Triangle>& triangles) {
    triangles_ = triangles;
    loops_.clear();
    const int m = int(triangles_.size());
    std::vector<V3> centres(static_cast<std::size_t>(m));
    for (int t = 0; t < m; ++t) centres[std::size_t(t)] = corners_box(x, t).centre();
    tree_.build(centres, 1);
    patches_.assign(tree_.size(), Patch{});
    loops_.reserve(std::size_t(8 * m));
    position_.assign(std::size_t(x.rows()), -1);
    // Children before their parent: a parent's loop is glued from its children's.
    for (std::size_t k = tree_.size(); k-- > 0;) {
      const auto& n = tree_.node(k);
      patches_[k].home =
          n.is_leaf()
              ? corners_box(x, tree_.primitive(n.begin))
              : patches_[std::size_t(n.left)].home.merged(patches_[std::size_t(n.right)].home);
      contour(x, k);
    }
    normals_.resize(tree_.size());
    std::size_t longest = 0;
    for (const Patch& p : patches_)
      longest = std::max(longest, std::size_t(p.loop_end - p.loop_begin));
    union_loop_.reserve(2 * longest);
  }

  /// @brief The number of nodes (2 m - 1 for m > 0 triangles).
  [[nodiscard]] std::size_t size() const { return tree_.size(); }

  /// @brief Each node's box over x0 -> x1 grown by g [m], and its normal bounds. Every triangle
  /// counts as changed (see the overload below).
  void refit(const Points<Scalar>& x0, const Points<Scalar>& x1, Scalar g) {
    tree_.refit([&](int t) { return swept_box(x0, x1, g, t); });
    fit_normals(x0, x1);
  }

  /// @brief refit() of the nodes whose patch holds a triangle t with changed[t] != 0 (a flag
  /// for each triangle given to build(), in its order; entries past them are not read), cost
  /// O(nodes) flag tests plus O(changed nodes) fits. The other nodes keep the last refit's boxes
  /// and normal bounds, which must be those of this x0 and g and of x1 at the corners of every
  /// unchanged triangle.
  void refit(const Points<Scalar>& x0, const Points<Scalar>& x1, Scalar g,
             const std::vector<char>& changed) {
    tree_.refit([&](int t) { return swept_box(x0, x1, g, t); }, changed);
    fit_normals(x0, x1);
  }

  /// @brief Calls visit(s, t) once for each pair of distinct triangles (indices into the
  /// triangles given to build()) whose boxes from the last refit() overlap, except pairs inside a
  /// patch that cannot touch itself over x0 -> x1 (the motion given to refit()), and pairs of
  /// two triangles that the last refit() did not change.
  template <class Visit>
  void self_pairs(const Points<Scalar>& x0, const Points<Scalar>& x1, Visit&& visit) {
    self_pairs(x0, x1, visit, [](std::size_t, std::size_t) {});
  }

  /// @brief self_pairs(), also calling skipped(i, j) for each patch not searched: the patch of
  /// node i alone (j == i, a node that passes cannot_touch_itself()), or the union of the
  /// disjoint patches of nodes i and j, whose pairs between the two are then not visited.
  template <class Visit, class Skipped>
  void self_pairs(const Points<Scalar>& x0, const Points<Scalar>& x1, Visit&& visit,
                  Skipped&& skipped) {
    if (!tree_.empty()) self(x0, x1, 0, visit, skipped);
  }

  /// @brief The triangles of node k's patch (node 0: all of them).
  [[nodiscard]] std::vector<int> patch(std::size_t k) const {
    std::vector<int> out;
    for (int s = tree_.node(k).begin; s < tree_.node(k).end; ++s) out.push_back(tree_.primitive(s));
    return out;
  }

  /// @brief Calls visit(t) for each triangle t that the last refit() changed and whose box
  /// overlaps b.
  template <class Visit>
  void query(const Box& b, Visit&& visit) const {
    tree_.descend([&](std::size_t k) { return tree_.changed(k) && tree_.node(k).box.overlaps(b); },
                  visit);
  }

  /// @brief Whether the patch of node k (0: the whole surface) passes the test of the file
  /// comment for the motion given to the last refit().
  [[nodiscard]] bool cannot_touch_itself(const Points<Scalar>& x0, const Points<Scalar>& x1,
                                         std::size_t k) const {
    V3 a;
    const Patch& p = patches_[k];
    return p.centre >= 0 && normals_[k].axis(a) &&
           star(x0, x1, a, p.centre, loops_.data() + p.loop_begin, p.loop_end - p.loop_begin);
  }

  /// @brief Whether the union of the patches of nodes i and j (disjoint: neither holds the
  /// other) passes the test of the file comment for the motion given to the last refit(), as
  /// self_pairs() tests the pairs of nodes it visits; false for two leaves, which it never tests.
  [[nodiscard]] bool union_cannot_touch_itself(const Points<Scalar>& x0, const Points<Scalar>& x1,
                                               std::size_t i, std::size_t j) {
    bool may_glue = true;
    return cannot_touch(x0, x1, int(i), int(j), may_glue);
  }

 private:
  // What a node adds to the box tree's: its patch's boundary loop and star centre, and its box
  // in the positions given to build().
  struct Patch {
    int loop_begin = 0, loop_end = 0;  // boundary loop in loops_
    int centre = -1;  // the triangle whose centroid is the star's centre; -1: not a disk
    Box home;         // the box of its triangles' corners in the x given to build()
  };
  using Normals = NormalBounds<Scalar>;

  static V3 row(const Points<Scalar>& x, int i) { return x.row(i).transpose(); }

  // The box of triangle t's corners in x.
  Box corners_box(const Points<Scalar>& x, int t) const {
    const Triangle& c = triangles_[std::size_t(t)];
    const V3 a = row(x, c[0]), b = row(x, c[1]), d = row(x, c[2]);
    return {a.cwiseMin(b).cwiseMin(d), a.cwiseMax(b).cwiseMax(d)};
  }

  // Triangle t's box over x0 -> x1, grown by g.
  Box swept_box(const Points<Scalar>& x0, const Points<Scalar>& x1, Scalar g, int t) const {
    const Triangle& c = triangles_[std::size_t(t)];
    const V3 a0 = row(x0, c[0]), b0 = row(x0, c[1]), c0 = row(x0, c[2]);
    const V3 a1 = row(x1, c[0]), b1 = row(x1, c[1]), c1 = row(x1, c[2]);
    Box box{a0.cwiseMin(b0).cwiseMin(c0).cwiseMin(a1).cwiseMin(b1).cwiseMin(c1),
            a0.cwiseMax(b0).cwiseMax(c0).cwiseMax(a1).cwiseMax(b1).cwiseMax(c1)};
    box.lo.array() -= g;
    box.hi.array() += g;
    return box;
  }

  // The normal bounds of the nodes the last refit changed: a leaf's from its triangle's motion,
  // an inner node's from its children's.
  void fit_normals(const Points<Scalar>& x0, const Points<Scalar>& x1) {
    for (std::size_t k = tree_.size(); k-- > 0;) {
      if (!tree_.changed(k)) continue;
      const auto& n = tree_.node(k);
      if (n.is_leaf()) {
        const Triangle& c = triangles_[std::size_t(tree_.primitive(n.begin))];
        normals_[k] = Normals::of_triangle(row(x0, c[0]), row(x0, c[1]), row(x0, c[2]),
                                           row(x1, c[0]), row(x1, c[1]), row(x1, c[2]));
      } else {
        normals_[k] =
            Normals::merged(normals_[std::size_t(n.left)], normals_[std::size_t(n.right)]);
      }
    }
  }

  // Node k's boundary loop and star centre, when its patch is a topological disk: a triangle
  // with three distinct corners (loop a, b, c); two disks glued along one arc of their loops,
  // the left loop running s -> e along it and the right one e -> s, sharing no other vertex (then
  // the loop is the left one's e -> s and the right one's s -> e; cost O(the two loops)); or,
  // when the children are not such disks (a tree split in a folded shape), a patch that passes
  // trace() (cost O(triangles log triangles)). Its children's must be set.
  void contour(const Points<Scalar>& x, std::size_t k) {
    const auto& n = tree_.node(k);
    Patch& p = patches_[k];
    const int begin = int(loops_.size());
    if (n.is_leaf()) {
      const Triangle& c = triangles_[std::size_t(tree_.primitive(n.begin))];
      if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) return;
      loops_.insert(loops_.end(), c.begin(), c.end());
    } else if (!glue(patches_[std::size_t(n.left)], patches_[std::size_t(n.right)], loops_) &&
               !trace(n)) {
      return;
    }
    p.loop_begin = begin;
    p.loop_end = int(loops_.size());
    // The centre: the centroid of the patch's triangle nearest the mean of the loop.
    V3 mean = V3::Zero();
    for (int i = begin; i < p.loop_end; ++i) mean += row(x, loops_[std::size_t(i)]);
    mean /= Scalar(p.loop_end - begin);
    Scalar best = -1;
    for (int s = n.begin; s < n.end; ++s) {
      const int t = tree_.primitive(s);
      const Triangle& c = triangles_[std::size_t(t)];
      const Scalar d = ((row(x, c[0]) + row(x, c[1]) + row(x, c[2])) / 3 - mean).squaredNorm();
      if (best < 0 || d < best) {
        best = d;
        p.centre = t;
      }
    }
  }

  // Appends the boundary loop of node n's triangles to loops_ when they form a consistently
  // oriented disk: each directed edge once, the boundary edges (whose reverse is not in the
  // patch) one closed loop through distinct vertices, V - E + F = 1, the vertices connected.
  bool trace(const typename BoxTree<Scalar>::Node& n) {
    directed_.clear();
    vertices_.clear();
    for (int s = n.begin; s < n.end; ++s) {
      const Triangle& c = triangles_[std::size_t(tree_.primitive(s))];
      for (int j = 0; j < 3; ++j) {
        directed_.emplace_back(c[std::size_t(j)], c[std::size_t((j + 1) % 3)]);
        vertices_.push_back(c[std::size_t(j)]);
      }
    }
    std::sort(directed_.begin(), directed_.end());
    std::sort(vertices_.begin(), vertices_.end());
    vertices_.erase(std::unique(vertices_.begin(), vertices_.end()), vertices_.end());
    if (std::adjacent_find(directed_.begin(), directed_.end()) != directed_.end()) return false;
    boundary_.clear();
    for (const auto& d : directed_)
      if (!std::binary_search(directed_.begin(), directed_.end(),
                              std::make_pair(d.second, d.first)))
        boundary_.push_back(d);  // sorted by start, as directed_ is
    const std::size_t edges = (directed_.size() + boundary_.size()) / 2;
    const long chi = long(vertices_.size()) - long(edges) + long(n.end - n.begin);
    if (boundary_.empty() || chi != 1) return false;
    for (std::size_t k = 1; k < boundary_.size(); ++k)
      if (boundary_[k].first == boundary_[k - 1].first) return false;  // a vertex passed twice
    // Connected: union-find over the vertices along the edges.
    parent_.resize(vertices_.size());
    for (std::size_t k = 0; k < parent_.size(); ++k) parent_[k] = int(k);
    const auto find = [&](int k) {
      while (parent_[std::size_t(k)] != k) k = parent_[std::size_t(k)];
      return k;
    };
    const auto index = [&](int v) {
      return int(std::lower_bound(vertices_.begin(), vertices_.end(), v) - vertices_.begin());
    };
    std::size_t groups = vertices_.size();
    for (const auto& d : directed_) {
      const int a = find(index(d.first)), b = find(index(d.second));
      if (a != b) {
        parent_[std::size_t(a)] = b;
        --groups;
      }
    }
    if (groups != 1) return false;
    // Follow the loop; it must take every boundary edge.
    const std::size_t begin = loops_.size();
    int v = boundary_.front().first;
    for (std::size_t step = 0; step < boundary_.size(); ++step) {
      loops_.push_back(v);
      const auto it = std::lower_bound(boundary_.begin(), boundary_.end(), std::make_pair(v, -1));
      if (it == boundary_.end() || it->first != v) break;
      v = it->second;
    }
    if (v != boundary_.front().first || loops_.size() - begin != boundary_.size()) {
      loops_.resize(begin);
      return false;
    }
    return true;
  }

  // Appends the loop of the union of disks l and r to out (see contour()); false when they do
  // not meet along exactly one arc. The vertices are rows of the x given to build(). `edges`:
  // how many edges of l's loop r's has reversed.
  bool glue(const Patch& l, const Patch& r, std::vector<int>& out, int* edges = nullptr) {
    if (l.centre < 0 || r.centre < 0) return false;
    const int p = l.loop_end - l.loop_begin, q = r.loop_end - r.loop_begin;
    const auto lv = [&](int i) { return loops_[std::size_t(l.loop_begin + (i % p))]; };
    const auto rv = [&](int j) { return loops_[std::size_t(r.loop_begin + (j % q))]; };
    for (int j = 0; j < q; ++j) position_[std::size_t(rv(j))] = j;
    const auto at = [&](int v) { return position_[std::size_t(v)]; };
    // Edge i of l (lv(i) -> lv(i + 1)) is shared when r has lv(i + 1) -> lv(i).
    const auto shared = [&](int i) {
      const int j = at(lv(i + 1));
      return j >= 0 && at(lv(i)) >= 0 && rv(j + 1) == lv(i);
    };
    int count = 0, starts = 0, first = -1, common = 0;
    for (int i = 0; i < p; ++i) {
      const bool here = shared(i);
      count += here;
      if (here && !shared(i + p - 1)) {
        ++starts;
        first = i;
      }
      common += at(lv(i)) >= 0;
    }
    if (edges) *edges = count;
    bool ok = starts == 1 && count < p && count < q && common == count + 1;
    if (ok) {
      const int s = lv(first), e = lv(first + count);
      const int js = at(s);
      ok = rv(at(e) + count) == s;
      for (int i = first + count; ok && i <= first + p; ++i) out.push_back(lv(i));  // e .. s
      for (int m = 1; ok && m < q - count; ++m) out.push_back(rv(js + m));          // after s .. e
    }
    for (int j = 0; j < q; ++j) position_[std::size_t(rv(j))] = -1;
    return ok;
  }

  // The contour test of the file comment: the loop (count vertices) stays star-shaped about
  // the centroid of triangle `centre`, seen along the unit axis a, over the step.
  bool star(const Points<Scalar>& x0, const Points<Scalar>& x1, const V3& a, int centre,
            const int* loop, int count) const {
    const Triangle& t = triangles_[std::size_t(centre)];
    const V3 c0 = (row(x0, t[0]) + row(x0, t[1]) + row(x0, t[2])) / 3;
    const V3 c1 = (row(x1, t[0]) + row(x1, t[1]) + row(x1, t[2])) / 3;
    return loop_stays_star_shaped(x0, x1, a, c0, c1, loop, count);
  }

  template <class Visit, class Skipped>
  void self(const Points<Scalar>& x0, const Points<Scalar>& x1, int k, Visit& visit,
            Skipped& skipped) {
    const auto& n = tree_.node(std::size_t(k));
    if (!tree_.changed(std::size_t(k)) || n.is_leaf()) return;
    if (cannot_touch_itself(x0, x1, std::size_t(k))) {
      skipped(std::size_t(k), std::size_t(k));
      return;
    }
    self(x0, x1, n.left, visit, skipped);
    self(x0, x1, n.right, visit, skipped);
    pair(x0, x1, n.left, n.right, visit, skipped);
  }

  // Whether the union of the disjoint patches of nodes i and j passes the test of the file
  // comment (not both leaves: two triangles' pairs cost less to list than their union's test).
  // Sets `may_glue` false when their loops share no edge: an edge between a triangle of a
  // part of i's patch and one of a part of j's lies on both loops, so no union of such parts is
  // a disk glued along an arc either.
  bool cannot_touch(const Points<Scalar>& x0, const Points<Scalar>& x1, int i, int j,
                    bool& may_glue) {
    const auto& a = tree_.node(std::size_t(i));
    const auto& b = tree_.node(std::size_t(j));
    const Patch& pa = patches_[std::size_t(i)];
    const Patch& pb = patches_[std::size_t(j)];
    V3 axis;
    // Patches that share a vertex have home boxes that meet at it.
    if (!may_glue || pa.centre < 0 || pb.centre < 0 || (a.is_leaf() && b.is_leaf()) ||
        !pa.home.overlaps(pb.home) ||
        !Normals::merged(normals_[std::size_t(i)], normals_[std::size_t(j)]).axis(axis))
      return false;
    union_loop_.clear();  // reserved in build(): the two longest loops at most
    int edges = 0;
    if (!glue(pa, pb, union_loop_, &edges)) {
      may_glue = edges > 0;
      return false;
    }
    const int centre = a.count() >= b.count() ? pa.centre : pb.centre;
    return star(x0, x1, axis, centre, union_loop_.data(), int(union_loop_.size()));
  }

  template <class Visit, class Skipped>
  void pair(const Points<Scalar>& x0, const Points<Scalar>& x1, int i, int j, Visit& visit,
            Skipped& skipped, bool may_glue = true) {
    const auto& a = tree_.node(std::size_t(i));
    const auto& b = tree_.node(std::size_t(j));
    if (!(tree_.changed(std::size_t(i)) || tree_.changed(std::size_t(j))) || !a.box.overlaps(b.box))
      return;
    if (cannot_touch(x0, x1, i, j, may_glue)) {
      skipped(std::size_t(i), std::size_t(j));
      return;
    }
    if (a.is_leaf() && b.is_leaf()) {
      visit(tree_.primitive(a.begin), tree_.primitive(b.begin));
      return;
    }
    if (b.is_leaf() || (!a.is_leaf() && a.count() >= b.count())) {
      pair(x0, x1, a.left, j, visit, skipped, may_glue);
      pair(x0, x1, a.right, j, visit, skipped, may_glue);
    } else {
      pair(x0, x1, i, b.left, visit, skipped, may_glue);
      pair(x0, x1, i, b.right, visit, skipped, may_glue);
    }
  }

  std::vector<Triangle> triangles_;
  BoxTree<Scalar> tree_;
  std::vector<Patch> patches_;    // by node
  std::vector<Normals> normals_;  // by node
  std::vector<int> loops_;
  // Scratch.
  std::vector<int> position_;    // a vertex's place in a loop, or -1 (glue()'s scratch)
  std::vector<int> union_loop_;  // the loop of two patches' union (cannot_touch()'s scratch)
  std::vector<std::pair<int, int>> directed_, boundary_;
  std::vector<int> vertices_, parent_;
};

}  // namespace massspring::contact
