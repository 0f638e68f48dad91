#pragma once
/// @file
/// @brief The shapes every part of the library exchanges.

#include <Eigen/Core>

namespace massspring {

/// @brief #points by 3 list of positions or velocities; row i is point i (x, y, z), stored row by
/// row so that one point's coordinates are contiguous.
template <class Scalar>
using Points = Eigen::Matrix<Scalar, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// @brief #springs by 2 list of point indices (0-based); row e is spring e = (i, j).
using Edges = Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>;

/// @brief #triangles by 3 list of point indices (0-based); row t is triangle t = (a, b, c).
using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// @brief Column vector of per-point or per-spring values.
template <class Scalar>
using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

/// @brief A 3-vector (a position, a force, an acceleration).
template <class Scalar>
using Vector3 = Eigen::Matrix<Scalar, 3, 1>;

}  // namespace massspring
