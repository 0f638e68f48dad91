#pragma once
/// @file
/// @brief TriangleMesh: a static triangle mesh with a bounding-volume hierarchy (axis-aligned
/// boxes, split at the median centroid of the longest axis), and the two queries a mesh collider
/// makes: the closest point within a distance, and the first crossing of a segment. Both visit
/// only the boxes that can hold an answer: O(log m) per query on a well-shaped mesh of m
/// triangles, and they allocate nothing (a fixed stack of 128 entries; the tree's depth is at most
/// log2(m) + 1).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

#include "massspring/contact/aligned_box.hpp"
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
    std::vector<int> order(std::size_t(m), 0);
    std::iota(order.begin(), order.end(), 0);
    nodes_.reserve(std::size_t(2 * m));
    nodes_.emplace_back();
    build(order, 0, m, 0);
    triangle_of_slot_ = std::move(order);
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
  /// none. `closest` and `triangle` are set only when true.
  bool closest_within(const V3& p, Scalar r, V3& closest, int& triangle) const {
    Scalar best = r * r;
    bool found = false;
    int stack[kStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[std::size_t(stack[--top])];
      if (node.box.squared_distance(p) >= best) continue;
      if (node.count > 0) {
        for (int s = node.first; s < node.first + node.count; ++s) {
          const int t = triangle_of_slot_[std::size_t(s)];
          const V3 q = closest_point_on_triangle(p, vertex(t, 0), vertex(t, 1), vertex(t, 2));
          const Scalar d2 = (q - p).squaredNorm();
          if (d2 < best) {
            best = d2;
            closest = q;
            triangle = t;
            found = true;
          }
        }
      } else if (top + 2 <= kStack) {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
    return found;
  }

  /// @brief The first crossing (smallest t in [0, 1]) of the segment p0 -> p1 with a triangle;
  /// false when there is none.
  bool first_crossing(const V3& p0, const V3& p1, Scalar& t_hit, int& triangle) const {
    const AlignedBox3<Scalar> path{p0.cwiseMin(p1), p0.cwiseMax(p1)};
    Scalar best = std::numeric_limits<Scalar>::infinity();
    int stack[kStack];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[std::size_t(stack[--top])];
      if (!node.box.overlaps(path)) continue;
      if (node.count > 0) {
        for (int s = node.first; s < node.first + node.count; ++s) {
          const int t = triangle_of_slot_[std::size_t(s)];
          Scalar u = 0;
          if (segment_crosses_triangle(p0, p1, vertex(t, 0), vertex(t, 1), vertex(t, 2), u) &&
              u < best) {
            best = u;
            triangle = t;
          }
        }
      } else if (top + 2 <= kStack) {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
    if (!(best <= 1)) return false;
    t_hit = best;
    return true;
  }

 private:
  static constexpr int kStack = 128;
  static constexpr int kLeaf = 4;  // triangles per leaf at most

  struct Node {
    AlignedBox3<Scalar> box;
    int first = 0;  // leaf: first slot; inner: index of the left child (right = first + 1)
    int count = 0;  // leaf: number of triangles; inner: 0
  };

  // Fills node `index` with the subtree over order[begin, end); an inner node's two children are
  // appended next to each other (left = first, right = first + 1).
  void build(std::vector<int>& order, int begin, int end, int index) {
    auto box = AlignedBox3<Scalar>::empty();
    auto centroids = AlignedBox3<Scalar>::empty();
    for (int s = begin; s < end; ++s) {
      const int t = order[std::size_t(s)];
      for (int k = 0; k < 3; ++k) box.extend(vertex(t, k));
      centroids.extend(centroid(t));
    }
    nodes_[std::size_t(index)].box = box;
    if (end - begin <= kLeaf) {
      nodes_[std::size_t(index)].first = begin;
      nodes_[std::size_t(index)].count = end - begin;
      return;
    }
    int axis = 0;
    (centroids.hi - centroids.lo).maxCoeff(&axis);
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](int a, int b) { return centroid(a)(axis) < centroid(b)(axis); });
    const int left = int(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    nodes_[std::size_t(index)].first = left;
    nodes_[std::size_t(index)].count = 0;
    build(order, begin, mid, left);
    build(order, mid, end, left + 1);
  }

  V3 centroid(int t) const { return (vertex(t, 0) + vertex(t, 1) + vertex(t, 2)) / Scalar(3); }

  Points<Scalar> v_;
  Triangles f_;
  Points<Scalar> normals_;
  std::vector<Node> nodes_;
  std::vector<int> triangle_of_slot_;
  V3 lo_ = V3::Zero(), hi_ = V3::Zero();
};

}  // namespace massspring::contact
