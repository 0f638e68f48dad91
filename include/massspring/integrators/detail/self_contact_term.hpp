#pragma once
/// @file
/// @brief SelfContactTerm: self-contact of a system's surface inside an implicit solve, as a
/// correction of each point that the contact term's local step (contact_dual.hpp) applies before
/// the colliders' projection: P = P_colliders o P_self, one scaled dual variable and one weight per
/// point, so the solve's matrix keeps its pattern. It is projective dynamics' collision constraint
/// between parts of one cloth (Ly, Jouve and Bertails-Descoubes 2020, "Projective dynamics with
/// dry frictional contact", ACM TOG 39(4), section 4: self-contacts as constraints of the local
/// step, with the global matrix unchanged), solved as a Jacobi projection (each constraint
/// projected alone, the corrections of a point averaged).
///
/// **Pairs** (prepare()): a point and a triangle it is not a corner of, two edges that share no
/// point, taken from the pairs of the surface's triangles whose boxes over the motion from the
/// step's start to a guess overlap (contact/broad_phase/normal_cone_tree.hpp, boxes grown by the
/// radius below; a patch that cannot touch itself is not searched). A pair is kept when its
/// distance at the step's start is below
///   R = d + m + s,
/// d the distance the term keeps (below), m = d a margin for the iterates' departure from the
/// guess, and s the largest relative displacement start -> guess |D_i - D_j| of a point i of one
/// element and a point j of the other: the distance of two elements changes at most by that much
/// (the difference of two convex combinations of the D; per-vertex displacement bounds, as in
/// Chen et al. 2025, "Offset Geometric Contact", ACM TOG 44(4)), and a cloth moving as one body
/// keeps few pairs however fast it moves. So a pair not kept stays at least d apart
/// at every iterate whose points are all within m / 2 of the guess; outgrown() says when an
/// iterate is not, and the solver prepares again with it as the guess. A pair records its side at
/// the start, which has no crossing: for a point and a triangle the sign of the point's height
/// over the triangle's plane, for two edges the sign of (e_a x e_b) . (a0 - b0).
///
/// The side is recorded only when the closest points at the start are inside both elements (the
/// point over the triangle's face, the edges' closest points inside both): elsewhere a plane's
/// side says nothing about crossing (a point beside a bent neighbour triangle may lie below its
/// plane), and the pair's distance is unsigned.
///
/// **Projection** (correct(), every iterate, at positions y): a pair with a recorded side has
/// the gap g of its signed distance along that side (the height over the triangle's plane; the
/// signed distance of the edges' lines) when it is on that side and its closest points are inside
/// both elements, or when it is on the other side and its straight path from the start crossed
/// the face (the edges): within d of the plane (the lines) and inside both elements at
/// t = h0 / (h0 - g), h0 > 0 the start's signed distance, its weights then taken there. Otherwise
/// the gap is the elements' unsigned distance (beside a triangle or past an edge's end, the other
/// side of the plane or line is not a crossing), with the normal n from the second element to the
/// first. A pair with g < d gets the change lambda = d - g of its relative displacement along n,
/// shared by inverse mass: point k (weight a_k, + on the first element, - on the second,
/// barycentric; inverse mass w_k, 0 when pinned) moves by a_k w_k lambda n / sum_j a_j^2 w_j (the
/// denominator kept >= max_k |a_k| w_k / 2, so no point moves more than 2 lambda), which keeps the
/// pair's momentum, sum_k m_k (move_k) = 0 when every point is free. Coulomb friction at position
/// level: the pair's relative tangential displacement over the step shrinks by at most mu lambda. A
/// point's correction is the mean of its pairs' (Jacobi).
///
/// d = 1.5 thickness: the Jacobi mean under-corrects a point in several pairs and a step's
/// iterations may stop short of convergence, so the margin keeps the pairs the solve leaves
/// short of d outside the end-of-step pass's thickness (contact/response/surface_contact.hpp),
/// which stays the guarantee.
///
/// Positions are given as rows of 3 values: `row[i]` is point i's row, `point[r]` row r's point
/// (a solver that keeps every point passes the identity; FastMassSpring's reduced rows drop
/// pinned points). Allocates in build() and while the pair list grows past its largest size so
/// far; nothing after that.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "massspring/contact/broad_phase/normal_cone_tree.hpp"
#include "massspring/contact/distance/barycentric.hpp"
#include "massspring/contact/distance/edge_edge.hpp"
#include "massspring/contact/distance/point_triangle.hpp"
#include "massspring/types.hpp"

namespace massspring::detail {

template <class Scalar>
class SelfContactTerm {
 public:
  using V3 = Vector3<Scalar>;

  /// @brief The distance the term keeps, as a multiple of the self-collision thickness.
  static constexpr double kDistanceFactor = 1.5;

  /// @brief The surface, its triangles' edges, the rows of the iterate (`row` per point, `point`
  /// per row, `rows` of them; see the file comment) and the inverse masses (0 for pinned points);
  /// the tree of the triangles. Off (clear()) when the system has no self-collision or no surface.
  /// Allocates.
  template <class System>
  void build(const System& system, const std::vector<int>& row, const std::vector<int>& point,
             int rows) {
    clear();
    const auto& tris = system.surface();
    if (!system.self_collision() || tris.rows() == 0) return;
    surface_ = tris;
    const int n = system.num_points();
    triangles_.resize(std::size_t(tris.rows()));
    for (Eigen::Index t = 0; t < tris.rows(); ++t)
      triangles_[std::size_t(t)] = {tris(t, 0), tris(t, 1), tris(t, 2)};
    const auto& edges = system.surface_edges();  // (i, j), i < j, ascending
    edges_.resize(std::size_t(edges.rows()));
    for (Eigen::Index e = 0; e < edges.rows(); ++e)
      edges_[std::size_t(e)] = {edges(e, 0), edges(e, 1)};
    triangle_edges_.resize(triangles_.size());
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int i = triangles_[t][std::size_t(k)], j = triangles_[t][std::size_t((k + 1) % 3)];
        const std::array<int, 2> key = {std::min(i, j), std::max(i, j)};
        triangle_edges_[t][std::size_t(k)] =
            int(std::lower_bound(edges_.begin(), edges_.end(), key) - edges_.begin());
      }
    point_owner_.assign(std::size_t(n), -1);
    edge_owner_.assign(edges_.size(), -1);
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        int& p = point_owner_[std::size_t(triangles_[t][std::size_t(k)])];
        if (p < 0) p = int(t);
        int& e = edge_owner_[std::size_t(triangle_edges_[t][std::size_t(k)])];
        if (e < 0) e = int(t);
      }
    row_ = row;
    point_ = point;
    inverse_mass_.setZero(rows);
    for (int i = 0; i < n; ++i)
      if (!system.is_pinned(i))
        inverse_mass_(row_[std::size_t(i)]) = Scalar(1) / system.masses()(i);
    x0_ = system.positions();
    x1_ = x0_;
    sum_.setZero(3 * Eigen::Index(rows));
    count_.setZero(rows);
    tree_.build(x0_, triangles_);
    built_ = true;
  }

  /// @brief build() with every point its own row, in order (BackwardEuler's layout).
  template <class System>
  void build(const System& system) {
    const int n = system.num_points();
    std::vector<int> identity(std::size_t(n), 0);
    for (int i = 0; i < n; ++i) identity[std::size_t(i)] = i;
    build(system, identity, identity, n);
  }

  /// @brief Off: no pairs, until build() again.
  void clear() {
    built_ = false;
    active_ = false;
    pairs_.clear();
  }

  /// @brief True when build() found a surface with self-collision.
  [[nodiscard]] bool built() const { return built_; }
  /// @brief True when prepare() kept any pair this step.
  [[nodiscard]] bool active() const { return active_; }
  /// @brief The pairs prepare() kept.
  [[nodiscard]] std::size_t pairs() const { return pairs_.size(); }
  /// @brief Whether build() must run again: the system's self-collision on a surface is not
  /// what build() saw (on or off), or its surface changed.
  template <class System>
  [[nodiscard]] bool stale(const System& system) const {
    const bool wanted = system.self_collision().has_value() && system.surface().rows() > 0;
    return wanted != built_ || (built_ && !same_surface(system.surface()));
  }
  /// @brief Whether `triangles` is the surface build() was given.
  [[nodiscard]] bool same_surface(const Triangles& triangles) const {
    return triangles.rows() == surface_.rows() && triangles == surface_;
  }

  /// @brief The step's pairs (see the file comment) for the motion from the system's positions
  /// to `guess` (the iterate's rows, as many as build() was given, row order), with the system's
  /// self-collision thickness and friction.
  template <class System>
  void prepare(const System& system, const Scalar* guess) {
    active_ = false;
    pairs_.clear();
    if (!built_ || !system.self_collision()) return;
    distance_ = Scalar(kDistanceFactor) * system.self_collision()->thickness;
    friction_ = system.self_collision()->friction;
    x0_ = system.positions();  // same size: no allocation
    const int n = int(x0_.rows());
    for (int i = 0; i < n; ++i) {
      const Scalar* g = guess + 3 * row_[std::size_t(i)];
      for (int c = 0; c < 3; ++c) x1_(i, c) = g[c];
    }
    const Scalar reach = 2 * distance_;  // d + m
    tree_.refit(x0_, x1_, reach / 2);
    // Each point and edge is paired from the triangle that owns it (the first that lists it),
    // so each pair comes from one pair of triangles: no duplicates.
    tree_.self_pairs(x0_, x1_, [&](int s, int t) {
      for (int st = 0; st < 2; ++st) {
        const int u = st == 0 ? s : t, v = st == 0 ? t : s;
        for (int i : triangles_[std::size_t(u)])
          if (point_owner_[std::size_t(i)] == u) add_point_triangle(i, v, reach);
      }
      for (int a : triangle_edges_[std::size_t(s)]) {
        if (edge_owner_[std::size_t(a)] != s) continue;
        for (int b : triangle_edges_[std::size_t(t)])
          if (edge_owner_[std::size_t(b)] == t) add_edge_edge(a, b, reach);
      }
    });
    active_ = !pairs_.empty();
  }

  /// @brief Whether some point of y (the iterate's rows, row order) is farther than m / 2 = d / 2
  /// from the guess prepare() was given: then a pair prepare() did not keep may be closer than d
  /// (see the file comment), and prepare() should be called again with y. False when not built.
  [[nodiscard]] bool outgrown(const Scalar* y) const {
    if (!built_) return false;
    const Scalar limit2 = distance_ * distance_ / 4;
    for (Eigen::Index i = 0; i < x1_.rows(); ++i) {
      const Scalar* p = y + 3 * row_[std::size_t(i)];
      const Scalar d2 = (V3(p[0], p[1], p[2]) - x1_.row(i).transpose()).squaredNorm();
      if (!(d2 <= limit2)) return true;
    }
    return false;
  }

  /// @brief The corrections of the term at positions y (the iterate's rows, row order), each row
  /// r < rows moved by dual[3 r .. 3 r + 3) first when `dual` is not null: into c (3 per row,
  /// the first `rows` rows), the mean of the pairs' moves of each point (0 when none). Returns
  /// whether any row moved. Allocates nothing.
  bool correct(const Scalar* y, const Scalar* dual, int rows, Scalar* c) {
    sum_.setZero();
    count_.setZero();
    const auto at = [&](int r) {
      V3 p(y[3 * r], y[3 * r + 1], y[3 * r + 2]);
      if (dual && r < rows) p += V3(dual[3 * r], dual[3 * r + 1], dual[3 * r + 2]);
      return p;
    };
    bool any = false;
    for (const Pair& q : pairs_) {
      const std::array<V3, 4> x = {at(q.p[0]), at(q.p[1]), at(q.p[2]), at(q.p[3])};
      // Cheap tests first: a pair at least d apart along its recorded side (the triangle's
      // plane, the edges' lines) or, on that side, with boxes more than d apart is inactive.
      const Scalar side = side_distance(q, x);
      if (side >= distance_ || (side >= 0 && apart(x, q.kind == 0 ? 1 : 2))) continue;
      std::array<Scalar, 4> a;
      V3 n;
      Scalar gap;
      if (!stencil(q, x, a, n, gap) || !(gap < distance_)) continue;
      any = project(q, x, a, n, distance_ - gap) || any;
    }
    for (int r = 0; r < rows; ++r) {
      const Scalar k = count_(r);
      for (int j = 0; j < 3; ++j) c[3 * r + j] = k > 0 ? sum_(3 * r + j) / k : Scalar(0);
    }
    return any;
  }

 private:
  struct Candidate {
    int kind, a, b;  // 0: point a, triangle b; 1: edges a and b
  };
  struct Pair {
    int kind;
    std::array<int, 4> p;  // rows: the point then the triangle's corners, or two edges' ends
    Scalar side;           // +1 or -1 (0: none recorded, the distance is unsigned)
  };

  void add_point_triangle(int i, int t, Scalar reach) {
    const auto& c = triangles_[std::size_t(t)];
    if (i != c[0] && i != c[1] && i != c[2]) keep({0, i, t}, reach);
  }
  void add_edge_edge(int a, int b, Scalar reach) {
    const auto& ea = edges_[std::size_t(a)];
    const auto& eb = edges_[std::size_t(b)];
    if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) return;
    keep({1, a, b}, reach);
  }

  V3 start(int i) const { return x0_.row(i).transpose(); }

  // Keeps candidate q when its start distance is below reach + the displacement bounds, with its
  // start side; skips pairs whose every point is pinned.
  void keep(const Candidate& q, Scalar reach) {
    std::array<int, 4> p;
    if (q.kind == 0) {
      const auto& t = triangles_[std::size_t(q.b)];
      p = {q.a, t[0], t[1], t[2]};
    } else {
      const auto& ea = edges_[std::size_t(q.a)];
      const auto& eb = edges_[std::size_t(q.b)];
      p = {ea[0], ea[1], eb[0], eb[1]};
    }
    const int split = q.kind == 0 ? 1 : 2;
    Scalar mobile = 0, spread2 = 0;
    for (int k = 0; k < 4; ++k) {
      const int i = p[std::size_t(k)];
      mobile += inverse_mass_(row_[std::size_t(i)]);
      for (int j = split; k < split && j < 4; ++j) {
        const int l = p[std::size_t(j)];
        spread2 = std::max(
            spread2, Scalar(((x1_.row(i) - x0_.row(i)) - (x1_.row(l) - x0_.row(l))).squaredNorm()));
      }
    }
    if (!(mobile > 0)) return;
    const Scalar radius = reach + std::sqrt(spread2);
    // The boxes of the two elements at the start, farther apart than the radius along an axis.
    for (int c = 0; c < 3; ++c) {
      Scalar lo[2] = {x0_(p[0], c), x0_(p[std::size_t(split)], c)}, hi[2] = {lo[0], lo[1]};
      for (int k = 0; k < 4; ++k) {
        const int side = k < split ? 0 : 1;
        const Scalar v = x0_(p[std::size_t(k)], c);
        lo[side] = std::min(lo[side], v);
        hi[side] = std::max(hi[side], v);
      }
      if (lo[0] - hi[1] > radius || lo[1] - hi[0] > radius) return;
    }
    const std::array<V3, 4> x = {start(p[0]), start(p[1]), start(p[2]), start(p[3])};
    Scalar distance2, side;
    // The side only when the closest points are inside both elements (see the file comment).
    if (q.kind == 0) {
      const V3 c = contact::closest_point_on_triangle<Scalar>(x[0], x[1], x[2], x[3]);
      distance2 = (x[0] - c).squaredNorm();
      side = over_face(x) ? (x[0] - x[1]).dot((x[2] - x[1]).cross(x[3] - x[1])) : Scalar(0);
    } else {
      const auto cp = contact::edge_edge_distance<Scalar>(x[0], x[1], x[2], x[3]);
      distance2 = cp.squared_distance;
      side = between_ends(x) ? (x[1] - x[0]).cross(x[3] - x[2]).dot(x[0] - x[2]) : Scalar(0);
    }
    if (!(distance2 < radius * radius)) return;
    Pair pair{q.kind, {}, side > 0 ? Scalar(1) : side < 0 ? Scalar(-1) : Scalar(0)};
    for (int k = 0; k < 4; ++k) pair.p[std::size_t(k)] = row_[std::size_t(p[std::size_t(k)])];
    pairs_.push_back(pair);
  }

  // The pair's weights a, normal n and gap at positions x (see the file comment); false when
  // degenerate (no normal).
  bool stencil(const Pair& q, const std::array<V3, 4>& x, std::array<Scalar, 4>& a, V3& n,
               Scalar& gap) const {
    const V3 normal =
        q.kind == 0 ? V3((x[2] - x[1]).cross(x[3] - x[1])) : V3((x[1] - x[0]).cross(x[3] - x[2]));
    const Scalar length = normal.norm();
    if (q.side != 0 && length > 0) {
      // Signed along the recorded side: on that side and over the face (between the ends) now,
      // or on the other side having crossed the face on the way: at the time t the height,
      // taken linear from the start's h0 > 0 to gap < 0, is zero, the straight paths' positions
      // within d of the plane (the lines) and over the face (between the ends).
      const V3& base = q.kind == 0 ? x[1] : x[2];
      n = normal * (q.side / length);
      gap = n.dot(x[0] - base);
      if (gap >= 0 && interior_weights(q.kind, x, a)) return true;
      if (gap < 0) {
        std::array<V3, 4> y;
        const std::array<V3, 4> x0 = {x0_row(q.p[0]), x0_row(q.p[1]), x0_row(q.p[2]),
                                      x0_row(q.p[3])};
        const Scalar h0 = side_distance(q, x0);
        if (h0 > 0) {
          const Scalar t = h0 / (h0 - gap);
          for (std::size_t k = 0; k < 4; ++k) y[k] = x0[k] + t * (x[k] - x0[k]);
          if (std::abs(side_distance(q, y)) < distance_ && interior_weights(q.kind, y, a))
            return true;
        }
      }
    }
    if (q.kind == 0) {
      const V3 c = contact::closest_point_on_triangle<Scalar>(x[0], x[1], x[2], x[3]);
      const std::array<Scalar, 3> b = contact::clamped_barycentric<Scalar>(c, x[1], x[2], x[3]);
      a = {1, -b[0], -b[1], -b[2]};
      return unsigned_gap(x[0] - c, n, gap);
    }
    const auto cp = contact::edge_edge_distance<Scalar>(x[0], x[1], x[2], x[3]);
    a = {1 - cp.s, cp.s, -(1 - cp.t), -cp.t};
    return unsigned_gap((x[0] + cp.s * (x[1] - x[0])) - (x[2] + cp.t * (x[3] - x[2])), n, gap);
  }
  // When the point is over the face (kind 0) or the edges' closest points are between their ends
  // (kind 1) at x, the pair's weights there into a (barycentric: + on the first element, - on
  // the second), and true.
  static bool interior_weights(int kind, const std::array<V3, 4>& x, std::array<Scalar, 4>& a) {
    if (kind == 0) {
      if (!over_face(x)) return false;
      const std::array<Scalar, 3> b = contact::plane_barycentric<Scalar>(x[0], x[1], x[2], x[3]);
      a = {1, -b[0], -b[1], -b[2]};
      return true;
    }
    Scalar s, t;
    if (!between_ends(x, s, t)) return false;
    a = {1 - s, s, -(1 - t), -t};
    return true;
  }
  // The signed distance along the pair's recorded side of the point from the triangle's plane,
  // or of the edges' lines (a lower bound of the elements' distance when >= 0); 0 when the pair
  // records no side or the normal is degenerate.
  static Scalar side_distance(const Pair& q, const std::array<V3, 4>& x) {
    if (q.side == 0) return 0;
    const V3 normal =
        q.kind == 0 ? V3((x[2] - x[1]).cross(x[3] - x[1])) : V3((x[1] - x[0]).cross(x[3] - x[2]));
    const Scalar length = normal.norm();
    if (!(length > 0)) return 0;
    return q.side * normal.dot(x[0] - (q.kind == 0 ? x[1] : x[2])) / length;
  }
  // Whether the boxes of x[0, split) and x[split, 4) are more than the distance apart along an
  // axis (then the elements are too, and the pair is inactive: gap >= distance).
  bool apart(const std::array<V3, 4>& x, int split) const {
    const std::size_t h = std::size_t(split);
    V3 lo_a = x[0], hi_a = x[0], lo_b = x[h], hi_b = x[h];
    for (std::size_t k = 1; k < 4; ++k) {
      V3& lo = k < h ? lo_a : lo_b;
      V3& hi = k < h ? hi_a : hi_b;
      lo = lo.cwiseMin(x[k]);
      hi = hi.cwiseMax(x[k]);
    }
    return ((lo_a - hi_b).array() > distance_).any() || ((lo_b - hi_a).array() > distance_).any();
  }
  // The gap |diff| along diff (the unsigned distance).
  static bool unsigned_gap(const V3& diff, V3& n, Scalar& gap) {
    gap = diff.norm();
    if (!(gap > 0)) return false;
    n = diff / gap;
    return true;
  }
  // Whether x[0]'s projection on the plane of the triangle (x[1], x[2], x[3]) is inside it, its
  // three barycentric coordinates positive (unclamped: a point beside an edge, whose closest
  // point is on the edge, is not over the face).
  static bool over_face(const std::array<V3, 4>& x) {
    const std::array<Scalar, 3> b = contact::plane_barycentric<Scalar>(x[0], x[1], x[2], x[3]);
    return b[0] > 0 && b[1] > 0 && b[2] > 0;
  }
  // Whether the edges (x[0], x[1]) and (x[2], x[3]) are not near parallel (kParallel) and their
  // lines' closest points are inside both, strictly (unclamped parameters).
  static bool between_ends(const std::array<V3, 4>& x) {
    Scalar s, t;
    return between_ends(x, s, t);
  }
  // between_ends(), with the lines' parameters of the closest points into s and t.
  static bool between_ends(const std::array<V3, 4>& x, Scalar& s, Scalar& t) {
    const V3 ea = x[1] - x[0], eb = x[3] - x[2], w = x[0] - x[2];
    const Scalar aa = ea.dot(ea), ab = ea.dot(eb), bb = eb.dot(eb);
    if (!(ea.cross(eb).squaredNorm() > kParallel * aa * bb)) return false;
    const Scalar den = aa * bb - ab * ab, aw = ea.dot(w), bw = eb.dot(w);
    s = (ab * bw - bb * aw) / den;
    t = (aa * bw - ab * aw) / den;
    return s > 0 && s < 1 && t > 0 && t < 1;
  }
  // Adds the pair's moves for the change lambda of its relative displacement along n, with
  // friction; false when no point may move.
  bool project(const Pair& q, const std::array<V3, 4>& x, const std::array<Scalar, 4>& a,
               const V3& n, Scalar lambda) {
    Scalar den = 0, lever = 0;
    for (int k = 0; k < 4; ++k) {
      const Scalar w = inverse_mass_(q.p[std::size_t(k)]);
      den += a[std::size_t(k)] * a[std::size_t(k)] * w;
      lever = std::max(lever, std::abs(a[std::size_t(k)]) * w);
    }
    if (!(den > 0)) return false;
    den = std::max(den, lever / 2);
    V3 change = lambda * n;
    if (friction_ > 0) {
      V3 relative = V3::Zero();  // relative displacement over the step
      for (int k = 0; k < 4; ++k) {
        const int r = q.p[std::size_t(k)];
        relative += a[std::size_t(k)] * (x[std::size_t(k)] - V3(x0_row(r)));
      }
      const V3 t = relative - relative.dot(n) * n;
      const Scalar length = t.norm();
      if (length > 0) change -= std::min(length, friction_ * lambda) / length * t;
    }
    for (int k = 0; k < 4; ++k) {
      const int r = q.p[std::size_t(k)];
      const Scalar s = a[std::size_t(k)] * inverse_mass_(r) / den;
      if (s == 0) continue;
      for (int c = 0; c < 3; ++c) sum_(3 * r + c) += s * change(c);
      count_(r) += 1;
    }
    return true;
  }
  // The start position of the point of row r.
  V3 x0_row(int r) const { return x0_.row(point_of_row(r)).transpose(); }
  int point_of_row(int r) const { return point_[std::size_t(r)]; }

  // Two edges closer to parallel than this (|e_a x e_b|^2 <= kParallel |e_a|^2 |e_b|^2, about
  // 0.6 degrees) record no side.
  static constexpr Scalar kParallel = Scalar(1e-4);

  bool built_ = false, active_ = false;
  Scalar distance_ = 0, friction_ = 0;
  Triangles surface_;
  std::vector<std::array<int, 3>> triangles_, triangle_edges_;
  std::vector<std::array<int, 2>> edges_;
  std::vector<int> row_, point_;
  std::vector<int> point_owner_, edge_owner_;  // the first triangle that lists each
  Vector<Scalar> inverse_mass_;                // per row [1/kg]; 0 when pinned
  Points<Scalar> x0_, x1_;                     // the step's start and the guess, per point
  Vector<Scalar> sum_, count_;                 // per row: the summed moves and their number
  contact::NormalConeTree<Scalar> tree_;
  std::vector<Pair> pairs_;
};

}  // namespace massspring::detail
