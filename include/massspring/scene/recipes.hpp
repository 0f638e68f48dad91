#pragma once
/// @file
/// @brief Named recipes that the project's scenes, benchmarks and examples share, each as the
/// options that make_chain(), make_net() or make_cloth() turn into a scene (one place for each).
/// A program that varies one (a stiffness sweep, another size) starts from the recipe and says
/// what it changes.

#include "massspring/scene/chain.hpp"
#include "massspring/scene/cloth.hpp"
#include "massspring/scene/net.hpp"

namespace massspring {

/// @brief A chain like the JSON+OBJ scenes' horizontal chain: 10 points over 1 m along +x, both
/// ends pinned, k = 500 N/m, 1 kg per point.
inline ChainOptions chain_recipe() { return ChainOptions{}; }  // ChainOptions' defaults

/// @brief A net like the JSON+OBJ scenes': 8 x 8 points over 1 m x 1 m, horizontal, hung by its
/// four corners, k = 300 N/m, 1 kg per point.
inline NetOptions net_recipe() { return NetOptions{}; }  // NetOptions' defaults

/// @brief A square cloth hanging from its two top corners: n x n points over 1 m x 1 m,
/// vertical, quads with both diagonals, k = 1000 N/m, lumped Voronoi masses (1 kg in all).
/// @param[in] n points per side, >= 2 (make_cloth() checks)
inline ClothOptions hanging_cloth_recipe(int n) {
  ClothOptions cloth;
  cloth.columns = n;
  cloth.rows = n;
  cloth.width = 1.0;
  cloth.height = 1.0;
  cloth.shear = ClothShear::Both;
  cloth.bending = false;
  cloth.plane = ClothPlane::Vertical;
  cloth.pins = ClothPins::TopCorners;
  cloth.stiffness = 1000;
  cloth.mass.reset();
  return cloth;
}

/// @brief The curtain of Liu et al. 2013 ("Fast Simulation of Mass-Spring Systems", section 6):
/// 81 x 81 points over 1 m x 1 m, vertical, one diagonal per cell, skip-one bending springs,
/// hanging from its two top corners, k = 1000 N/m, lumped Voronoi masses (1 kg in all): 6561
/// points, 32158 springs.
inline ClothOptions curtain_recipe() {
  ClothOptions curtain = hanging_cloth_recipe(81);
  curtain.shear = ClothShear::One;
  curtain.bending = true;
  return curtain;
}

/// @brief A flag like the JSON+OBJ scenes': 60 x 50 points over 1.2 m x 1 m, lying flat, quads with
/// both diagonals, held at two corners, k = 1000 N/m, lumped Voronoi masses (1.2 kg in all): the
/// hanging cloth's springs, pins and masses at another size, laid down.
inline ClothOptions flag_recipe() {
  ClothOptions flag = hanging_cloth_recipe(60);
  flag.rows = 50;
  flag.width = 1.2;
  flag.plane = ClothPlane::Horizontal;
  return flag;
}

/// @brief The cloth of the drape (the contact cost benchmark, the demo): 81 x 81 points over
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
