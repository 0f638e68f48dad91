#pragma once
/// @file
/// @brief SurfaceElements: the work state of surface contact (contact/response/
/// surface_contact.hpp) over one step: the cloth's points, then the obstacles' (sphere centre,
/// capsule axis ends, box corners, mesh vertices) at the start and end of the step, their inverse
/// masses, and the elements that collide: points, edges and triangles. Also the closest-point
/// geometry of a point-triangle or edge-edge pair (PairStencil).
///
/// An obstacle's points have infinite mass (w = 0) and move with their collider from its pose
/// at the start of the step to the one at its end. A cloth point the colliders' point response
/// left touching a solid (plane, sphere, capsule, box) is held too (w = 0), so that no impulse
/// pushes it back inside; the solid already gave it its contact and friction.
///
/// The element lists are rebuilt only when what they are made of changes (the number of points,
/// the surface's triangles and edges, the obstacles' elements); `layout` then takes a value no
/// SurfaceElements had before, so that equal values mean equal lists.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "massspring/contact/aligned_box.hpp"
#include "massspring/contact/colliders/colliders.hpp"
#include "massspring/contact/distance/barycentric.hpp"
#include "massspring/contact/distance/edge_edge.hpp"
#include "massspring/contact/distance/point_triangle.hpp"
#include "massspring/contact/response/surface_contact_slot.hpp"
#include "massspring/contact/self_collision.hpp"
#include "massspring/detail/triangle_edges.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The pair's points p and barycentric weights a (+ on the first element, - on the
/// second), its closest distance [m] and unit normal n (from
/// the second element to the first).
template <class Scalar>
struct PairStencil {
  std::array<int, 4> p;
  std::array<Scalar, 4> a;
  Vector3<Scalar> n;
  Scalar distance;
};

/// @brief What a candidate pair's two elements are.
enum class ElementPairKind : int {
  PointTriangle = 0,  ///< a: a point element, b: a triangle element
  EdgeEdge = 1        ///< a < b: two edge elements
};

/// @brief A candidate pair of elements (indices into SurfaceElements' lists).
struct ElementPair {
  ElementPairKind kind;
  int a, b;
  /// @brief How many of the pair's four points (SurfaceElements::points_of()) belong to its
  /// first element: 1 (a point) or 2 (an edge).
  [[nodiscard]] int split() const { return kind == ElementPairKind::PointTriangle ? 1 : 2; }
};

/// @brief The work state (see the file comment); its arrays keep their capacity.
template <class Scalar>
struct SurfaceElements {
  using V3 = Vector3<Scalar>;
  using Stencil = PairStencil<Scalar>;
  using Pair = ElementPair;

  /// An element: up to three point indices into the augmented arrays; owner -1 for the cloth, or
  /// the collider's index.
  struct Element {
    std::array<int, 3> p;
    int owner;
  };

  // Augmented arrays: the cloth's points, then the obstacles' (infinite mass); elements.
  void setup(const SurfaceContactInput<Scalar>& in) {
    n = int(in.step.x_start.rows());
    int extra = 0;
    for (const auto& c : in.colliders) extra += obstacle_points(c);
    const int total = n + extra;
    x0.resize(total, 3);
    x1.resize(total, 3);
    x0.topRows(n) = in.step.x_start;
    x1.topRows(n) = in.step.x_end;
    w.resize(total);
    w.head(n) = in.step.inverse_masses;
    pinned.assign(std::size_t(total), 0);
    for (int i : in.step.pinned) pinned[std::size_t(i)] = 1;
    w.tail(extra).setZero();
    hold_solid_contacts(in);
    owner.assign(std::size_t(total), -1);
    // Cloth: the corners of the triangles (each once), the edges, the triangles; kept from the
    // last call when n, the triangles and the edges are the same.
    const bool same_cloth = n == cloth_n && in.triangles.rows() == cloth_triangles.rows() &&
                            in.edges.rows() == cloth_edges.rows() &&
                            in.triangles == cloth_triangles && in.edges == cloth_edges;
    bool changed = !same_cloth;
    if (same_cloth) {
      points.resize(cloth_sizes[0]);  // the obstacles' elements follow: added again below
      edges.resize(cloth_sizes[1]);
      triangles.resize(cloth_sizes[2]);
    } else {
      points.clear();
      edges.clear();
      triangles.clear();
      mark.assign(std::size_t(n), 0);
      for (Eigen::Index t = 0; t < in.triangles.rows(); ++t) {
        triangles.push_back({{in.triangles(t, 0), in.triangles(t, 1), in.triangles(t, 2)}, -1});
        for (int k = 0; k < 3; ++k) mark[std::size_t(in.triangles(t, k))] = 1;
      }
      for (int i = 0; i < n; ++i)
        if (mark[std::size_t(i)]) points.push_back({{i, -1, -1}, -1});
      for (Eigen::Index e = 0; e < in.edges.rows(); ++e)
        edges.push_back({{in.edges(e, 0), in.edges(e, 1), -1}, -1});
      cloth_n = n;
      cloth_triangles = in.triangles;
      cloth_edges = in.edges;
      cloth_sizes = {points.size(), edges.size(), triangles.size()};
    }
    const std::size_t cloth_elements = points.size() + edges.size() + triangles.size();
    // Obstacles.
    int next = n;
    gap.assign(std::size_t(in.colliders.size()), 0);
    for (int ci = 0; ci < in.colliders.size(); ++ci)
      next = add_obstacle(in.colliders[ci], ci, next, in.self_collision);
    changed = !same_tail(points, cloth_sizes[0], kept_points) || changed;
    changed = !same_tail(edges, cloth_sizes[1], kept_edges) || changed;
    changed = !same_tail(triangles, cloth_sizes[2], kept_triangles) || changed;
    if (changed) layout = next_layout();
    any_pairs = in.self_collision.has_value() ||
                points.size() + edges.size() + triangles.size() > cloth_elements;
    self = in.self_collision.has_value();
    self_gap = in.self_collision ? in.self_collision->thickness / 10 : Scalar(0);
  }

  // Whether list[from..] equals kept; if not, kept takes it.
  static bool same_tail(const std::vector<Element>& list, std::size_t from,
                        std::vector<Element>& kept) {
    const auto begin = list.begin() + std::ptrdiff_t(from);
    const bool same = std::equal(
        begin, list.end(), kept.begin(), kept.end(),
        [](const Element& a, const Element& b) { return a.p == b.p && a.owner == b.owner; });
    if (!same) kept.assign(begin, list.end());
    return same;
  }
  // A value of `layout` no SurfaceElements had before.
  static std::uint64_t next_layout() {
    static std::atomic<std::uint64_t> last{0};
    return ++last;
  }

  // A point the colliders' point response left touching a solid (a plane, sphere, capsule or
  // box) is held by it in this pass: infinite mass, so that no impulse pushes it back inside;
  // the solid already gave it its contact and friction.
  void hold_solid_contacts(const SurfaceContactInput<Scalar>& in) {
    if (in.colliders.empty()) return;
    ColliderContact<Scalar> k;
    for (int i = 0; i < n; ++i) {
      if (w(i) == 0) continue;
      const V3 xs = p0(i), xe = p1(i);
      if (!in.colliders.near(xs, xe)) continue;
      const Scalar slop = ColliderSet<Scalar>::point_slop(xe);
      for (const auto& c : in.colliders)
        if (c.shape() != ColliderShape::Mesh && c.contact(xs, xe, slop + c.slop(), k)) {
          w(i) = 0;
          break;
        }
    }
  }

  // True when point i's end position is inside a solid collider (a plane, sphere, capsule or
  // box) by more than rounding.
  bool inside_solid(const ColliderSet<Scalar>& colliders, int i) const {
    const V3 xs = p0(i), xe = p1(i);
    if (!colliders.near(xs, xe)) return false;
    ColliderContact<Scalar> k;
    for (const auto& c : colliders)
      if (c.shape() != ColliderShape::Mesh && c.contact(xs, xe, Scalar(0), k) && k.depth > 0)
        return true;
    return false;
  }
  // A point an impulse pushed into a solid gets the colliders' position response (with their
  // friction) and is held from then on, like the points the response left touching; moved[i]
  // is set for each.
  void hold_pushed_into_solids(const SurfaceContactInput<Scalar>& in, std::vector<char>& moved) {
    if (in.colliders.empty()) return;
    for (int i = 0; i < n; ++i) {
      if (w(i) == 0 || !inside_solid(in.colliders, i)) continue;
      in.colliders.project(x0.row(i).data(), x1.row(i).data(), in.step.dt);
      w(i) = 0;
      moved[std::size_t(i)] = 1;
    }
  }

  static int obstacle_points(const Collider<Scalar>& c) {
    switch (c.shape()) {
      case ColliderShape::Sphere:
        return 1;
      case ColliderShape::Capsule:
        return 2;
      case ColliderShape::Box:
        return 8;
      case ColliderShape::Mesh:
        return int(c.triangle_mesh()->vertices().rows());
      default:
        return 0;
    }
  }

  // Appends collider ci's points (start and end of the step) and elements; returns the next
  // free point index.
  int add_obstacle(const Collider<Scalar>& c, int ci, int next,
                   const std::optional<SelfCollision<Scalar>>& self_collision) {
    const auto place = [&](int i, const V3& local) {
      x0.row(i) = (c.rotation() * local + c.translation()).transpose();
      x1.row(i) = (c.end_rotation() * local + c.end_translation()).transpose();
      owner[std::size_t(i)] = ci;
    };
    // The gap kept from an obstacle's centre, axis, edges and faces [m]: half the sum of a
    // sphere's or capsule's radius and the thickness (half the distance at which the point
    // response keeps the points), or, for a box or mesh of no thickness, a quarter of the
    // self-collision thickness (0.25 mm without it).
    const bool round = c.shape() == ColliderShape::Sphere || c.shape() == ColliderShape::Capsule;
    Scalar keep = (c.radius() * Scalar(round) + c.thickness()) / 2;
    if (!(keep > 0)) keep = self_collision ? self_collision->thickness / 4 : Scalar(2.5e-4);
    gap[std::size_t(ci)] = keep;
    // Every obstacle point also meets the cloth's triangles: a sphere's centre (no cloth
    // triangle comes nearer than the gap, so no edge cuts through the ball's core), a capsule's
    // axis ends, a box's corners.
    const auto point = [&](int i, const V3& local) {
      place(i, local);
      points.push_back({{i, -1, -1}, ci});
    };
    switch (c.shape()) {
      case ColliderShape::Sphere:
        point(next, V3::Zero());
        return next + 1;
      case ColliderShape::Capsule:
        point(next, -c.axis());
        point(next + 1, c.axis());
        edges.push_back({{next, next + 1, -1}, ci});
        return next + 2;
      case ColliderShape::Box: {
        for (int k = 0; k < 8; ++k)
          point(next + k,
                V3((k & 1) ? c.axis()(0) : -c.axis()(0), (k & 2) ? c.axis()(1) : -c.axis()(1),
                   (k & 4) ? c.axis()(2) : -c.axis()(2)));
        for (int k = 0; k < 8; ++k)
          for (int bit : {1, 2, 4})
            if (!(k & bit)) edges.push_back({{next + k, next + (k | bit), -1}, ci});
        return next + 8;
      }
      case ColliderShape::Mesh: {
        const auto& mesh = *c.triangle_mesh();
        const int m = int(mesh.vertices().rows());
        const Triangles& f = mesh.triangles();
        // Every vertex is placed (the indices stay the mesh's); only those of a triangle are
        // points of the surface (a state scene's mesh carries two unused corners that keep its
        // frame).
        used_vertex.assign(std::size_t(m), 0);
        for (Eigen::Index t = 0; t < f.rows(); ++t)
          for (int k = 0; k < 3; ++k) used_vertex[std::size_t(f(t, k))] = 1;
        for (int k = 0; k < m; ++k) {
          if (used_vertex[std::size_t(k)])
            point(next + k, mesh.vertices().row(k).transpose());
          else
            place(next + k, mesh.vertices().row(k).transpose());
        }
        for (Eigen::Index t = 0; t < f.rows(); ++t)
          triangles.push_back({{next + f(t, 0), next + f(t, 1), next + f(t, 2)}, ci});
        massspring::detail::triangle_edges(f, mesh_edges);
        for (const auto& [a, b] : mesh_edges) edges.push_back({{next + a, next + b, -1}, ci});
        return next + m;
      }
      default:
        return next;
    }
  }

  // The gap a pair keeps [m] (by the owners of its two elements) and whether it is tested.
  [[nodiscard]] Scalar pair_gap(int owner_a, int owner_b) const {
    if (owner_a >= 0 && owner_b >= 0) return -1;  // obstacle-obstacle: never
    if (owner_a < 0 && owner_b < 0) return self ? self_gap : Scalar(-1);
    return gap[std::size_t(std::max(owner_a, owner_b))];
  }

  // How far an element's box is grown [m]: an obstacle's by its whole gap, the cloth's by
  // `cloth` (then two boxes overlap whenever the elements are nearer than their pair's gap, as
  // long as cloth >= half the cloth's own gap).
  [[nodiscard]] Scalar grow_of(const Element& e, Scalar cloth) const {
    return e.owner < 0 ? cloth : gap[std::size_t(e.owner)];
  }

  V3 p0(int i) const { return x0.row(i).transpose(); }
  V3 p1(int i) const { return x1.row(i).transpose(); }
  V3 d(int i) const { return (x1.row(i) - x0.row(i)).transpose(); }

  AlignedBox3<Scalar> swept(const Element& e, int count, Scalar grow) const {
    AlignedBox3<Scalar> b{p0(e.p[0]), p0(e.p[0])};
    for (int k = 0; k < count; ++k) {
      b.lo = b.lo.cwiseMin(p0(e.p[std::size_t(k)])).cwiseMin(p1(e.p[std::size_t(k)]));
      b.hi = b.hi.cwiseMax(p0(e.p[std::size_t(k)])).cwiseMax(p1(e.p[std::size_t(k)]));
    }
    b.lo.array() -= grow;
    b.hi.array() += grow;
    return b;
  }

  // The owners of the pair's two elements (-1: the cloth; else the obstacle's collider).
  [[nodiscard]] std::array<int, 2> owners_of(const Pair& q) const {
    if (q.kind == ElementPairKind::PointTriangle)
      return {points[std::size_t(q.a)].owner, triangles[std::size_t(q.b)].owner};
    return {edges[std::size_t(q.a)].owner, edges[std::size_t(q.b)].owner};
  }

  // The pair's four points: the point and the triangle's corners, or both edges' ends.
  [[nodiscard]] std::array<int, 4> points_of(const Pair& q) const {
    if (q.kind == ElementPairKind::PointTriangle) {
      const Element& pe = points[std::size_t(q.a)];
      const Element& te = triangles[std::size_t(q.b)];
      return {pe.p[0], te.p[0], te.p[1], te.p[2]};
    }
    const Element& ea = edges[std::size_t(q.a)];
    const Element& eb = edges[std::size_t(q.b)];
    return {ea.p[0], ea.p[1], eb.p[0], eb.p[1]};
  }

  template <class Pos>
  Stencil stencil(const Pair& q, Pos&& x) const {
    Stencil s;
    if (q.kind == ElementPairKind::PointTriangle) {
      const Element& pe = points[std::size_t(q.a)];
      const Element& te = triangles[std::size_t(q.b)];
      s.p = {pe.p[0], te.p[0], te.p[1], te.p[2]};
      const V3 xp = x(s.p[0]), xa = x(s.p[1]), xb = x(s.p[2]), xc = x(s.p[3]);
      const V3 c = closest_point_on_triangle<Scalar>(xp, xa, xb, xc);
      const std::array<Scalar, 3> bary = clamped_barycentric<Scalar>(c, xa, xb, xc);
      s.a = {1, -bary[0], -bary[1], -bary[2]};
      const V3 diff = xp - c;
      s.distance = diff.norm();
      s.n = s.distance > 0 ? V3(diff / s.distance) : triangle_normal(xa, xb, xc);
    } else {
      const Element& ea = edges[std::size_t(q.a)];
      const Element& eb = edges[std::size_t(q.b)];
      s.p = {ea.p[0], ea.p[1], eb.p[0], eb.p[1]};
      const V3 a0 = x(s.p[0]), a1 = x(s.p[1]), b0 = x(s.p[2]), b1 = x(s.p[3]);
      const auto cp = edge_edge_distance<Scalar>(a0, a1, b0, b1);
      s.a = {1 - cp.s, cp.s, -(1 - cp.t), -cp.t};
      const V3 diff = (a0 + cp.s * (a1 - a0)) - (b0 + cp.t * (b1 - b0));
      s.distance = std::sqrt(cp.squared_distance);
      s.n = s.distance > 0 ? V3(diff / s.distance) : edge_normal(a1 - a0, b1 - b0);
    }
    return s;
  }
  static V3 triangle_normal(const V3& a, const V3& b, const V3& c) {
    const V3 n = (b - a).cross(c - a);
    const Scalar len = n.norm();
    return len > 0 ? V3(n / len) : V3::UnitZ();
  }
  static V3 edge_normal(const V3& u, const V3& v) {
    V3 n = u.cross(v);
    if (!(n.norm() > 0)) n = u.unitOrthogonal();
    return n.normalized();
  }

  int n = 0;               // cloth points; obstacle points follow
  bool self = false;       // self-collision on
  Scalar self_gap = 0;     // the gap two cloth elements keep [m]
  bool any_pairs = false;  // anything to test
  Points<Scalar> x0, x1;   // start and end positions, cloth then obstacles
  Vector<Scalar> w;        // inverse masses [1/kg]; 0: immobile
  std::vector<int> owner;  // -1: cloth; else the collider's index
  std::vector<char> mark, pinned;
  std::vector<Scalar> gap;  // per collider [m]
  std::vector<Element> points, edges, triangles;
  std::vector<std::pair<int, int>> mesh_edges;  // scratch of add_obstacle()
  std::vector<char> used_vertex;                // scratch of add_obstacle(): in a triangle
  std::uint64_t layout = 0;  // the lists' value (see the file comment); 0: never set up
  // What the lists were last built from: the cloth's part and the obstacles'.
  int cloth_n = -1;
  Triangles cloth_triangles;
  Edges cloth_edges;
  std::array<std::size_t, 3> cloth_sizes{};  // points, edges, triangles of the cloth
  std::vector<Element> kept_points, kept_edges, kept_triangles;
};

}  // namespace massspring::contact
