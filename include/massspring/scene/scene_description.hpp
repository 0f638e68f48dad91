#pragma once
/// @file
/// @brief SceneDescription: a mesh, its pins, stiffness and mass, as the JSON+OBJ
/// scenes hold them, and the obstacles it falls on. make_system() turns it into a MassSpringSystem.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "massspring/contact/self_collision.hpp"
#include "massspring/scene/collider_description.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Where a scene's mesh was read from, so that a message can point into the file: its name
/// and the line of each vertex and of each polygon, as read_obj() gives them (ObjMesh). Empty for
/// a mesh built in code; the file's indices are 1-based (OBJ), the description's 0-based.
struct MeshSource {
  /// @brief The file's name as messages give it; empty: built in code.
  std::string file;
  /// @brief The line (1-based) of each vertex: #V entries, or none.
  std::vector<std::size_t> vertex_lines;
  /// @brief The line (1-based) of each polygon of `faces`: one entry per polygon, or none.
  std::vector<std::size_t> face_lines;
};

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
  /// @brief The OBJ file `vertices` and `faces` were read from (read_json_scene() sets it), for
  /// make_system()'s messages; empty for a scene built in code. Not part of the scene written.
  MeshSource source;
};

}  // namespace massspring
