#pragma once
/// @file
/// @brief Scene files: the JSON+OBJ scenes, FOSSSim's XML scenes and OBJ frames.
/// Needs nlohmann_json and pugixml (CMake target massspring::io). The core
/// (massspring/massspring.hpp) never includes this.

#include "massspring/io/fosssim_scene.hpp"
#include "massspring/io/json_scene.hpp"
#include "massspring/io/load_scene.hpp"
#include "massspring/io/obj.hpp"
#include "massspring/massspring.hpp"
