#pragma once
/// @file
/// @brief SurfaceCandidates: the broad phase of surface contact (contact/response/
/// surface_contact.hpp): the point-triangle and edge-edge pairs whose swept boxes overlap, for
/// the motion x0 -> x1 of SurfaceElements, kept up to date while the rounds of impulses move
/// some end positions.
///
/// A pair is a candidate when the boxes of its two elements' straight-line sweeps overlap, each
/// grown on every side by SurfaceElements::grow_of() (the cloth's by `grow`, an obstacle's by its
/// gap); pairs of an element with itself, of elements that share a
/// point, and pairs SurfaceElements::pair_gap() excludes (obstacle with obstacle; cloth with
/// cloth without self-collision) are left out.
///
/// **With self-collision** full() and next_step() list the candidates of the current motion
/// afresh through contact/broad_phase/normal_cone_tree.hpp, built once per surface: the tree's
/// overlapping pairs of the cloth's triangles give the cloth's pairs (each point and edge paired
/// from one triangle that has it), and the obstacles' elements are queried against the tree's
/// boxes. One more kind of pair is left out: a point and a triangle, or two edges, inside a patch
/// of the cloth that cannot touch itself over the step (an axis on the positive side of all its
/// normals, a star-shaped boundary: see that file). Cost O(triangles + nodes visited + pairs log
/// pairs); a cloth that bends smoothly has few pairs, as its neighbours on one layer are not
/// paired. refresh() lists again only the pairs of the elements whose points' end positions
/// changed, refitting the tree above their triangles alone; a pair of two unchanged elements is
/// kept, or stays out when the tree skipped it for the same motion of its points (cost O(elements)
/// flag tests, plus the changed part of the tree).
///
/// **Without self-collision** every pair has an obstacle's element and one of the cloth, and the
/// list is kept from step to step. Each element keeps a stored box that holds its current one: the
/// box of its points at the start and end of the step and at the end of a next step at the same
/// velocity (x1 + (x1 - x0)), grown by grow_of() and a further margin m. The list holds every pair
/// whose stored boxes overlap: a superset of the candidates while every current box stays inside
/// its stored box. full() stores every element's box, hashes the obstacles'
/// (contact/broad_phase/box_hash.hpp) and queries the cloth's elements against them.
/// refresh() follows a round that moved the end positions of the points flagged in `moved`, and
/// next_step() a new step of the same elements (every point moved): an element whose current box
/// has left its stored box has escaped; its stored box is taken again from its current motion, its
/// pairs are dropped and listed again from that box, against a hash of the elements in place and a
/// second hash of the escaped ones (the first still has them in the cells of their old boxes): a
/// cloth element against the obstacles' elements alone, an obstacle's against every element (a
/// hash of the cloth's is built only when an obstacle's element escapes, as a moving collider's
/// do). Elements that stay inside keep their pairs untouched, so a cloth that rests, or whose
/// displacement changes by less than m from one step to the next, costs O(elements) a step, not a
/// hash query per element.
/// More than a quarter of the elements of a kind escaped since the last full() (then a new hash
/// costs less than the queries), or other elements than the last step's (a new surface, collider
/// or self-collision switch): full() instead.
/// Cost: full() O(obstacles' elements x cells per box + cloth's elements); refresh() and
/// next_step() O(elements + pairs), plus one query per escaped element.
///
/// Work arrays keep their capacity: after the first steps nothing allocates.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "massspring/contact/aligned_box.hpp"
#include "massspring/contact/broad_phase/normal_cone_tree.hpp"
#include "massspring/contact/response/detail/element_boxes.hpp"
#include "massspring/contact/response/surface_elements.hpp"
#include "massspring/detail/merge_sorted_tail.hpp"

namespace massspring::contact {

/// @brief Candidate pairs of a SurfaceElements motion (see the file comment).
template <class Scalar>
class SurfaceCandidates {
 public:
  using Box = AlignedBox3<Scalar>;
  using Elements = SurfaceElements<Scalar>;
  using Element = typename Elements::Element;

  /// @brief The candidates, point-triangle and edge-edge, each once, in ascending order of
  /// (kind, a, b) whatever the list's history: the rounds of impulses apply them in this order,
  /// so a step gives the same result after a full() as after a next_step() (a state saved and
  /// resumed continues bit for bit).
  [[nodiscard]] const std::vector<ElementPair>& pairs() const { return pairs_; }

  /// @brief Lists every candidate of e's motion with the cloth's boxes grown by `grow` [m]
  /// (>= 0); without self-collision, storing boxes grown by a further `margin` [m] (>= 0) for
  /// refresh() and next_step().
  void full(const Elements& e, Scalar grow, Scalar margin) {
    grow_ = grow;
    margin_ = margin;
    ++full_count_;
    if (e.self && !(self_seen_ && e.layout != 0 && e.layout == layout_seen_)) build_tree(e);
    layout_seen_ = e.layout;
    self_seen_ = e.self;
    if (e.self) {
      tree_full(e, grow);
      return;
    }
    points_.store(e, e.points, 1, grow, margin);
    triangles_.store(e, e.triangles, 3, grow, margin);
    edges_.store(e, e.edges, 2, grow, margin);
    // Cells about the size of a triangle's box (a zero-sized surface: any positive size).
    Scalar extent = 0;
    for (const Box& b : triangles_.stored) extent += (b.hi - b.lo).maxCoeff() - 2 * margin;
    Scalar cell = extent / Scalar(std::max<std::size_t>(1, triangles_.stored.size()));
    if (!(cell > 0)) cell = 1;
    cell_ = cell;
    // The hashes are built when a query first needs them (refresh() too), but for the one below.
    for (Layer* layer : {&points_, &triangles_, &edges_}) layer->cell = cell;
    pairs_.clear();
    obstacle_pairs(e);
    // A moving obstacle's elements leave their boxes in the steps to come, and their queries read
    // the hash of every element: built now, in a step that sizes the work arrays.
    const Eigen::Index extra = e.x0.rows() - e.n;
    const bool obstacles_move = e.x0.bottomRows(extra) != e.x1.bottomRows(extra);
    for (Layer* layer : {&points_, &triangles_, &edges_}) {
      if (obstacles_move) layer->hash_all();
      layer->reserve_escaped();
    }
    reserve_refresh(e);
  }

  /// @brief Brings the list to the next step's motion of the same elements (see the file
  /// comment): full() when e's elements or self-collision switch differ from the last full()'s,
  /// or `grow` or `margin` from its values.
  void next_step(const Elements& e, Scalar grow, Scalar margin) {
    if (full_count_ == 0 || e.self || grow != grow_ || margin != margin_ || e.self != self_seen_ ||
        e.layout == 0 || e.layout != layout_seen_) {
      full(e, grow, margin);
      return;
    }
    all_moved_.assign(std::size_t(e.x1.rows()), 1);
    refresh(e, all_moved_);
  }

  /// @brief Brings the list up to date after the end positions of the points with moved[i] != 0
  /// changed (see the file comment); needs a full() or next_step() on the same elements since
  /// their setup.
  void refresh(const Elements& e, const std::vector<char>& moved) {
    if (self_seen_) {
      tree_refresh(e, moved);
      return;
    }
    if (!points_.update(e, e.points, 1, moved, grow_, margin_) ||
        !triangles_.update(e, e.triangles, 3, moved, grow_, margin_) ||
        !edges_.update(e, e.edges, 2, moved, grow_, margin_)) {
      full(e, grow_, margin_);
      return;
    }
    // Keep the pairs of the elements in place; query the escaped ones again.
    drop_moved_pairs();
    const std::size_t kept = pairs_.size();  // still in order
    for (int v : points_.moved_ids)
      triangles_.query(points_.is_cloth(v), points_.stored[std::size_t(v)],
                       [&](int t) { add_point_triangle(e, v, t); });
    for (int t : triangles_.moved_ids)
      points_.query(triangles_.is_cloth(t), triangles_.stored[std::size_t(t)], [&](int v) {
        if (!points_.moved[std::size_t(v)]) add_point_triangle(e, v, t);
      });
    for (int a : edges_.moved_ids)
      edges_.query(edges_.is_cloth(a), edges_.stored[std::size_t(a)], [&](int b) {
        if (!edges_.moved[std::size_t(b)] || b > a) add_edge_edge(e, a, b);
      });
    merge_new(kept);
  }

  /// @brief How many times full() ran since construction.
  [[nodiscard]] long full_count() const { return full_count_; }

 private:
  using Layer = detail::ElementLayer<Scalar>;
  // Makes room for the refresh() and next_step() that follow full(): the flags of every point,
  // and twice the pairs listed, in the list and in the merge's scratch.
  void reserve_refresh(const Elements& e) {
    all_moved_.reserve(std::size_t(e.x1.rows()));
    const std::size_t pairs = std::max<std::size_t>(64, 2 * pairs_.size());
    pairs_.reserve(pairs);
    merged_.reserve(pairs);
  }

  // Drops the pairs with an element flagged in its layer's `moved` (their pairs are listed
  // again); the others stay in order.
  void drop_moved_pairs() {
    const auto moved = [&](const ElementPair& q) {
      return q.kind == ElementPairKind::PointTriangle
                 ? points_.moved[std::size_t(q.a)] || triangles_.moved[std::size_t(q.b)]
                 : edges_.moved[std::size_t(q.a)] || edges_.moved[std::size_t(q.b)];
    };
    pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(), moved), pairs_.end());
  }
  // Sorts the pairs listed after the first `kept` (in order) and merges the two runs.
  void merge_new(std::size_t kept) {
    massspring::detail::merge_sorted_tail(pairs_, kept, merged_, before);
  }

  // The order of the list: by kind, then first element, then second.
  static bool before(const ElementPair& x, const ElementPair& y) {
    return x.kind != y.kind ? x.kind < y.kind : x.a != y.a ? x.a < y.a : x.b < y.b;
  }

  // full()'s pairs without self-collision, where every pair has an obstacle's element and one of
  // the cloth: each cloth point, triangle and edge queried against the obstacles' elements of the
  // other kind (their hashes hold only the obstacles'); then sorted.
  void obstacle_pairs(const Elements& e) {
    for (std::size_t v = 0; v < points_.cloth; ++v)
      triangles_.query(true, points_.stored[v], [&](int t) { add_point_triangle(e, int(v), t); });
    for (std::size_t t = 0; t < triangles_.cloth; ++t)
      points_.query(true, triangles_.stored[t], [&](int v) { add_point_triangle(e, v, int(t)); });
    for (std::size_t a = 0; a < edges_.cloth; ++a)
      edges_.query(true, edges_.stored[a], [&](int b) { add_edge_edge(e, int(a), b); });
    std::sort(pairs_.begin(), pairs_.end(), before);
  }

  // The tree of the cloth's triangles (the first elements of e.triangles, owner -1) and which
  // triangle lists each cloth point and edge: the first that has it (-1: on no triangle).
  void build_tree(const Elements& e) {
    std::size_t cloth = 0;
    while (cloth < e.triangles.size() && e.triangles[cloth].owner < 0) ++cloth;
    tree_triangles_.resize(cloth);
    for (std::size_t t = 0; t < cloth; ++t) tree_triangles_[t] = e.triangles[t].p;
    point_of_.assign(std::size_t(e.x0.rows()), -1);
    for (std::size_t v = 0; v < e.points.size(); ++v)
      if (e.points[v].owner < 0) point_of_[std::size_t(e.points[v].p[0])] = int(v);
    point_owner_.assign(e.points.size(), -1);
    edge_owner_.assign(e.edges.size(), -1);
    edge_keys_.clear();
    for (std::size_t a = 0; a < e.edges.size(); ++a)
      if (e.edges[a].owner < 0)
        edge_keys_.push_back({std::min(e.edges[a].p[0], e.edges[a].p[1]),
                              std::max(e.edges[a].p[0], e.edges[a].p[1]), int(a)});
    std::sort(edge_keys_.begin(), edge_keys_.end());
    triangle_edges_.resize(cloth);
    for (std::size_t t = 0; t < cloth; ++t)
      for (int k = 0; k < 3; ++k) {
        const int i = tree_triangles_[t][std::size_t(k)];
        const int j = tree_triangles_[t][std::size_t((k + 1) % 3)];
        const int v = point_of_[std::size_t(i)];
        if (v >= 0 && point_owner_[std::size_t(v)] < 0) point_owner_[std::size_t(v)] = int(t);
        const std::array<int, 3> key = {std::min(i, j), std::max(i, j), -1};
        const auto it = std::lower_bound(edge_keys_.begin(), edge_keys_.end(), key);
        const int a =
            it != edge_keys_.end() && (*it)[0] == key[0] && (*it)[1] == key[1] ? (*it)[2] : -1;
        triangle_edges_[t][std::size_t(k)] = a;
        if (a >= 0 && edge_owner_[std::size_t(a)] < 0) edge_owner_[std::size_t(a)] = int(t);
      }
    // The points whose motion tree_refresh() leaves to full(): the obstacles', and the
    // cloth's on a point or edge that no cloth triangle lists.
    loose_.assign(std::size_t(e.x0.rows()), 0);
    for (std::size_t i = 0; i < loose_.size(); ++i) loose_[i] = e.owner[i] >= 0;
    for (std::size_t v = 0; v < e.points.size(); ++v)
      if (point_owner_[v] < 0) loose_[std::size_t(e.points[v].p[0])] = 1;
    for (std::size_t a = 0; a < e.edges.size(); ++a)
      if (edge_owner_[a] < 0)
        for (int k = 0; k < 2; ++k) loose_[std::size_t(e.edges[a].p[std::size_t(k)])] = 1;
    tree_.build(e.x0, tree_triangles_);
  }

  // full() with self-collision through the tree: the boxes of the step's sweeps (no margin),
  // every element changed, and the pairs listed by tree_pairs().
  void tree_full(const Elements& e, Scalar grow) {
    points_.store(e, e.points, 1, grow, 0, true);
    triangles_.store(e, e.triangles, 3, grow, 0, true);
    edges_.store(e, e.edges, 2, grow, 0, true);
    tree_.refit(e.x0, e.x1, grow);
    fitted_ = e.x1;  // same size after the first steps: no allocation
    for (Layer* layer : {&points_, &triangles_, &edges_})
      layer->moved.assign(layer->stored.size(), 1);
    pairs_.clear();
    tree_pairs(e);
    std::sort(pairs_.begin(), pairs_.end(), before);
    reserve_refresh(e);
  }
  // refresh() with self-collision: a cloth point flagged in `moved` whose end position differs
  // from the one its elements were last fitted to has changed, and so has each element with a
  // changed point. Their boxes are taken again, the tree refitted above their triangles, their
  // pairs dropped and listed again by tree_pairs(); the other pairs are kept. A pair of two
  // unchanged elements keeps its elements' motion, so a patch that the tree skipped for that
  // motion still cannot bring them together. An obstacle's point, or a cloth point on an element
  // that no cloth triangle lists, that has changed: full() instead.
  void tree_refresh(const Elements& e, const std::vector<char>& moved) {
    bool any = false;
    changed_.assign(std::size_t(e.x1.rows()), 0);
    for (std::size_t i = 0; i < moved.size(); ++i) {
      if (!moved[i] || fitted_.row(Eigen::Index(i)) == e.x1.row(Eigen::Index(i))) continue;
      if (loose_[i]) {
        full(e, grow_, margin_);
        return;
      }
      fitted_.row(Eigen::Index(i)) = e.x1.row(Eigen::Index(i));
      changed_[i] = 1;
      any = true;
    }
    if (!any) return;
    const auto mark = [&](Layer& layer, const std::vector<Element>& elements, int count) {
      for (std::size_t k = 0; k < elements.size(); ++k) {
        bool hit = false;
        for (int j = 0; j < count; ++j)
          hit = hit || changed_[std::size_t(elements[k].p[std::size_t(j)])];
        layer.moved[k] = hit;
        if (hit) layer.stored[k] = e.swept(elements[k], count, e.grow_of(elements[k], grow_));
      }
    };
    mark(points_, e.points, 1);
    mark(triangles_, e.triangles, 3);
    mark(edges_, e.edges, 2);
    tree_.refit(e.x0, e.x1, grow_, triangles_.moved);
    drop_moved_pairs();
    const std::size_t kept = pairs_.size();  // still in order
    tree_pairs(e);
    merge_new(kept);
  }
  // Appends every candidate with a changed element. The obstacles' elements, and any cloth point
  // or edge on no triangle, against the cloth's triangles and their points and edges through the
  // tree's boxes (the tree visits only its changed triangles); those among themselves one by
  // one. The cloth's pairs from the tree's pairs of triangles: a cloth point is paired from the
  // triangle that lists it, an edge from its triangle likewise, so each pair comes from one pair
  // of triangles, the one holding both elements' boxes (a triangle's box holds its corners' and
  // sides'). A pair the tree skips lies in a patch that cannot touch itself over the step.
  void tree_pairs(const Elements& e) {
    const auto point_triangle = [&](int v, int t) {
      if ((points_.moved[std::size_t(v)] || triangles_.moved[std::size_t(t)]) &&
          points_.stored[std::size_t(v)].overlaps(triangles_.stored[std::size_t(t)]))
        add_point_triangle(e, v, t);
    };
    const auto edge_edge = [&](int a, int b) {
      if ((edges_.moved[std::size_t(a)] || edges_.moved[std::size_t(b)]) &&
          edges_.stored[std::size_t(a)].overlaps(edges_.stored[std::size_t(b)]))
        add_edge_edge(e, a, b);
    };
    for (std::size_t v = 0; v < e.points.size(); ++v)
      if (e.points[v].owner >= 0 || point_owner_[v] < 0) {
        tree_.query(points_.stored[v], [&](int t) { point_triangle(int(v), t); });
        if (e.points[v].owner < 0)
          for (std::size_t s = tree_triangles_.size(); s < e.triangles.size(); ++s)
            point_triangle(int(v), int(s));
      }
    for (std::size_t s = 0; s < e.triangles.size(); ++s)
      if (e.triangles[s].owner >= 0)
        tree_.query(triangles_.stored[s], [&](int t) {
          for (int i : tree_triangles_[std::size_t(t)]) {
            const int v = point_of_[std::size_t(i)];
            if (v >= 0 && point_owner_[std::size_t(v)] == t) point_triangle(v, int(s));
          }
        });
    loose_edges_.clear();
    for (std::size_t a = 0; a < e.edges.size(); ++a)
      if (e.edges[a].owner >= 0 || edge_owner_[a] < 0) {
        for (int b : loose_edges_) edge_edge(int(a), b);
        loose_edges_.push_back(int(a));
        tree_.query(edges_.stored[a], [&](int t) {
          for (int b : triangle_edges_[std::size_t(t)])
            if (b >= 0 && edge_owner_[std::size_t(b)] == t) edge_edge(int(a), b);
        });
      }
    tree_.self_pairs(e.x0, e.x1, [&](int s, int t) {
      corners_against(s, t, point_triangle);
      corners_against(t, s, point_triangle);
      for (int a : triangle_edges_[std::size_t(s)]) {
        if (a < 0 || edge_owner_[std::size_t(a)] != s) continue;
        for (int b : triangle_edges_[std::size_t(t)])
          if (b >= 0 && edge_owner_[std::size_t(b)] == t) edge_edge(a, b);
      }
    });
  }
  // The corners triangle s lists, against triangle t.
  template <class PointTriangle>
  void corners_against(int s, int t, const PointTriangle& point_triangle) const {
    for (int i : tree_triangles_[std::size_t(s)]) {
      const int v = point_of_[std::size_t(i)];
      if (v >= 0 && point_owner_[std::size_t(v)] == s) point_triangle(v, t);
    }
  }

  void add_point_triangle(const Elements& e, int v, int t) {
    const Element& pe = e.points[std::size_t(v)];
    const Element& te = e.triangles[std::size_t(t)];
    if (e.pair_gap(pe.owner, te.owner) < 0) return;
    const int i = pe.p[0];
    if (i == te.p[0] || i == te.p[1] || i == te.p[2]) return;
    pairs_.push_back({ElementPairKind::PointTriangle, v, t});
  }
  void add_edge_edge(const Elements& e, int a, int b) {
    if (a == b) return;
    const Element& ea = e.edges[std::size_t(a)];
    const Element& eb = e.edges[std::size_t(b)];
    if (e.pair_gap(ea.owner, eb.owner) < 0) return;
    for (int i : {ea.p[0], ea.p[1]})
      if (i == eb.p[0] || i == eb.p[1]) return;
    pairs_.push_back({ElementPairKind::EdgeEdge, std::min(a, b), std::max(a, b)});
  }

  Scalar grow_ = 0, margin_ = 0, cell_ = 1;
  long full_count_ = 0;
  Layer points_, triangles_, edges_;
  std::vector<ElementPair> pairs_, merged_;
  std::uint64_t layout_seen_ = 0;  // the last full()'s SurfaceElements::layout
  bool self_seen_ = false;
  std::vector<char> all_moved_;
  // Self-collision through the tree (build_tree()).
  NormalConeTree<Scalar> tree_;
  std::vector<std::array<int, 3>> tree_triangles_, triangle_edges_, edge_keys_;
  std::vector<int> point_of_, point_owner_, edge_owner_, loose_edges_;
  Points<Scalar> fitted_;  // the end positions the tree and the stored boxes were fitted to
  std::vector<char> loose_, changed_;  // per point: see tree_refresh()
};

}  // namespace massspring::contact
