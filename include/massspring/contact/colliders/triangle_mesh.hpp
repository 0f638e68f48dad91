#pragma once
/// @file
/// @brief TriangleMesh: a static triangle mesh with a bounding-volume hierarchy
/// (contact/broad_phase/box_tree.hpp, at most four triangles a leaf), and the two queries a mesh
/// collider makes: the closest point within a distance, and the first crossing of a segment.
/// Both enter only the boxes that can hold an answer: O(log m) per query on a well-shaped mesh of
/// m triangles; they allocate nothing. Their answers do not depend on the tree: among triangles
/// at the same distance, or crossed at the same parameter, the one of lowest index is returned.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "massspring/contact/aligned_box.hpp"
#include "massspring/contact/broad_phase/box_tree.hpp"
#include "massspring/contact/distance/point_triangle.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief #triangles by 3 vertex indices (0-based), row by row.
using Triangles = massspring::Triangles;

/// @brief A static triangle mesh and its bounding-volume hierarchy, in its own (local) frame.
template <class Scalar>
class TriangleMesh {
 public:
  using V3 = Vector3<Scalar>;

  /// @brief Builds the hierarchy. Throws Error (naming the triangle) for no triangles, an index
  /// out of range, a vertex that is not finite, or a triangle of zero area.
  TriangleMesh(Points<Scalar> vertices, Triangles triangles)
      : v_(std::move(vertices)), f_(std::move(triangles)) {
    using massspring::detail::message;
    const int n = int(v_.rows()), m = int(f_.rows());
    if (m == 0) throw Error("mesh collider: no triangles");
    if (!v_.allFinite()) throw Error("mesh collider: a vertex is not finite");
    normals_.resize(m, 3);
    for (int t = 0; t < m; ++t) {
      for (int c = 0; c < 3; ++c)
        if (f_(t, c) < 0 || f_(t, c) >= n)
          throw Error(message("mesh collider: triangle ", t, " has vertex index ", f_(t, c),
                              ", out of range [0, ", n, ")"));
      const V3 nrm = (vertex(t, 1) - vertex(t, 0)).cross(vertex(t, 2) - vertex(t, 0));
      const Scalar len = nrm.norm();
      // Zero area relative to the triangle's size: (twice the area) <= eps * (longest edge)^2.
      const Scalar edge2 = std::max({(vertex(t, 1) - vertex(t, 0)).squaredNorm(),
                                     (vertex(t, 2) - vertex(t, 1)).squaredNorm(),
                                     (vertex(t, 0) - vertex(t, 2)).squaredNorm()});
      if (!(len > std::numeric_limits<Scalar>::epsilon() * edge2))
        throw Error(message("mesh collider: triangle ", t, " (vertices ", f_(t, 0), ", ", f_(t, 1),
                            ", ", f_(t, 2), ") has zero area"));
      normals_.row(t) = (nrm / len).transpose();
    }
    std::vector<V3> centres(static_cast<std::size_t>(m));
    for (int t = 0; t < m; ++t) centres[std::size_t(t)] = box(t).centre();
    tree_.build(centres, kLeaf);
    tree_.refit([this](int t) { return box(t); });
    lo_ = v_.colwise().minCoeff().transpose();
    hi_ = v_.colwise().maxCoeff().transpose();
  }

  [[nodiscard]] int num_triangles() const { return int(f_.rows()); }
  [[nodiscard]] const Points<Scalar>& vertices() const { return v_; }
  [[nodiscard]] const Triangles& triangles() const { return f_; }
  /// @brief Unit normal of triangle t, (b - a) x (c - a) normalised (the OBJ's winding).
  [[nodiscard]] V3 normal(int t) const { return normals_.row(t).transpose(); }
  /// @brief Vertex k (0, 1, 2) of triangle t.
  [[nodiscard]] V3 vertex(int t, int k) const { return v_.row(f_(t, k)).transpose(); }
  /// @brief The corners of the vertices' bounding box.
  [[nodiscard]] const V3& lower() const { return lo_; }
  [[nodiscard]] const V3& upper() const { return hi_; }

  /// @brief The closest point of the mesh to p among those at distance < r; false when there is
  /// none. `closest` and `triangle` are set only when true; of several triangles at the least
  /// distance, `triangle` is the one of lowest index.
  bool closest_within(const V3& p, Scalar r, V3& closest, int& triangle) const {
    Scalar best = r * r;
    bool found = false;
    // A box at the best distance may still hold a tie of lower index, once one is found.
    const auto enter = [&](std::size_t k) {
      const Scalar d2 = tree_.node(k).box.squared_distance(p);
      return d2 < best || (found && d2 == best);
    };
    tree_.descend(enter, [&](int t) {
      const V3 q = closest_point_on_triangle(p, vertex(t, 0), vertex(t, 1), vertex(t, 2));
      const Scalar d2 = (q - p).squaredNorm();
      if (d2 < best || (found && d2 == best && t < triangle)) {
        best = d2;
        closest = q;
        triangle = t;
        found = true;
      }
    });
    return found;
  }

  /// @brief The first crossing (smallest t in [0, 1]) of the segment p0 -> p1 with a triangle;
  /// false when there is none. Of several triangles crossed at t, `triangle` is the one of lowest
  /// index.
  bool first_crossing(const V3& p0, const V3& p1, Scalar& t_hit, int& triangle) const {
    const AlignedBox3<Scalar> path{p0.cwiseMin(p1), p0.cwiseMax(p1)};
    Scalar best = std::numeric_limits<Scalar>::infinity();
    tree_.descend(
        [&](std::size_t k) { return tree_.node(k).box.overlaps(path); },
        [&](int t) {
          Scalar u = 0;
          if (segment_crosses_triangle(p0, p1, vertex(t, 0), vertex(t, 1), vertex(t, 2), u) &&
              (u < best || (u == best && t < triangle))) {
            best = u;
            triangle = t;
          }
        });
    if (!(best <= 1)) return false;
    t_hit = best;
    return true;
  }

 private:
  static constexpr int kLeaf = 4;  // triangles per leaf at most

  // The box of triangle t's corners.
  AlignedBox3<Scalar> box(int t) const {
    auto b = AlignedBox3<Scalar>::empty();
    for (int k = 0; k < 3; ++k) b.extend(vertex(t, k));
    return b;
  }

  Points<Scalar> v_;
  Triangles f_;
  Points<Scalar> normals_;
  BoxTree<Scalar> tree_;
  V3 lo_ = V3::Zero(), hi_ = V3::Zero();
};

}  // namespace massspring::contact
