#pragma once
// An independent oracle for the self-collision and contact tests: does a cloth's surface cross
// itself, and how close do its non-adjacent elements come? Written without the library's contact
// code (nothing from massspring/contact/ is used), for correctness over speed.
//
// Exactness. Crossing decisions use exact signs of two determinants:
//   orient3d(a, b, c, d) = det[a - d; b - d; c - d]   (rows are 3-vectors)
//   orient2d(a, b, c)    = det[a - c; b - c]          (rows are 2-vectors)
// computed as in J. R. Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast Robust
// Geometric Predicates", Discrete Comput. Geom. 18 (1997): first in double with the error bounds
// of that paper (errboundA: (7 + 56 eps) eps times the permanent for orient3d, (3 + 16 eps) eps
// for orient2d, eps = 2^-53); when the filter cannot decide, the determinant is evaluated exactly
// in expansion arithmetic (two_diff, two_product by fma, scale_expansion_zeroelim,
// grow_expansion_zeroelim of the same paper) and its sign is the sign of the expansion's most
// significant component. The signs are exact for any double coordinates whose products neither
// overflow nor underflow (|x| between about 1e-100 and 1e100, or 0).
//
// Distances (min_separation) are ordinary double arithmetic: each candidate is the distance to
// an actual point of the element, so every candidate is an upper bound and the minimum over the
// candidates is the true distance up to rounding.
//
// Pruning. Both brute-force searches visit only the pairs whose axis-aligned bounding boxes could
// matter: a sort-and-sweep along the axis of largest extent. For crossings, a segment and a
// triangle can meet only if their closed boxes overlap; for distances, a pair is skipped only
// when the distance between the boxes (a lower bound of the elements' distance) is not below the
// best distance found so far. Neither can drop a pair that changes the answer.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "massspring/types.hpp"

namespace massspring::test {

namespace intersections_detail {

using P3 = Eigen::Vector3d;

// ---- expansion arithmetic (Shewchuk 1997, section 2) ------------------------------------------

/// A nonoverlapping expansion: the exact value is the sum of v[0..n), smallest magnitude first,
/// no zero component (so the sign is the sign of v[n - 1], and n == 0 means exactly 0).
struct Expansion {
  static constexpr int kCapacity = 256;
  std::array<double, kCapacity> v{};
  int n = 0;
  void push(double x) {
    if (x == 0) return;
    if (n == kCapacity) throw std::logic_error("intersections: expansion capacity exceeded");
    v[std::size_t(n++)] = x;
  }
  [[nodiscard]] int sign() const { return n == 0 ? 0 : (v[std::size_t(n - 1)] > 0 ? 1 : -1); }
};

/// x + y = a + b exactly, x = fl(a + b) (Knuth's two_sum).
inline void two_sum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a, av = x - bv;
  y = (a - av) + (b - bv);
}

/// x + y = a * b exactly, x = fl(a * b) (the fma gives the rounding error exactly).
inline void two_product(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);
}

/// The exact difference a - b as an expansion of at most two components.
inline Expansion difference(double a, double b) {
  double x, y;
  two_sum(a, -b, x, y);
  Expansion e;
  e.push(y);
  e.push(x);
  return e;
}

/// e + b (grow_expansion_zeroelim).
inline Expansion grow(const Expansion& e, double b) {
  Expansion h;
  double q = b;
  for (int i = 0; i < e.n; ++i) {
    double sum, err;
    two_sum(q, e.v[std::size_t(i)], sum, err);
    h.push(err);
    q = sum;
  }
  h.push(q);
  return h;
}

/// e + f (repeated grow_expansion_zeroelim, the expansion_sum of the paper).
inline Expansion sum(const Expansion& e, const Expansion& f) {
  Expansion h = e;
  for (int i = 0; i < f.n; ++i) h = grow(h, f.v[std::size_t(i)]);
  return h;
}

inline Expansion negate(Expansion e) {
  for (int i = 0; i < e.n; ++i) e.v[std::size_t(i)] = -e.v[std::size_t(i)];
  return e;
}

/// e * b (scale_expansion_zeroelim).
inline Expansion scale(const Expansion& e, double b) {
  Expansion h;
  if (e.n == 0 || b == 0) return h;
  double q, err;
  two_product(e.v[0], b, q, err);
  h.push(err);
  for (int i = 1; i < e.n; ++i) {
    double p1, p0, s, t;
    two_product(e.v[std::size_t(i)], b, p1, p0);
    two_sum(q, p0, s, t);
    h.push(t);
    two_sum(p1, s, q, t);  // p1 + s is exact in two components: q (fast_two_sum would do)
    h.push(t);
  }
  h.push(q);
  return h;
}

/// e * f (the sum of e scaled by each component of f).
inline Expansion product(const Expansion& e, const Expansion& f) {
  Expansion h;
  for (int i = 0; i < f.n; ++i) h = sum(h, scale(e, f.v[std::size_t(i)]));
  return h;
}

inline int sign_of(double x) { return (x > 0) - (x < 0); }

// ---- the predicates ----------------------------------------------------------------------------

/// The exact sign of orient3d(a, b, c, d) = det[a - d; b - d; c - d]: zero iff the four points
/// are coplanar; swapping two arguments flips it.
inline int orient3d(const P3& a, const P3& b, const P3& c, const P3& d) {
  const double adx = a.x() - d.x(), bdx = b.x() - d.x(), cdx = c.x() - d.x();
  const double ady = a.y() - d.y(), bdy = b.y() - d.y(), cdy = c.y() - d.y();
  const double adz = a.z() - d.z(), bdz = b.z() - d.z(), cdz = c.z() - d.z();
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
                           (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
                           (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
  constexpr double eps = std::numeric_limits<double>::epsilon() / 2;  // 2^-53
  const double bound = (7.0 + 56.0 * eps) * eps * permanent;
  if (det > bound || -det > bound) return sign_of(det);
  // Exact: the same formula on exact differences.
  const Expansion ax = difference(a.x(), d.x()), bx = difference(b.x(), d.x()),
                  cx = difference(c.x(), d.x());
  const Expansion ay = difference(a.y(), d.y()), by = difference(b.y(), d.y()),
                  cy = difference(c.y(), d.y());
  const Expansion az = difference(a.z(), d.z()), bz = difference(b.z(), d.z()),
                  cz = difference(c.z(), d.z());
  auto minor = [](const Expansion& p, const Expansion& q, const Expansion& r, const Expansion& s) {
    return sum(product(p, q), negate(product(r, s)));
  };
  const Expansion t1 = product(az, minor(bx, cy, cx, by));
  const Expansion t2 = product(bz, minor(cx, ay, ax, cy));
  const Expansion t3 = product(cz, minor(ax, by, bx, ay));
  return sum(sum(t1, t2), t3).sign();
}

using P2 = Eigen::Vector2d;

/// The exact sign of orient2d(a, b, c) = det[a - c; b - c]: positive iff a, b, c turn
/// counterclockwise, zero iff collinear.
inline int orient2d(const P2& a, const P2& b, const P2& c) {
  const double left = (a.x() - c.x()) * (b.y() - c.y());
  const double right = (a.y() - c.y()) * (b.x() - c.x());
  const double det = left - right;
  constexpr double eps = std::numeric_limits<double>::epsilon() / 2;
  const double bound = (3.0 + 16.0 * eps) * eps * (std::abs(left) + std::abs(right));
  if (det > bound || -det > bound) return sign_of(det);
  const Expansion l = product(difference(a.x(), c.x()), difference(b.y(), c.y()));
  const Expansion r = product(difference(a.y(), c.y()), difference(b.x(), c.x()));
  return sum(l, negate(r)).sign();
}

/// Whether c, known collinear with a and b, lies in the closed segment ab (coordinate bounds;
/// exact comparisons).
inline bool on_segment_2d(const P2& a, const P2& b, const P2& c) {
  return std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

/// Whether the closed segments pq and rs of the plane meet (Cormen et al., "Introduction to
/// Algorithms", section 33.1: a proper crossing, or an endpoint on the other segment).
inline bool segments_meet_2d(const P2& p, const P2& q, const P2& r, const P2& s) {
  const int d1 = orient2d(r, s, p), d2 = orient2d(r, s, q);
  const int d3 = orient2d(p, q, r), d4 = orient2d(p, q, s);
  if (d1 * d2 < 0 && d3 * d4 < 0) return true;
  return (d1 == 0 && on_segment_2d(r, s, p)) || (d2 == 0 && on_segment_2d(r, s, q)) ||
         (d3 == 0 && on_segment_2d(p, q, r)) || (d4 == 0 && on_segment_2d(p, q, s));
}

/// Whether the closed segment pq meets the closed triangle abc, all five points in one plane.
/// They are projected along a coordinate axis for which the triangle's projection is not
/// degenerate (the projection is then an affine bijection of their plane, so it keeps
/// intersection); there the segment meets the triangle iff an end point is inside it or the
/// segment meets one of its sides.
/// @throws std::invalid_argument when the triangle is degenerate (collinear corners).
inline bool coplanar_segment_meets_triangle(const P3& p, const P3& q, const P3& a, const P3& b,
                                            const P3& c) {
  const P3 n = (b - a).cross(c - a);
  std::array<int, 3> axes{0, 1, 2};  // try the dropped axis in order of |normal| component
  std::sort(axes.begin(), axes.end(),
            [&](int i, int j) { return std::abs(n(i)) > std::abs(n(j)); });
  for (const int drop : axes) {
    const int u = (drop + 1) % 3, v = (drop + 2) % 3;
    auto proj = [&](const P3& x) { return P2(x(u), x(v)); };
    const P2 a2 = proj(a), q2 = proj(q), p2 = proj(p);
    P2 b2 = proj(b), c2 = proj(c);
    const int o = orient2d(a2, b2, c2);
    if (o == 0) continue;
    if (o < 0) std::swap(b2, c2);  // counterclockwise from here on
    auto inside = [&](const P2& x) {
      return orient2d(a2, b2, x) >= 0 && orient2d(b2, c2, x) >= 0 && orient2d(c2, a2, x) >= 0;
    };
    return inside(p2) || inside(q2) || segments_meet_2d(p2, q2, a2, b2) ||
           segments_meet_2d(p2, q2, b2, c2) || segments_meet_2d(p2, q2, c2, a2);
  }
  throw std::invalid_argument("intersections: degenerate triangle (collinear corners)");
}

/// Whether the closed segment pq meets the closed triangle abc (touching counts). When p and q
/// are not both in the triangle's plane: they must not be strictly on the same side of it
/// (orient3d(a,b,c,p) and orient3d(a,b,c,q) of opposite signs, or one zero), and the line pq
/// must pass through the closed triangle, i.e. orient3d(p,q,a,b), orient3d(p,q,b,c),
/// orient3d(p,q,c,a) never of strictly opposite signs. Then the line meets the plane at one
/// point, which is on the segment, so the two conditions are exact. Otherwise the coplanar test.
inline bool segment_meets_triangle(const P3& p, const P3& q, const P3& a, const P3& b,
                                   const P3& c) {
  const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
  if (sp == 0 && sq == 0) return coplanar_segment_meets_triangle(p, q, a, b, c);
  if (sp * sq > 0) return false;
  const int o1 = orient3d(p, q, a, b), o2 = orient3d(p, q, b, c), o3 = orient3d(p, q, c, a);
  const bool positive = o1 > 0 || o2 > 0 || o3 > 0, negative = o1 < 0 || o2 < 0 || o3 < 0;
  return !(positive && negative);
}

// ---- distances ---------------------------------------------------------------------------------

/// Distance from p to the closed segment ab: the clamped projection (a point of the segment).
inline double point_segment_distance(const P3& p, const P3& a, const P3& b) {
  const P3 d = b - a;
  const double dd = d.squaredNorm();
  const double t = dd > 0 ? std::clamp((p - a).dot(d) / dd, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

/// Distance from p to the closed triangle abc. The nearest point is either inside the triangle,
/// where it is the orthogonal projection onto the plane (taken when its barycentric coordinates
/// are all >= 0), or on a side: the minimum of both kinds of candidate.
inline double point_triangle_distance(const P3& p, const P3& a, const P3& b, const P3& c) {
  double best = std::min({point_segment_distance(p, a, b), point_segment_distance(p, b, c),
                          point_segment_distance(p, c, a)});
  const P3 n = (b - a).cross(c - a);
  const double nn = n.squaredNorm();
  if (nn > 0) {
    const P3 f = p - ((p - a).dot(n) / nn) * n;  // the foot in the plane
    const double wa = (c - b).cross(f - b).dot(n), wb = (a - c).cross(f - c).dot(n),
                 wc = (b - a).cross(f - a).dot(n);
    if (wa >= 0 && wb >= 0 && wc >= 0) best = std::min(best, (p - f).norm());
  }
  return best;
}

/// Distance between the closed segments p0p1 and q0q1. |p0 + s d1 - q0 - t d2|^2 is convex in
/// (s, t): its minimum over [0, 1]^2 is the unconstrained minimiser (when unique and inside) or
/// lies on the square's border, where one segment is at an end point: the minimum of the
/// interior candidate and the four end point to segment distances.
inline double segment_segment_distance(const P3& p0, const P3& p1, const P3& q0, const P3& q1) {
  double best = std::min({point_segment_distance(p0, q0, q1), point_segment_distance(p1, q0, q1),
                          point_segment_distance(q0, p0, p1), point_segment_distance(q1, p0, p1)});
  const P3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.dot(d1), b = d1.dot(d2), e = d2.dot(d2), c = d1.dot(r), f = d2.dot(r);
  const double den = a * e - b * b;  // >= 0; 0 when parallel
  if (den > 0) {
    // Stationary point: a s - b t = -c, b s - e t = -f.
    const double s = (b * f - c * e) / den, t = (a * f - b * c) / den;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1)
      best = std::min(best, ((p0 + s * d1) - (q0 + t * d2)).norm());
  }
  return best;
}

// ---- the sweep ---------------------------------------------------------------------------------

/// One element's closed axis-aligned bounding box; kind 0 point, 1 edge, 2 triangle.
struct Box {
  P3 lo, hi;
  int kind = 0;
  int index = 0;
};

inline Box box_of(const Points<double>& x, std::initializer_list<int> ids, int kind, int index) {
  Box b;
  b.lo = P3::Constant(std::numeric_limits<double>::infinity());
  b.hi = -b.lo;
  for (const int i : ids) {
    b.lo = b.lo.cwiseMin(x.row(i).transpose());
    b.hi = b.hi.cwiseMax(x.row(i).transpose());
  }
  b.kind = kind;
  b.index = index;
  return b;
}

/// The coordinate axis along which the points spread most.
inline int sweep_axis(const Points<double>& x) {
  if (x.rows() == 0) return 0;
  const Eigen::RowVector3d extent = x.colwise().maxCoeff() - x.colwise().minCoeff();
  Eigen::Index axis = 0;
  extent.maxCoeff(&axis);
  return int(axis);
}

/// Sorts the boxes by their low end along axis.
inline void sort_along(std::vector<Box>& boxes, int axis) {
  std::sort(boxes.begin(), boxes.end(),
            [axis](const Box& l, const Box& r) { return l.lo(axis) < r.lo(axis); });
}

/// Distance between two boxes (0 when they overlap): a lower bound of their contents' distance.
inline double box_distance(const Box& l, const Box& r) {
  const P3 gap = (l.lo - r.hi).cwiseMax(r.lo - l.hi).cwiseMax(0.0);
  return gap.norm();
}

inline P3 point(const Points<double>& x, int i) { return x.row(i).transpose(); }

template <class Indices>
void check_indices(const Points<double>& x, const Indices& ids, const char* what) {
  if (ids.size() > 0 && (ids.minCoeff() < 0 || ids.maxCoeff() >= x.rows()))
    throw std::invalid_argument(std::string("intersections: ") + what +
                                " refer to a point that does not exist");
}

}  // namespace intersections_detail

/// @brief The edges of a triangle surface: each side of a triangle once, as (i, j) with i < j,
/// ascending. These are the edges count_crossings() and min_separation() expect (a surface's
/// springs would not do: a bending spring passes through a point of the surface).
inline Edges triangle_edges(const Triangles& triangles) {
  std::set<std::pair<int, int>> sides;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int i = triangles(t, k), j = triangles(t, (k + 1) % 3);
      sides.emplace(std::min(i, j), std::max(i, j));
    }
  Edges edges(Eigen::Index(sides.size()), 2);
  Eigen::Index e = 0;
  for (const auto& [i, j] : sides) edges.row(e++) << i, j;
  return edges;
}

/// @brief The number of (edge, triangle) pairs, the edge sharing no point with the triangle,
/// whose closed segment meets the closed triangle (touching counts). Exact (see the file's
/// comment); 0 for a surface free of self-intersection.
/// @param x positions, #points by 3
/// @param triangles the surface, #triangles by 3 indices into x
/// @param edges the segments to test, #edges by 2 (normally triangle_edges(triangles))
/// @throws std::invalid_argument for an index out of range or a degenerate triangle met by a
/// coplanar segment.
inline int count_crossings(const Points<double>& x, const Triangles& triangles,
                           const Edges& edges) {
  namespace d = intersections_detail;
  d::check_indices(x, triangles, "triangles");
  d::check_indices(x, edges, "edges");
  std::vector<d::Box> boxes;
  boxes.reserve(std::size_t(edges.rows() + triangles.rows()));
  for (Eigen::Index e = 0; e < edges.rows(); ++e)
    boxes.push_back(d::box_of(x, {edges(e, 0), edges(e, 1)}, 1, int(e)));
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    boxes.push_back(d::box_of(x, {triangles(t, 0), triangles(t, 1), triangles(t, 2)}, 2, int(t)));
  const int axis = d::sweep_axis(x);
  d::sort_along(boxes, axis);
  int crossings = 0;
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size() && boxes[j].lo(axis) <= boxes[i].hi(axis); ++j) {
      if (boxes[i].kind == boxes[j].kind) continue;
      if ((boxes[i].lo.array() > boxes[j].hi.array()).any() ||
          (boxes[j].lo.array() > boxes[i].hi.array()).any())
        continue;
      const int e = boxes[i].kind == 1 ? boxes[i].index : boxes[j].index;
      const int t = boxes[i].kind == 2 ? boxes[i].index : boxes[j].index;
      const int p = edges(e, 0), q = edges(e, 1);
      const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
      if (p == a || p == b || p == c || q == a || q == b || q == c) continue;
      if (d::segment_meets_triangle(d::point(x, p), d::point(x, q), d::point(x, a), d::point(x, b),
                                    d::point(x, c)))
        ++crossings;
    }
  return crossings;
}

/// @brief count_crossings() with the surface's own edges, triangle_edges(triangles).
inline int count_crossings(const Points<double>& x, const Triangles& triangles) {
  return count_crossings(x, triangles, triangle_edges(triangles));
}

/// @brief The number of triangles of the surface that the closed segment p0p1 (an obstacle, e.g.
/// a capsule's axis) meets, touching included. Exact, like count_crossings().
inline int count_segment_crossings(const Points<double>& x, const Triangles& triangles,
                                   const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
  namespace d = intersections_detail;
  d::check_indices(x, triangles, "triangles");
  const Eigen::Vector3d lo = p0.cwiseMin(p1), hi = p0.cwiseMax(p1);
  int crossings = 0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const d::Box b = d::box_of(x, {triangles(t, 0), triangles(t, 1), triangles(t, 2)}, 2, 0);
    if ((b.lo.array() > hi.array()).any() || (lo.array() > b.hi.array()).any()) continue;
    if (d::segment_meets_triangle(p0, p1, d::point(x, triangles(t, 0)),
                                  d::point(x, triangles(t, 1)), d::point(x, triangles(t, 2))))
      ++crossings;
  }
  return crossings;
}

/// @brief The smallest distance between non-adjacent elements of the surface: a point of the
/// surface (any point of a triangle or an edge) to a triangle it is not a corner of, and an edge
/// to an edge it shares no point with. +infinity when there is no such pair. Double arithmetic
/// (see the file's comment). Meant for surfaces without crossings: where an edge passes through
/// a triangle, no point-triangle or edge-edge distance need be 0 (count_crossings() sees it).
/// @param edges normally triangle_edges(triangles)
/// @throws std::invalid_argument for an index out of range.
inline double min_separation(const Points<double>& x, const Triangles& triangles,
                             const Edges& edges) {
  namespace d = intersections_detail;
  d::check_indices(x, triangles, "triangles");
  d::check_indices(x, edges, "edges");
  std::vector<char> used(std::size_t(x.rows()), 0);
  for (Eigen::Index k = 0; k < triangles.size(); ++k) used[std::size_t(triangles.data()[k])] = 1;
  for (Eigen::Index k = 0; k < edges.size(); ++k) used[std::size_t(edges.data()[k])] = 1;
  std::vector<d::Box> boxes;
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    if (used[std::size_t(i)]) boxes.push_back(d::box_of(x, {int(i)}, 0, int(i)));
  for (Eigen::Index e = 0; e < edges.rows(); ++e)
    boxes.push_back(d::box_of(x, {edges(e, 0), edges(e, 1)}, 1, int(e)));
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    boxes.push_back(d::box_of(x, {triangles(t, 0), triangles(t, 1), triangles(t, 2)}, 2, int(t)));
  const int axis = d::sweep_axis(x);
  d::sort_along(boxes, axis);
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size() && boxes[j].lo(axis) - boxes[i].hi(axis) < best;
         ++j) {
      const d::Box &l = boxes[i], &r = boxes[j];
      const int kinds = (1 << l.kind) | (1 << r.kind);
      const bool point_triangle = kinds == ((1 << 0) | (1 << 2));
      const bool edge_edge = l.kind == 1 && r.kind == 1;
      if (!point_triangle && !edge_edge) continue;
      if (d::box_distance(l, r) >= best) continue;
      double distance;
      if (point_triangle) {
        const int p = l.kind == 0 ? l.index : r.index;
        const int t = l.kind == 2 ? l.index : r.index;
        const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
        if (p == a || p == b || p == c) continue;
        distance = d::point_triangle_distance(d::point(x, p), d::point(x, a), d::point(x, b),
                                              d::point(x, c));
      } else {
        const int p = edges(l.index, 0), q = edges(l.index, 1);
        const int u = edges(r.index, 0), v = edges(r.index, 1);
        if (p == u || p == v || q == u || q == v) continue;
        distance = d::segment_segment_distance(d::point(x, p), d::point(x, q), d::point(x, u),
                                               d::point(x, v));
      }
      best = std::min(best, distance);
    }
  return best;
}

/// @brief min_separation() with the surface's own edges, triangle_edges(triangles).
inline double min_separation(const Points<double>& x, const Triangles& triangles) {
  return min_separation(x, triangles, triangle_edges(triangles));
}

}  // namespace massspring::test
