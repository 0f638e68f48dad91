#pragma once
/// @file
/// @brief face_springs(): the springs of a mesh, every vertex pair of each face plus extra edges.

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Springs of a mesh: every pair of vertices of each face (a triangle gives 3, a quad its 4
/// sides and 2 diagonals) and every extra edge, each pair once, as (min, max), sorted.
/// @param[in] num_vertices #V, for range checks
/// @param[in] faces        polygons, 0-based vertex indices
/// @param[in] edges        #E by 2 extra springs, 0-based
/// @throws Error naming the face or edge with an index out of range or a repeated vertex.
inline Edges face_springs(int num_vertices, const std::vector<std::vector<int>>& faces,
                          const Edges& edges) {
  std::vector<std::array<int, 2>> pairs;
  auto check = [&](const char* what, std::size_t item, int v) {
    if (v < 0 || v >= num_vertices)
      throw Error(detail::message(what, ' ', item, ": vertex index ", v, " out of range [0, ",
                                  num_vertices, ")"));
  };
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto& face = faces[f];
    for (int v : face) check("face", f, v);
    for (std::size_t a = 0; a < face.size(); ++a)
      for (std::size_t b = a + 1; b < face.size(); ++b) {
        if (face[a] == face[b])
          throw Error(detail::message("face ", f, ": vertex ", face[a], " appears twice"));
        pairs.push_back({std::min(face[a], face[b]), std::max(face[a], face[b])});
      }
  }
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    check("edge", std::size_t(e), edges(e, 0));
    check("edge", std::size_t(e), edges(e, 1));
    if (edges(e, 0) == edges(e, 1))
      throw Error(detail::message("edge ", e, " joins vertex ", edges(e, 0), " to itself"));
    pairs.push_back({std::min(edges(e, 0), edges(e, 1)), std::max(edges(e, 0), edges(e, 1))});
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  Edges result(Eigen::Index(pairs.size()), 2);
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    result(Eigen::Index(e), 0) = pairs[e][0];
    result(Eigen::Index(e), 1) = pairs[e][1];
  }
  return result;
}

}  // namespace massspring
