#pragma once
// The project's own scenes, written by massspring-make-scenes into examples/scenes and checked
// against the committed files by tests/scene/test_generators.cpp.

#include <string>
#include <utility>
#include <vector>

#include "massspring/massspring.hpp"
#include "massspring/scene/recipes.hpp"

namespace massspring::examples {

/// @brief (file stem, scene) of every scene in examples/scenes.
inline std::vector<std::pair<std::string, SceneDescription<double>>> project_scenes() {
  std::vector<std::pair<std::string, SceneDescription<double>>> scenes;

  // A chain like the assignment's horizontal chain: 10 points over 1 m along +x, both ends pinned.
  ChainOptions chain;
  chain.points = 10;
  chain.length = 1.0;
  chain.pins = ChainPins::BothEnds;
  chain.stiffness = 500;
  chain.mass = 1;
  scenes.emplace_back("chain", make_chain(chain));

  // A horizontal net of 8 x 8 points over 1 m x 1 m, hung by its four corners.
  NetOptions net;
  net.columns = 8;
  net.rows = 8;
  net.width = 1.0;
  net.depth = 1.0;
  net.pins = NetPins::Corners;
  net.stiffness = 300;
  net.mass = 1;
  scenes.emplace_back("net", make_net(net));

  // A flag like the assignment's, and the curtain of Liu et al. 2013 (fast mass-spring): see
  // massspring/scene/recipes.hpp.
  scenes.emplace_back("flag", make_cloth(flag_recipe()));
  scenes.emplace_back("curtain", make_cloth(curtain_recipe()));

  return scenes;
}

}  // namespace massspring::examples
