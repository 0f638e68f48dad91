#pragma once
/// @file
/// @brief The core of massspring: systems, storage, integrators, scene descriptions and generators.
/// Needs Eigen only. Scene files (JSON, OBJ) are in massspring/io.hpp.

#include "massspring/error.hpp"
#include "massspring/integrators/fast_mass_spring.hpp"
#include "massspring/integrators/step_report.hpp"
#include "massspring/scene/chain.hpp"
#include "massspring/scene/cloth.hpp"
#include "massspring/scene/face_springs.hpp"
#include "massspring/scene/make_system.hpp"
#include "massspring/scene/net.hpp"
#include "massspring/scene/scene_description.hpp"
#include "massspring/scene/voronoi_masses.hpp"
#include "massspring/storage/storage.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "massspring/types.hpp"
#include "massspring/version.hpp"
