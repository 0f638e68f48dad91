#pragma once
/// @file
/// @brief The small rotation helpers a collider's motion needs: the matrix of a unit quaternion,
/// the exponential of an angular displacement (Rodrigues' formula), and a unit vector
/// perpendicular to a given one.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The rotation matrix of a unit quaternion q = (w, x, y, z).
template <class Scalar>
Eigen::Matrix<Scalar, 3, 3> quaternion_matrix(const Eigen::Matrix<Scalar, 4, 1>& q) {
  const Scalar w = q(0), x = q(1), y = q(2), z = q(3);
  Eigen::Matrix<Scalar, 3, 3> r;
  r << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
      2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
      2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
  return r;
}

/// @brief exp([theta]x), the rotation by |theta| [rad] about theta / |theta|, by Rodrigues'
/// formula I + sin|t| K + (1 - cos|t|) K^2, K the unit axis's cross-product matrix.
template <class Scalar>
Eigen::Matrix<Scalar, 3, 3> rotation_exp(const Vector3<Scalar>& theta) {
  using M3 = Eigen::Matrix<Scalar, 3, 3>;
  const Scalar angle = theta.norm();
  if (!(angle > 0)) return M3::Identity();
  const Vector3<Scalar> k = theta / angle;
  M3 kx;
  kx << 0, -k(2), k(1), k(2), 0, -k(0), -k(1), k(0), 0;
  return M3::Identity() + std::sin(angle) * kx + (1 - std::cos(angle)) * (kx * kx);
}

/// @brief A unit vector perpendicular to a (+z when a is zero).
template <class Scalar>
Vector3<Scalar> perpendicular(const Vector3<Scalar>& a) {
  using V3 = Vector3<Scalar>;
  const V3 other = std::abs(a(0)) < std::abs(a(2)) ? V3::UnitX() : V3::UnitZ();
  const V3 p = a.cross(other);
  return p.norm() > 0 ? V3(p / p.norm()) : V3::UnitZ();
}

}  // namespace massspring::contact
