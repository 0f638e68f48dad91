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
/// full() hashes every element (contact/broad_phase/box_hash.hpp) with its box grown by a further
/// margin m, and lists the pairs of the true boxes; without self-collision only the obstacles'
/// elements are queried, as every pair then has one. refresh() then updates the list after a round
/// moved the points flagged in `moved`: the pairs that have no moved point keep their boxes and
/// stay; the elements that have a moved point are queried again with their new boxes against the
/// stored ones. While a moved element's box stays inside its stored box (grown by m), the stored
/// box covers the current one and the hash finds its overlaps. An element whose box leaves its
/// stored one has escaped: from then on its stored box is its current box grown by m, and it is
/// compared with every query box directly rather than through the hash (the hash still has it in
/// the cells of its old box). More than max(64, 1/16 of the elements of its kind) escaped:
/// refresh() calls full() instead. Either way the list afterwards holds every candidate of the
/// current motion (and, from refresh(), some pairs whose boxes overlap only through the slack of
/// the stored ones).
/// Cost: full() O(elements x cells per box); refresh() O(pairs) to filter, plus the queries of
/// the moved elements, each O(cells per box + escaped elements).
///
/// Work arrays keep their capacity: after the first steps nothing allocates.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "massspring/contact/broad_phase/box_hash.hpp"
#include "massspring/contact/response/surface_elements.hpp"

namespace massspring::contact {

/// @brief Candidate pairs of a SurfaceElements motion (see the file comment).
template <class Scalar>
class SurfaceCandidates {
 public:
  using Box = AlignedBox3<Scalar>;
  using Elements = SurfaceElements<Scalar>;
  using Element = typename Elements::Element;

  /// @brief The candidates, point-triangle and edge-edge, each once.
  [[nodiscard]] const std::vector<ElementPair>& pairs() const { return pairs_; }

  /// @brief Lists every candidate of e's motion with the cloth's boxes grown by `grow` [m]
  /// (>= 0), storing boxes grown by a further `margin` [m] (>= 0) for refresh().
  void full(const Elements& e, Scalar grow, Scalar margin) {
    grow_ = grow;
    margin_ = margin;
    ++full_count_;
    points_.store(e, e.points, 1, grow, margin);
    triangles_.store(e, e.triangles, 3, grow, margin);
    edges_.store(e, e.edges, 2, grow, margin);
    // Cells about the size of a triangle's box (a zero-sized surface: any positive size).
    Scalar extent = 0;
    for (const Box& b : triangles_.stored) extent += (b.hi - b.lo).maxCoeff() - 2 * margin;
    Scalar cell = extent / Scalar(std::max<std::size_t>(1, triangles_.stored.size()));
    if (!(cell > 0)) cell = 1;
    cell_ = cell;
    // Each hash is built when a query first needs it (refresh() too).
    points_.hashed = triangles_.hashed = edges_.hashed = false;
    pairs_.clear();
    if (!e.self) {
      obstacle_pairs(e);
      return;
    }
    triangles_.hash_boxes(cell_);
    edges_.hash_boxes(cell_);
    // The true boxes are the stored ones shrunk by the margin.
    for (std::size_t v = 0; v < e.points.size(); ++v) {
      const Box& box = points_.stored[v];
      triangles_.hash.query(box, [&](int t) {
        if (overlap_shrunk(box, triangles_.stored[std::size_t(t)]))
          add_point_triangle(e, int(v), t);
      });
    }
    for (std::size_t a = 0; a < e.edges.size(); ++a) {
      const Box& box = edges_.stored[a];
      edges_.hash.query(
          box,
          [&](int b) {
            if (overlap_shrunk(box, edges_.stored[std::size_t(b)])) add_edge_edge(e, int(a), b);
          },
          int(a));
    }
  }

  /// @brief Brings the list up to date after the end positions of the points with moved[i] != 0
  /// changed (see the file comment); needs a full() on the same elements since their setup.
  void refresh(const Elements& e, const std::vector<char>& moved) {
    if (!points_.update(e, e.points, 1, moved, grow_, margin_) ||
        !triangles_.update(e, e.triangles, 3, moved, grow_, margin_) ||
        !edges_.update(e, e.edges, 2, moved, grow_, margin_)) {
      full(e, grow_, margin_);
      return;
    }
    // Keep the pairs of unmoved elements; query the moved ones again.
    const auto stale = [&](const ElementPair& q) {
      return q.kind == 0 ? points_.moved[std::size_t(q.a)] || triangles_.moved[std::size_t(q.b)]
                         : edges_.moved[std::size_t(q.a)] || edges_.moved[std::size_t(q.b)];
    };
    pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(), stale), pairs_.end());
    if (!points_.moved_ids.empty()) triangles_.hash_boxes(cell_);
    for (int v : points_.moved_ids)
      triangles_.query(points_.now[std::size_t(v)], [&](int t) { add_point_triangle(e, v, t); });
    if (!triangles_.moved_ids.empty()) points_.hash_boxes(cell_);
    for (int t : triangles_.moved_ids)
      points_.query(triangles_.now[std::size_t(t)], [&](int v) {
        if (!points_.moved[std::size_t(v)]) add_point_triangle(e, v, t);
      });
    if (!edges_.moved_ids.empty()) edges_.hash_boxes(cell_);
    for (int a : edges_.moved_ids)
      edges_.query(edges_.now[std::size_t(a)], [&](int b) {
        if (!edges_.moved[std::size_t(b)] || b > a) add_edge_edge(e, a, b);
      });
  }

  /// @brief How many times full() ran since construction.
  [[nodiscard]] long full_count() const { return full_count_; }

 private:
  // The boxes and hash of one kind of element (points, edges or triangles).
  struct Layer {
    std::vector<Box> stored;  // grown by grow_of() + margin; hashed unless escaped
    std::vector<Box> now;     // the moved elements' current boxes, grown by grow_of()
    std::vector<char> moved, escaped;
    std::vector<int> moved_ids, escaped_ids;
    BoxHash<Scalar> hash;
    bool hashed = false;  // hash holds `stored` as full() left it

    // Hashes the stored boxes, unless done since the last full().
    void hash_boxes(Scalar cell) {
      if (hashed) return;
      hash.build(stored, cell);
      hashed = true;
    }

    void store(const Elements& e, const std::vector<Element>& elements, int count, Scalar grow,
               Scalar margin) {
      stored.resize(elements.size());
      for (std::size_t i = 0; i < elements.size(); ++i)
        stored[i] = e.swept(elements[i], count, e.grow_of(elements[i], grow) + margin);
      now.resize(elements.size());
      escaped.assign(elements.size(), 0);
      escaped_ids.clear();
    }
    // Flags the elements with a moved point and takes their current boxes; false when too many
    // have escaped their stored boxes.
    bool update(const Elements& e, const std::vector<Element>& elements, int count,
                const std::vector<char>& moved_points, Scalar grow, Scalar margin) {
      moved.assign(elements.size(), 0);
      moved_ids.clear();
      for (std::size_t i = 0; i < elements.size(); ++i) {
        bool any = false;
        for (int k = 0; k < count; ++k)
          any = any || moved_points[std::size_t(elements[i].p[std::size_t(k)])];
        if (!any) continue;
        moved[i] = 1;
        moved_ids.push_back(int(i));
        now[i] = e.swept(elements[i], count, e.grow_of(elements[i], grow));
        if (escaped[i] || !inside(now[i], stored[i])) {
          if (!escaped[i]) escaped_ids.push_back(int(i));
          escaped[i] = 1;
          stored[i] = {now[i].lo.array() - margin, now[i].hi.array() + margin};
        }
      }
      return escaped_ids.size() <= std::max<std::size_t>(64, elements.size() / 16);
    }
    // Calls visit(i) for each element i whose stored box overlaps q: through the hash for the
    // elements in place, directly for the escaped ones.
    template <class Visit>
    void query(const Box& q, Visit&& visit) {
      hash.query(q, [&](int i) {
        if (!escaped[std::size_t(i)]) visit(i);
      });
      for (int i : escaped_ids)
        if (stored[std::size_t(i)].overlaps(q)) visit(i);
    }
  };

  // full()'s pairs without self-collision, where every pair has an obstacle's element: only the
  // obstacles' points, triangles and edges are queried (the cloth's with one another would all be
  // rejected by pair_gap()), the cloth's points through their own hash.
  void obstacle_pairs(const Elements& e) {
    for (std::size_t v = 0; v < e.points.size(); ++v) {
      if (e.points[v].owner < 0) continue;
      triangles_.hash_boxes(cell_);
      const Box& box = points_.stored[v];
      triangles_.hash.query(box, [&](int t) {
        if (overlap_shrunk(box, triangles_.stored[std::size_t(t)]))
          add_point_triangle(e, int(v), t);
      });
    }
    bool obstacle_triangles = false;
    for (const Element& t : e.triangles) obstacle_triangles = obstacle_triangles || t.owner >= 0;
    if (obstacle_triangles) {
      points_.hash_boxes(cell_);
      for (std::size_t t = 0; t < e.triangles.size(); ++t) {
        if (e.triangles[t].owner < 0) continue;
        const Box& box = triangles_.stored[t];
        points_.hash.query(box, [&](int v) {
          if (e.points[std::size_t(v)].owner < 0 &&
              overlap_shrunk(points_.stored[std::size_t(v)], box))
            add_point_triangle(e, v, int(t));
        });
      }
    }
    for (std::size_t a = 0; a < e.edges.size(); ++a) {
      if (e.edges[a].owner < 0) continue;
      edges_.hash_boxes(cell_);
      const Box& box = edges_.stored[a];
      edges_.hash.query(box, [&](int b) {
        if (e.edges[std::size_t(b)].owner < 0 && overlap_shrunk(box, edges_.stored[std::size_t(b)]))
          add_edge_edge(e, int(a), b);
      });
    }
  }

  static bool inside(const Box& b, const Box& outer) {
    return (outer.lo.array() <= b.lo.array()).all() && (b.hi.array() <= outer.hi.array()).all();
  }
  // Whether a and b, both grown by the margin, overlap once shrunk by it.
  bool overlap_shrunk(const Box& a, const Box& b) const {
    const Scalar m2 = 2 * margin_;
    return (a.lo.array() + m2 <= b.hi.array()).all() && (b.lo.array() + m2 <= a.hi.array()).all();
  }
  void add_point_triangle(const Elements& e, int v, int t) {
    const Element& pe = e.points[std::size_t(v)];
    const Element& te = e.triangles[std::size_t(t)];
    if (e.pair_gap(pe.owner, te.owner) < 0) return;
    const int i = pe.p[0];
    if (i == te.p[0] || i == te.p[1] || i == te.p[2]) return;
    pairs_.push_back({0, v, t});
  }
  void add_edge_edge(const Elements& e, int a, int b) {
    if (a == b) return;
    const Element& ea = e.edges[std::size_t(a)];
    const Element& eb = e.edges[std::size_t(b)];
    if (e.pair_gap(ea.owner, eb.owner) < 0) return;
    for (int i : {ea.p[0], ea.p[1]})
      if (i == eb.p[0] || i == eb.p[1]) return;
    pairs_.push_back({1, std::min(a, b), std::max(a, b)});
  }

  Scalar grow_ = 0, margin_ = 0, cell_ = 1;
  long full_count_ = 0;
  Layer points_, triangles_, edges_;
  std::vector<ElementPair> pairs_;
};

}  // namespace massspring::contact
