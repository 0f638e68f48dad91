#pragma once
/// @file
/// @brief triangle_edges(): the edges of a triangle set, each side once.

#include <Eigen/Core>
#include <algorithm>
#include <utility>
#include <vector>

namespace massspring::detail {

/// @brief Fills `edges` with the sides of the triangles (#triangles by 3 indices), each once, as
/// (i, j) with i < j, ascending. O(m log m) for m triangles; reuses the vector's capacity, so it
/// allocates nothing once the vector has grown.
template <class Derived>
void triangle_edges(const Eigen::MatrixBase<Derived>& triangles,
                    std::vector<std::pair<int, int>>& edges) {
  edges.clear();
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int i = int(triangles(t, k)), j = int(triangles(t, (k + 1) % 3));
      edges.emplace_back(std::min(i, j), std::max(i, j));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
}

}  // namespace massspring::detail
