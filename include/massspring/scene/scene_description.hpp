#pragma once
/// @file
/// @brief SceneDescription: a mesh, its pins, stiffness and mass, as the JSON+OBJ
/// scenes hold them, and the obstacles it falls on. make_system() turns it into a MassSpringSystem.

#include <optional>
#include <vector>

#include "massspring/contact/self_collision.hpp"
#include "massspring/scene/collider_description.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief The content of a JSON+OBJ scene (see docs/scenes.md).
///
/// Springs are derived, not listed: every pair of vertices of each face (so a quad gives its four
/// sides and both diagonals) plus every entry of `edges`; a pair that occurs twice is one spring.
/// Rest lengths are the distances between the vertices.
template <class Scalar>
struct SceneDescription {
  /// @brief #V by 3 vertex positions [m].
  Points<Scalar> vertices = Points<Scalar>(0, 3);
  /// @brief Polygons (3 or more vertex indices each, 0-based). They carry springs, are the system's
  /// surface (each split into a fan of triangles by make_system()) and, when `mass` is absent,
  /// give the lumped Voronoi areas that are the masses (density 1 kg/m^2).
  std::vector<std::vector<int>> faces;
  /// @brief Two-vertex springs (0-based), the OBJ's `f i j` lines.
  Edges edges = Edges(0, 2);
  /// @brief Pinned vertices (0-based; the JSON file holds them 1-based).
  std::vector<int> pinned;
  /// @brief Stiffness of every spring [N/m].
  Scalar stiffness = 0;
  /// @brief Mass of every vertex [kg]; when absent, the lumped Voronoi areas of the faces.
  std::optional<Scalar> mass;
  /// @brief Obstacles (the key "colliders"), in file order: make_system() adds them to the
  /// system in this order.
  std::vector<ColliderDescription<Scalar>> colliders;
  /// @brief Self-collision of the surface (the key "self_collision"); absent: off. Needs faces.
  std::optional<contact::SelfCollision<Scalar>> self_collision;
  /// @brief The acceleration of gravity [m/s^2] (the key "gravity"); make_system() adds it as a
  /// Gravity term. Absent: no term.
  std::optional<Vector3<Scalar>> gravity;
  /// @brief The time step the scene is meant to run at [s], > 0 (the key "dt"). Not part of a
  /// system: a program reads it here (massspring-simulate uses it unless --dt is given).
  std::optional<Scalar> dt;
};

}  // namespace massspring
