#pragma once
// The project's own scenes, written by massspring-make-scenes into examples/scenes and checked
// against the committed files by tests/scene/test_generators.cpp.

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "massspring/massspring.hpp"
#include "massspring/scene/contact_recipes.hpp"
#include "massspring/scene/recipes.hpp"

namespace massspring::examples {

/// @brief A horizontal cloth of columns x rows points over width x width [m] (quads with both
/// diagonals, Voronoi masses, k = 1000 N/m, nothing pinned), centred above the origin at height y.
inline SceneDescription<double> cloth_above(int columns, double width, double y) {
  ClothOptions o;
  o.columns = columns;
  o.rows = columns;
  o.width = width;
  o.height = width;
  o.plane = ClothPlane::Horizontal;
  o.pins = ClothPins::None;
  o.center = Vector3<double>(0, y, 0);
  return make_cloth(o);
}

/// @brief The floor y = 0 with friction mu.
inline ColliderDescription<double> floor_plane(double mu) {
  ColliderDescription<double> floor;
  floor.shape = contact::ColliderShape::Plane;
  floor.point = Vector3<double>::Zero();
  floor.normal = Vector3<double>::UnitY();
  floor.static_friction = floor.kinetic_friction = mu;
  return floor;
}

/// @brief An icosphere of radius r about c: 12 vertices, 20 triangles (outward winding).
inline ColliderDescription<double> icosphere(const Vector3<double>& c, double r) {
  ColliderDescription<double> mesh;
  mesh.shape = contact::ColliderShape::Mesh;
  const double t = (1 + std::sqrt(5.0)) / 2;
  mesh.vertices.resize(12, 3);
  mesh.vertices << -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t, 0, 0, -1, t, 0, 1, t, 0, -1, -t, 0, 1, -t,
      t, 0, -1, t, 0, 1, -t, 0, -1, -t, 0, 1;
  for (int i = 0; i < 12; ++i)
    mesh.vertices.row(i) = c.transpose() + r * mesh.vertices.row(i).normalized();
  mesh.triangles.resize(20, 3);
  mesh.triangles << 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2,
      10, 7, 6, 7, 1, 8, 3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10,
      8, 6, 7, 9, 8, 1;
  return mesh;
}

/// @brief (file stem, scene) of every scene in examples/scenes.
inline std::vector<std::pair<std::string, SceneDescription<double>>> project_scenes() {
  std::vector<std::pair<std::string, SceneDescription<double>>> scenes;

  // A chain, a net and a flag like the JSON+OBJ scenes' and the curtain of Liu et al. 2013 (fast
  // mass-spring): see massspring/scene/recipes.hpp.
  scenes.emplace_back("chain", make_chain(chain_recipe()));
  scenes.emplace_back("net", make_net(net_recipe()));
  scenes.emplace_back("flag", make_cloth(flag_recipe()));
  scenes.emplace_back("curtain", make_cloth(curtain_recipe()));

  // Contact (docs/contact.md). Cloths of 1 kg/m^2, k = 1000 N/m, dropped from rest;
  // small enough to simulate in seconds with the local-global solver at dt = 1/30.
  using Shape = contact::ColliderShape;
  {  // drape: a 1.2 m cloth dropped over a ball onto the floor, friction 0.3 on both
    SceneDescription<double> drape = cloth_above(31, 1.2, 1.0);
    ColliderDescription<double> ball;
    ball.shape = Shape::Sphere;
    ball.center = {0, 0.4, 0};
    ball.radius = 0.3;
    ball.static_friction = ball.kinetic_friction = 0.3;
    drape.colliders = {floor_plane(0.3), ball};
    // its own gravity and step: 1/200 s keeps each step's motion below the points' spacing
    // (docs/contact.md, Limits)
    drape.gravity = Vector3<double>(0, -9.8, 0);
    drape.dt = 0.005;
    scenes.emplace_back("drape", std::move(drape));
  }
  {  // table: the same cloth falling on a 0.8 m x 0.8 m table top 0.7 m high
    SceneDescription<double> table = cloth_above(31, 1.2, 1.0);
    ColliderDescription<double> top;
    top.shape = Shape::Box;
    top.center = {0, 0.35, 0};
    top.half_extents = {0.4, 0.35, 0.4};
    top.static_friction = top.kinetic_friction = 0.5;
    table.colliders = {floor_plane(0.3), top};
    scenes.emplace_back("table", std::move(table));
  }
  {  // tilted: a 0.6 m cloth sliding off a box tilted 20 degrees about z (friction 0.1)
    SceneDescription<double> tilted = cloth_above(21, 0.6, 0.9);
    ColliderDescription<double> ramp;
    ramp.shape = Shape::Box;
    ramp.center = {0, 0.4, 0};
    ramp.half_extents = {0.5, 0.1, 0.4};
    const double half = 10 * 3.14159265358979323846 / 180;
    ramp.rotation = {std::cos(half), 0, 0, std::sin(half)};
    ramp.static_friction = ramp.kinetic_friction = 0.1;
    tilted.colliders = {floor_plane(0.3), ramp};
    scenes.emplace_back("tilted", std::move(tilted));
  }
  {  // pole: a hanging 1.2 m x 0.8 m flag pinned along its top edge, pressed by a horizontal pole
     // that turns about its axis (2 rad/s, friction 0.8) and winds the cloth around it
    ClothOptions o = hanging_cloth_recipe(31);
    o.rows = 21;
    o.width = 1.2;
    o.height = 0.8;
    o.pins = ClothPins::TopEdge;
    SceneDescription<double> pole = make_cloth(o);
    pole.vertices.col(1).array() += 1.5;
    ColliderDescription<double> rod;
    rod.shape = Shape::Capsule;
    rod.a = {-0.1, 1.2, 0.03};
    rod.b = {1.3, 1.2, 0.03};
    rod.radius = 0.04;
    rod.angular_velocity = {2, 0, 0};
    rod.static_friction = rod.kinetic_friction = 0.8;
    pole.colliders = {rod};
    scenes.emplace_back("pole", std::move(pole));
  }
  {  // mesh: a 1 m cloth dropped on an icosphere (a 20-triangle mesh) of radius 0.3 m
    SceneDescription<double> mesh = cloth_above(25, 1.0, 0.9);
    ColliderDescription<double> ball = icosphere({0, 0.3, 0}, 0.3);
    ball.static_friction = ball.kinetic_friction = 0.3;
    ball.thickness = 0.005;
    mesh.colliders = {floor_plane(0.3), ball};
    scenes.emplace_back("mesh", std::move(mesh));
  }
  // The contact scenes of scene/contact_recipes.hpp, self-collision on with its defaults
  // (thickness 4 mm, friction 0.2).
  for (auto [stem, scene] : {std::pair{"clothesline", clothesline_scene()},
                             std::pair{"ribbon_pile", ribbon_pile_scene()},
                             std::pair{"two_cloths", two_cloths_on_ball_scene()}}) {
    scene.self_collision = contact::SelfCollision<double>{};
    scenes.emplace_back(stem, std::move(scene));
  }

  return scenes;
}

}  // namespace massspring::examples
