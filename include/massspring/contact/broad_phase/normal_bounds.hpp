#pragma once
/// @file
/// @brief NormalBounds: where the normals of a patch of triangles point over a time step, as
/// ranges along seven fixed directions, and the axis they give to the self-collision tree's skip
/// test (contact/broad_phase/normal_cone_tree.hpp).
///
/// With the corners moving linearly over the step, x(t) = (1 - t) x0 + t x1, a triangle's normal
/// n(t) = (b - a) x (c - a) is quadratic in t: n(t) = (1-t)^2 B0 + 2 t (1-t) B1 + t^2 B2 with
/// B0 = n(0), B2 = n(1), B1 = ((b0 - a0) x (c1 - a1) + (b1 - a1) x (c0 - a0)) / 2, so n(t) is a
/// combination of B0, B1, B2 with non-negative weights, and an axis a with a . Bk > 0 for all
/// three has a . n(t) > 0 throughout.
///
/// The bounds keep, for the seven directions e = (1,0,0), (0,1,0), (0,0,1), (1,1,1), (1,1,-1),
/// (1,-1,1), (-1,1,1), the least and greatest e . Bk over the patch's triangles (the bounds of a
/// discrete orientation polytope, Klosowski et al. 1998, "Efficient collision detection using
/// bounding volume hierarchies of k-DOPs", here of the normals rather than of the points). The
/// union of two patches takes the least and greatest of their bounds: exact, with no rounding.
/// When some e has e . Bk > 0 (or < 0) for all of a patch's Bk, a = e / |e| (or -e / |e|) is an
/// axis, and axis() takes the one whose least a . Bk is the largest. Every direction lies within
/// 36.2 degrees of one of the fourteen axes +-e, so a patch whose Bk all lie within 53 degrees of
/// a common direction always has an axis. Each e . Bk of a triangle is lowered (raised) by
/// 1e-6 |e|_1 max_k |Bk|_1 before it counts, a cosine margin of at least 1e-6 that keeps
/// rounding on the safe side.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The ranges of a patch's Bernstein normals along seven directions (see the file
/// comment).
template <class Scalar>
struct NormalBounds {
  using V3 = Vector3<Scalar>;
  std::array<Scalar, 7> low, high;  // least and greatest e . Bk, direction by direction

  /// @brief The bounds of the triangle (a, b, c) moving from (a0, b0, c0) to (a1, b1, c1). A
  /// normal that is not finite leaves them unbounded, so that no axis holds.
  static NormalBounds of_triangle(const V3& a0, const V3& b0, const V3& c0, const V3& a1,
                                  const V3& b1, const V3& c1) {
    const V3 e0 = b0 - a0, f0 = c0 - a0, e1 = b1 - a1, f1 = c1 - a1;
    const V3 n0 = e0.cross(f0), n1 = (e0.cross(f1) + e1.cross(f0)) / 2, n2 = e1.cross(f1);
    NormalBounds b;
    Eigen::Map<Bounds> low(b.low.data()), high(b.high.data());
    constexpr Scalar inf = std::numeric_limits<Scalar>::infinity();
    const Scalar l0 = n0.template lpNorm<1>(), l1 = n1.template lpNorm<1>(),
                 l2 = n2.template lpNorm<1>();
    if (!(l0 < inf && l1 < inf && l2 < inf)) {
      low.setConstant(-inf);
      high.setConstant(inf);
      return b;
    }
    const auto along = [](const V3& v) {  // e . v for the seven directions
      const Scalar x = v(0), y = v(1), z = v(2);
      return (Bounds() << x, y, z, x + y + z, x + y - z, x - y + z, y + z - x).finished();
    };
    const Bounds p0 = along(n0), p1 = along(n1), p2 = along(n2);
    // 1e-6 |e|_1 |Bk|_1, with the largest |Bk|_1 of the three.
    const Scalar m = Scalar(1e-6) * std::max({l0, l1, l2});
    const Bounds margin = (Bounds() << m, m, m, 3 * m, 3 * m, 3 * m, 3 * m).finished();
    low = p0.min(p1).min(p2) - margin;
    high = p0.max(p1).max(p2) + margin;
    return b;
  }

  /// @brief The bounds of the union of two patches.
  static NormalBounds merged(const NormalBounds& l, const NormalBounds& r) {
    NormalBounds b;
    for (std::size_t j = 0; j < 7; ++j) {
      b.low[j] = std::min(l.low[j], r.low[j]);
      b.high[j] = std::max(l.high[j], r.high[j]);
    }
    return b;
  }

  /// @brief The unit axis of the patch (see the file comment); false when no direction bounds
  /// its normals.
  bool axis(V3& a) const {
    const Eigen::Map<const Bounds> l(low.data()), h(high.data());
    if (!((l > 0).any() || (h < 0).any())) return false;
    const Scalar root3 = std::sqrt(Scalar(3)), inverse[2] = {1, 1 / root3};  // 1 / |e|
    Scalar best = 0;
    int which = -1;
    for (std::size_t j = 0; j < 7; ++j) {
      const Scalar s = inverse[j < 3 ? 0 : 1];
      if (low[j] * s > best) {
        best = low[j] * s;
        which = int(2 * j);
      }
      if (-high[j] * s > best) {
        best = -high[j] * s;
        which = int(2 * j + 1);
      }
    }
    static constexpr Scalar e[7][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1}, {1, 1, 1},
                                       {1, 1, -1}, {1, -1, 1}, {-1, 1, 1}};
    const std::size_t j = std::size_t(which / 2);
    const Scalar sign = (which & 1) ? Scalar(-1) : Scalar(1);
    a = sign * V3(e[j][0], e[j][1], e[j][2]) / (j < 3 ? Scalar(1) : root3);
    return true;
  }

 private:
  using Bounds = Eigen::Array<Scalar, 7, 1>;
};

}  // namespace massspring::contact
