#pragma once
/// @file
/// @brief FastMassSpring, the local-global solver of Liu et al. 2013: the public include. The
/// solver and its pieces live in integrators/local_global/.

#include "massspring/integrators/local_global/fast_mass_spring.hpp"
