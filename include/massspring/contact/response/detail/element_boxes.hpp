#pragma once
/// @file
/// @brief ElementLayer: the stored boxes of one kind of surface element (points, edges or
/// triangles) and the spatial hashes SurfaceCandidates (contact/response/surface_candidates.hpp)
/// queries them through; ElementSubset, some of those elements and a hash of their boxes. What a
/// stored box holds and when it is stored again is surface_candidates.hpp's file comment.

#include <algorithm>
#include <cstddef>
#include <vector>

#include "massspring/contact/broad_phase/box_hash.hpp"
#include "massspring/contact/response/surface_elements.hpp"
#include "massspring/types.hpp"

namespace massspring::contact::detail {

/// @brief Whether box b lies inside box outer (faces may touch).
template <class Scalar>
bool box_inside(const AlignedBox3<Scalar>& b, const AlignedBox3<Scalar>& outer) {
  return (outer.lo.array() <= b.lo.array()).all() && (b.hi.array() <= outer.hi.array()).all();
}

// Some elements of a layer and a hash of their stored boxes, built when first queried.
template <class Scalar>
struct ElementSubset {
  using Box = AlignedBox3<Scalar>;

  std::vector<int> ids;
  std::vector<Box> boxes;  // stored[ids[j]] as they were when hashed
  BoxHash<Scalar> hash;
  bool hashed = false;

  void clear() {
    ids.clear();
    hashed = false;
  }
  // Calls visit(i) for each element i of the subset whose box, as hashed, overlaps q.
  template <class Visit>
  void query(const std::vector<Box>& stored, Scalar cell, const Box& q, Visit&& visit) {
    if (ids.empty()) return;
    if (!hashed) {
      boxes.resize(ids.size());
      for (std::size_t j = 0; j < ids.size(); ++j) boxes[j] = stored[std::size_t(ids[j])];
      hash.build(boxes, cell);
      hashed = true;
    }
    hash.query(q, [&](int j) { visit(ids[std::size_t(j)]); });
  }
};

// The boxes and hashes of one kind of element (points, edges or triangles): the cloth's
// elements [0, cloth), then the obstacles'. Without self-collision a cloth element pairs only
// with an obstacle's, so its queries read the obstacles' hashes alone; an obstacle's read the
// hash of every element.
template <class Scalar>
struct ElementLayer {
  using Box = AlignedBox3<Scalar>;
  using Elements = SurfaceElements<Scalar>;
  using Element = typename Elements::Element;

  std::vector<Box> stored;  // ahead(), grown by grow_of() + margin; hashed unless escaped
  // moved: the elements whose pairs are listed again (escaped in the last update(), or, with
  // self-collision, on a point whose end position changed); escaped: since the last store().
  std::vector<char> moved, escaped;
  std::vector<int> moved_ids;
  std::size_t cloth = 0;
  BoxHash<Scalar> hash;  // every element's stored box as full() left it
  bool hashed = false;
  ElementSubset<Scalar> obstacles;          // the obstacles' elements, boxes as full() left them
  ElementSubset<Scalar> escaped_all;        // the escaped elements
  ElementSubset<Scalar> escaped_obstacles;  // the escaped obstacles' elements
  Scalar cell = 1;

  [[nodiscard]] bool is_cloth(int i) const { return std::size_t(i) < cloth; }

  // Hashes every element's stored box, unless done since the last full().
  void hash_all() {
    if (hashed) return;
    hash.build(stored, cell);
    hashed = true;
    // The escaped ones, a part of these, fit in as much room.
    escaped_all.hash.reserve(stored.size(), hash.entries());
  }
  // Makes room for the hash of the escaped obstacles' elements, a part of the obstacles'.
  void reserve_escaped() {
    if (obstacles.hashed)
      escaped_obstacles.hash.reserve(obstacles.ids.size(), obstacles.hash.entries());
  }

  // The box of the element's points at x0, x1 and x1 + (x1 - x0), grown by g.
  static Box ahead(const Elements& e, const Element& element, int count, Scalar g) {
    Box b = e.swept(element, count, g);
    for (int k = 0; k < count; ++k) {
      const int i = element.p[std::size_t(k)];
      const Vector3<Scalar> next = 2 * e.p1(i) - e.p0(i);
      b.lo = b.lo.cwiseMin(next - Vector3<Scalar>::Constant(g));
      b.hi = b.hi.cwiseMax(next + Vector3<Scalar>::Constant(g));
    }
    return b;
  }

  // Stores each element's box: ahead() grown by grow_of() and the margin, or (`swept_only`)
  // the box of the step's sweep grown by grow_of().
  void store(const Elements& e, const std::vector<Element>& elements, int count, Scalar grow,
             Scalar margin, bool swept_only = false) {
    stored.resize(elements.size());
    for (std::size_t i = 0; i < elements.size(); ++i)
      stored[i] = swept_only ? e.swept(elements[i], count, e.grow_of(elements[i], grow))
                             : ahead(e, elements[i], count, e.grow_of(elements[i], grow) + margin);
    escaped.assign(elements.size(), 0);
    cloth = 0;
    while (cloth < elements.size() && elements[cloth].owner < 0) ++cloth;
    hashed = false;
    obstacles.clear();
    for (std::size_t i = cloth; i < elements.size(); ++i) obstacles.ids.push_back(int(i));
    escaped_all.clear();
    escaped_obstacles.clear();
    // refresh()'s arrays, so that the steps after the first allocate nothing.
    moved.reserve(elements.size());
    moved_ids.reserve(elements.size());
    for (ElementSubset<Scalar>* subset : {&escaped_all, &escaped_obstacles}) {
      subset->ids.reserve(elements.size());
      subset->boxes.reserve(elements.size());
    }
  }
  // Flags the elements with a moved point whose current box left the stored one, and stores
  // their box again (ahead()); false when too many have escaped their stored boxes.
  bool update(const Elements& e, const std::vector<Element>& elements, int count,
              const std::vector<char>& moved_points, Scalar grow, Scalar margin) {
    moved.assign(elements.size(), 0);
    moved_ids.clear();
    for (std::size_t i = 0; i < elements.size(); ++i) {
      bool any = false;
      for (int k = 0; k < count; ++k)
        any = any || moved_points[std::size_t(elements[i].p[std::size_t(k)])];
      if (!any) continue;
      const Box now = e.swept(elements[i], count, e.grow_of(elements[i], grow));
      if (box_inside(now, stored[i])) continue;
      moved[i] = 1;
      moved_ids.push_back(int(i));
      // A box stored again, or a new escaped element: the hashes that hold it are stale.
      const bool obstacle = !is_cloth(int(i));
      if (!escaped[i]) {
        escaped_all.ids.push_back(int(i));
        if (obstacle) escaped_obstacles.ids.push_back(int(i));
      }
      escaped[i] = 1;
      escaped_all.hashed = false;
      if (obstacle) escaped_obstacles.hashed = false;
      stored[i] = ahead(e, elements[i], count, e.grow_of(elements[i], grow) + margin);
    }
    return escaped_all.ids.size() <= std::max<std::size_t>(64, elements.size() / 4);
  }
  // Calls visit(i) for each element i whose stored box overlaps q and that can pair with an
  // element of the cloth (`from_cloth`: the obstacles' elements) or of an obstacle (every
  // element): the ones in place through a hash of full()'s boxes, the escaped ones through a
  // second hash.
  template <class Visit>
  void query(bool from_cloth, const Box& q, Visit&& visit) {
    const auto in_place = [&](int i) {
      if (!escaped[std::size_t(i)]) visit(i);
    };
    if (from_cloth) {
      obstacles.query(stored, cell, q, in_place);
      escaped_obstacles.query(stored, cell, q, visit);
      return;
    }
    hash_all();
    hash.query(q, in_place);
    escaped_all.query(stored, cell, q, visit);
  }
};

}  // namespace massspring::contact::detail
