#pragma once
/// @file
/// @brief The kinds of collider shape and a point's contact with one collider: what a collider's
/// geometry (contact/colliders/collider.hpp, box_shape.hpp, mesh_shape.hpp) reports to the
/// response (contact/colliders/collider_set.hpp).

#include <Eigen/Core>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The kind of a collider's shape.
enum class ColliderShape { Plane, Sphere, Capsule, Box, Mesh };

/// @brief A collider's name in messages and scenes: "plane", "sphere", "capsule", "box", "mesh".
inline const char* to_string(ColliderShape shape) {
  static constexpr const char* names[] = {"plane", "sphere", "capsule", "box", "mesh"};
  const int i = static_cast<int>(shape);
  return i >= 0 && i < 5 ? names[i] : "?";
}

/// @brief A point's contact with one collider, in world coordinates.
template <class Scalar>
struct ColliderContact {
  /// @brief thickness - phi(x) [m]: how far the point must move along `normal` to leave the
  /// contact zone (> 0 inside it, <= 0 when it only touches within the tolerance).
  Scalar depth = 0;
  /// @brief Unit outward normal of the surface at the contact.
  Vector3<Scalar> normal = Vector3<Scalar>::UnitZ();
  /// @brief Velocity of the collider's surface at the point [m/s].
  Vector3<Scalar> velocity = Vector3<Scalar>::Zero();
};

}  // namespace massspring::contact
