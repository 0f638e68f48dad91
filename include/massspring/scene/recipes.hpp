#pragma once
/// @file
/// @brief Named cloth recipes that the project's scenes, benchmarks and examples share, each as the
/// ClothOptions that make_cloth() turns into a scene (one place for each).

#include "massspring/scene/cloth.hpp"

namespace massspring {

/// @brief The curtain of Liu et al. 2013 ("Fast Simulation of Mass-Spring Systems", section 6):
/// 81 x 81 points over 1 m x 1 m, vertical, one diagonal per cell, skip-one bending springs,
/// hanging from its two top corners, k = 1000 N/m, lumped Voronoi masses (1 kg in all): 6561
/// points, 32158 springs.
inline ClothOptions curtain_recipe() {
  ClothOptions curtain;
  curtain.columns = 81;
  curtain.rows = 81;
  curtain.width = 1.0;
  curtain.height = 1.0;
  curtain.shear = ClothShear::One;
  curtain.bending = true;
  curtain.plane = ClothPlane::Vertical;
  curtain.pins = ClothPins::TopCorners;
  curtain.stiffness = 1000;
  curtain.mass.reset();
  return curtain;
}

/// @brief A flag like the assignment's: 60 x 50 points over 1.2 m x 1 m, lying flat, quads with
/// both diagonals, held at two corners, k = 1000 N/m, lumped Voronoi masses (1.2 kg in all).
inline ClothOptions flag_recipe() {
  ClothOptions flag;
  flag.columns = 60;
  flag.rows = 50;
  flag.width = 1.2;
  flag.height = 1.0;
  flag.shear = ClothShear::Both;
  flag.plane = ClothPlane::Horizontal;
  flag.pins = ClothPins::TopCorners;
  flag.stiffness = 1000;
  flag.mass.reset();
  return flag;
}

/// @brief The cloth of the drape (issue 22's cost figure, the demo): 81 x 81 points over
/// 1 m x 1 m, lying flat in the x-z plane at y = 0 (y is up), one diagonal per cell, skip-one
/// bending springs, nothing pinned, k = 1000 N/m, lumped Voronoi masses (1 kg in all): the
/// curtain's cloth, laid down. drape_obstacles() gives what it falls on.
inline ClothOptions drape_recipe() {
  ClothOptions drape = curtain_recipe();
  drape.plane = ClothPlane::Horizontal;
  drape.pins = ClothPins::None;
  return drape;
}

/// @brief What the drape falls on, as (kind, parameters) a scene or a program turns into
/// colliders: a sphere of radius 0.25 m centred 0.3 m below the cloth's centre, and a floor
/// (plane, normal +y) 0.6 m below the cloth; Coulomb friction 0.3 on both.
struct DrapeObstacles {
  double sphere_center[3] = {0.5, -0.3, 0.5};
  double sphere_radius = 0.25;
  double floor_point[3] = {0.0, -0.6, 0.0};
  double floor_normal[3] = {0.0, 1.0, 0.0};
  double friction = 0.3;
};

}  // namespace massspring
