#pragma once
/// @file
/// @brief Strain of springs and faces: how far each spring is from its rest length, for colour
/// maps and exports.
///
/// A spring e = (i, j) of rest length r_e > 0 has strain s_e = | |x_i - x_j| / r_e - 1 |
/// (dimensionless; 0 at rest, 0.1 when 10% longer or shorter). A spring of rest length 0 has
/// strain 0 (there is no length to compare with). A face's strain is the mean of the strains of
/// the springs along its boundary (each pair of consecutive vertices, the last with the first,
/// joined by a spring), or 0 when no spring runs along it.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "massspring/types.hpp"

namespace massspring {

/// @brief s_e = | |x_i - x_j| / r_e - 1 | for every spring (0 where r_e = 0).
/// @param positions     #points by 3 [m]
/// @param springs       #springs by 2 point indices
/// @param rest_lengths  #springs rest lengths [m]
template <class DerivedX, class DerivedR>
Eigen::VectorXd spring_strain(const Eigen::MatrixBase<DerivedX>& positions, const Edges& springs,
                              const Eigen::MatrixBase<DerivedR>& rest_lengths) {
  Eigen::VectorXd s(springs.rows());
  for (Eigen::Index e = 0; e < springs.rows(); ++e) {
    const double r = double(rest_lengths(e));
    const double l = (positions.row(springs(e, 0)) - positions.row(springs(e, 1)))
                         .template cast<double>()
                         .norm();
    s(e) = r > 0 ? std::abs(l / r - 1) : 0.0;
  }
  return s;
}

/// @brief For each face, the springs along its boundary (see the file comment), found once.
/// @param faces    polygons as point indices (3 or more each)
/// @param springs  #springs by 2 point indices
inline std::vector<std::vector<int>> face_boundary_springs(
    const std::vector<std::vector<int>>& faces, const Edges& springs) {
  auto key = [](int a, int b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
  };
  std::unordered_map<std::uint64_t, int> spring_of;
  spring_of.reserve(std::size_t(springs.rows()));
  for (Eigen::Index e = 0; e < springs.rows(); ++e)
    spring_of.emplace(key(springs(e, 0), springs(e, 1)), int(e));
  std::vector<std::vector<int>> out(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::vector<int>& face = faces[f];
    for (std::size_t k = 0; k < face.size(); ++k) {
      const auto it = spring_of.find(key(face[k], face[(k + 1) % face.size()]));
      if (it != spring_of.end()) out[f].push_back(it->second);
    }
  }
  return out;
}

/// @brief Each face's strain: the mean strain of its boundary springs (0 when it has none).
/// @param boundary       face_boundary_springs() of the faces
/// @param spring_strain  spring_strain() of the springs
inline Eigen::VectorXd face_strain(const std::vector<std::vector<int>>& boundary,
                                   const Eigen::VectorXd& spring_strain) {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(Eigen::Index(boundary.size()));
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    if (boundary[f].empty()) continue;
    double sum = 0;
    for (int e : boundary[f]) sum += spring_strain(e);
    s(Eigen::Index(f)) = sum / double(boundary[f].size());
  }
  return s;
}

}  // namespace massspring
