#pragma once
/// @file
/// @brief Scenes for self-collision and edge contact: cloths that fall onto obstacles and onto
/// themselves, as whole SceneDescriptions (cloth, masses and colliders).
///
/// Common to all: y is up and the floor, where a scene has one, is the plane y = 0 (normal +y);
/// cloths are make_cloth()
/// grids with one diagonal per cell (so every face is a triangle, the surface self-collision acts
/// on) and skip-one bending springs, k = 1000 N/m, nothing pinned, at rest; Coulomb friction 0.3
/// on every collider. Masses are the lumped Voronoi areas at 1 kg/m^2 unless a scene says
/// otherwise. Every point starts at least 5 cm from every obstacle, and no two parts of a cloth
/// touch. Self-collision is not part of the description: a program turns it on for the system it
/// builds (MassSpringSystem::set_surface() with the faces, then set_self_collision()).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "massspring/contact/colliders/collider.hpp"
#include "massspring/scene/cloth.hpp"
#include "massspring/scene/collider_description.hpp"
#include "massspring/scene/recipes.hpp"
#include "massspring/scene/scene_description.hpp"

namespace massspring {

namespace detail {

/// @brief The options of the contact scenes' cloths (see the file): the drape's cloth
/// (drape_recipe()) at columns x rows points over width x depth [m], horizontal, at the origin.
inline ClothOptions contact_cloth_options(int columns, int rows, double width, double depth) {
  ClothOptions o = drape_recipe();
  o.columns = columns;
  o.rows = rows;
  o.width = width;
  o.height = depth;
  return o;
}

/// @brief The cloth of the contact scenes (see the file): columns x rows points over
/// width x depth [m], horizontal, centred above the origin at height y.
inline SceneDescription<double> contact_cloth(int columns, int rows, double width, double depth,
                                              double y) {
  SceneDescription<double> cloth = make_cloth(contact_cloth_options(columns, rows, width, depth));
  cloth.vertices.col(0).array() -= width / 2;
  cloth.vertices.col(1).array() += y;
  cloth.vertices.col(2).array() -= depth / 2;
  return cloth;
}

/// @brief `second` appended to `first` as one vertex and face set: its vertices, faces, edges
/// and pins renumbered after first's. Stiffness, mass and colliders are first's.
inline SceneDescription<double> disjoint_union(SceneDescription<double> first,
                                               const SceneDescription<double>& second) {
  const int offset = int(first.vertices.rows());
  Points<double> vertices(first.vertices.rows() + second.vertices.rows(), 3);
  vertices << first.vertices, second.vertices;
  first.vertices = std::move(vertices);
  for (std::vector<int> face : second.faces) {
    for (int& v : face) v += offset;
    first.faces.push_back(std::move(face));
  }
  Edges edges(first.edges.rows() + second.edges.rows(), 2);
  edges << first.edges, (second.edges.array() + offset).matrix();
  first.edges = std::move(edges);
  for (const int p : second.pinned) first.pinned.push_back(p + offset);
  return first;
}

/// @brief The floor y = 0 of the contact scenes.
inline ColliderDescription<double> contact_floor() {
  ColliderDescription<double> floor;
  floor.shape = contact::ColliderShape::Plane;
  floor.point = Vector3<double>::Zero();
  floor.normal = Vector3<double>::UnitY();
  floor.static_friction = floor.kinetic_friction = 0.3;
  return floor;
}

/// @brief A sphere of the contact scenes.
inline ColliderDescription<double> contact_sphere(const Vector3<double>& center, double radius) {
  ColliderDescription<double> ball;
  ball.shape = contact::ColliderShape::Sphere;
  ball.center = center;
  ball.radius = radius;
  ball.static_friction = ball.kinetic_friction = 0.3;
  return ball;
}

}  // namespace detail

/// @brief A cloth dropped across a thin rod, like washing on a line: 31 x 31 points with 4 cm
/// spacing (1.2 m x 1.2 m), horizontal at y = 1.1, centred above the rod: a capsule of radius
/// 1 cm whose axis runs along x from (-0.8, 1, 0) to (0.8, 1, 0), 10 cm below the cloth (the row
/// z = 0 lies right above the axis). Colliders: the floor, then the rod. The cloth folds over
/// the rod, its two halves hanging to y = 0.4, clear of the floor; the rod's axis must never
/// cross it.
inline SceneDescription<double> clothesline_scene() {
  SceneDescription<double> scene = detail::contact_cloth(31, 31, 1.2, 1.2, 1.1);
  ColliderDescription<double> rod;
  rod.shape = contact::ColliderShape::Capsule;
  rod.a = {-0.8, 1.0, 0.0};
  rod.b = {0.8, 1.0, 0.0};
  rod.radius = 0.01;
  rod.static_friction = rod.kinetic_friction = 0.3;
  scene.colliders = {detail::contact_floor(), rod};
  return scene;
}

/// @brief A ribbon that falls end-first and piles onto itself: 9 x 61 points over
/// 0.24 m x 1.8 m (3 cm spacing), upright, its lower end 5 cm above the floor, centred on x = 0.
/// Row 0 is the top; point (r, c) is at (0.03 c - 0.12, 0.05 + s cos(a), s sin(a)) with
/// s = 0.03 (60 - r) its height along the ribbon and a = 0.05 rad: tilted by about 3 degrees
/// towards +z so that it buckles out of its plane instead of crumpling within it (an exactly
/// upright ribbon stays in the plane z = 0). Collider: the floor.
inline SceneDescription<double> ribbon_pile_scene() {
  ClothOptions o = detail::contact_cloth_options(9, 61, 0.24, 1.8);
  o.plane = ClothPlane::Vertical;
  SceneDescription<double> scene = make_cloth(o);
  const double tilt = 0.05;
  for (Eigen::Index i = 0; i < scene.vertices.rows(); ++i) {
    const double s = scene.vertices(i, 1) + 1.8;  // 0 at the lower end
    scene.vertices(i, 0) -= 0.12;
    scene.vertices(i, 1) = 0.05 + s * std::cos(tilt);
    scene.vertices(i, 2) = s * std::sin(tilt);
  }
  scene.colliders = {detail::contact_floor()};
  return scene;
}

/// @brief Two cloths falling onto a ball and onto each other: two 21 x 21 cloths of 1 m x 1 m
/// (5 cm spacing), horizontal and centred on the y axis, at y = 0.8 (points 0 ... 440) and
/// y = 0.9 (points 441 ... 881), as one vertex and face set; a sphere of radius 0.3 centred at
/// (0, 0.3, 0), resting on the floor, its top 20 cm below the lower cloth. Colliders: the floor,
/// then the sphere. 2 kg in all.
inline SceneDescription<double> two_cloths_on_ball_scene() {
  SceneDescription<double> scene = detail::disjoint_union(
      detail::contact_cloth(21, 21, 1.0, 1.0, 0.8), detail::contact_cloth(21, 21, 1.0, 1.0, 0.9));
  scene.colliders = {detail::contact_floor(), detail::contact_sphere({0.0, 0.3, 0.0}, 0.3)};
  return scene;
}

/// @brief A large cloth draped over a ball onto the floor: 81 x 81 points over 2 m x 2 m
/// (2.5 cm spacing), horizontal at y = 1.1 and centred on the y axis, 1.9 kg in all as the same
/// mass 1.9 / 6561 kg on every point; a sphere of radius 0.5 centred at (0, 0.5, 0), resting on
/// the floor, its top 10 cm below the cloth. Colliders: the floor, then the sphere. The cloth
/// reaches the floor around the ball and folds there. (Unlike drape_recipe() and
/// examples/scenes/drape.json, which are smaller cloths of 1 kg/m^2 over smaller balls.)
inline SceneDescription<double> large_drape_scene() {
  SceneDescription<double> scene = detail::contact_cloth(81, 81, 2.0, 2.0, 1.1);
  scene.mass = 1.9 / (81 * 81);
  scene.colliders = {detail::contact_floor(), detail::contact_sphere({0.0, 0.5, 0.0}, 0.5)};
  return scene;
}

/// @brief A cloth twisted by its two ends: 21 x 21 points over 1 m x 1 m (5 cm spacing),
/// horizontal at y = 1, centred on the y axis; its two ends, the columns x = -0.5 (points
/// 21 r) and x = +0.5 (points 21 r + 20), pinned. twisting_cloth_target() moves them. No
/// colliders: only the cloth's contact with itself keeps it from passing through itself.
inline SceneDescription<double> twisting_cloth_scene() {
  SceneDescription<double> scene = detail::contact_cloth(21, 21, 1.0, 1.0, 1.0);
  for (int r = 0; r < 21; ++r) {
    scene.pinned.push_back(21 * r);
    scene.pinned.push_back(21 * r + 20);
  }
  std::sort(scene.pinned.begin(), scene.pinned.end());
  return scene;
}

/// @brief Where the twisting cloth's pinned point that starts at `start` is at time t [s] >= 0:
/// its end turned about the cloth's middle line (the x axis through y = 1, z = 0) by +pi t for
/// the end at x < 0 and -pi t for the end at x > 0 (half a turn per second each, in opposite
/// directions), and moved along x towards the middle so that the ends' distance shrinks from
/// 1 m by 30% over 4 s (0.075 m/s; no closer after 4 s).
inline Vector3<double> twisting_cloth_target(const Vector3<double>& start, double t) {
  const double pi = 3.14159265358979323846;
  const double side = start.x() < 0 ? -1.0 : 1.0;
  const double angle = -side * pi * t;
  const double y = start.y() - 1.0, z = start.z();
  const double c = std::cos(angle), s = std::sin(angle);
  const double half = 0.5 * (1.0 - 0.3 * std::min(t, 4.0) / 4.0);
  return {side * half, 1.0 + c * y - s * z, s * y + c * z};
}

}  // namespace massspring
