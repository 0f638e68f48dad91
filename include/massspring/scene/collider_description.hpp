#pragma once
/// @file
/// @brief ColliderDescription: an obstacle as a scene file gives it (the JSON key "colliders",
/// docs/scenes.md), and make_collider(), which builds the contact::Collider it describes.

#include <Eigen/Core>
#include <string>
#include <utility>

#include "massspring/contact/colliders/box_shape.hpp"
#include "massspring/contact/colliders/collider.hpp"
#include "massspring/contact/colliders/mesh_shape.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief One collider of a scene, in world coordinates, as its file states it. Only the fields
/// of its `shape` are read; the material and motion fields apply to every shape.
template <class Scalar>
struct ColliderDescription {
  using V3 = Vector3<Scalar>;
  /// @brief Plane, sphere, capsule, box or mesh.
  contact::ColliderShape shape = contact::ColliderShape::Plane;
  /// @brief Plane: a point on it [m] and its outward normal (any length > 0; the free side).
  V3 point = V3::Zero(), normal = V3::UnitY();
  /// @brief Sphere and box: the centre [m].
  V3 center = V3::Zero();
  /// @brief Capsule: the end points of its axis [m].
  V3 a = V3::Zero(), b = V3::Zero();
  /// @brief Sphere and capsule: the radius [m] (> 0).
  Scalar radius = 0;
  /// @brief Box: half the edge lengths along its own axes [m] (each > 0), and its orientation as
  /// a quaternion (w, x, y, z) (any length > 0; normalised; default: the identity).
  V3 half_extents = V3::Zero();
  Eigen::Matrix<Scalar, 4, 1> rotation = Eigen::Matrix<Scalar, 4, 1>(1, 0, 0, 0);
  /// @brief Mesh: #V by 3 vertices [m] and #T by 3 triangles (0-based; the OBJ's polygons,
  /// fan-triangulated).
  Points<Scalar> vertices = Points<Scalar>(0, 3);
  contact::Triangles triangles = contact::Triangles(0, 3);
  /// @brief Coulomb friction coefficients (0 <= kinetic <= static; default 0: frictionless).
  Scalar static_friction = 0, kinetic_friction = 0;
  /// @brief Coefficient of restitution in [0, 1] (default 0: inelastic).
  Scalar restitution = 0;
  /// @brief Distance from the surface at which contact starts [m] (>= 0, default 0).
  Scalar thickness = 0;
  /// @brief Constant linear velocity [m/s] of the reference point (the plane's point, the centre
  /// of a sphere or box, a capsule's midpoint, the centre of a mesh's bounding box) and angular
  /// velocity [rad/s] about it (default 0: at rest).
  V3 velocity = V3::Zero(), angular_velocity = V3::Zero();
};

/// @brief The collider a description gives, in the Scalar `S` of the system that will hold it.
/// @throws Error (the message of contact::Collider's factories and setters) for an invalid
/// description: a zero normal, a radius <= 0, a degenerate mesh, friction out of order, ...
template <class S, class Scalar>
contact::Collider<S> make_collider(const ColliderDescription<Scalar>& d) {
  using C = contact::Collider<S>;
  auto v = [](const Vector3<Scalar>& x) -> Vector3<S> { return x.template cast<S>(); };
  C c = [&] {
    switch (d.shape) {
      case contact::ColliderShape::Plane:
        return C::plane(v(d.point), v(d.normal));
      case contact::ColliderShape::Sphere:
        return C::sphere(v(d.center), S(d.radius));
      case contact::ColliderShape::Capsule:
        return C::capsule(v(d.a), v(d.b), S(d.radius));
      case contact::ColliderShape::Box:
        return C::box(v(d.center), v(d.half_extents), d.rotation.template cast<S>());
      case contact::ColliderShape::Mesh:
        return C::mesh(d.vertices.template cast<S>(), d.triangles);
    }
    throw Error("make_collider: unknown collider shape");
  }();
  c.set_friction(S(d.static_friction), S(d.kinetic_friction));
  c.set_restitution(S(d.restitution));
  c.set_thickness(S(d.thickness));
  c.set_velocity(v(d.velocity));
  c.set_angular_velocity(v(d.angular_velocity));
  return c;
}

}  // namespace massspring
