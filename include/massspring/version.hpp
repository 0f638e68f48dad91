#pragma once
/// @file
/// @brief The library's version: the one place it is written (CMake reads it from here).

#define MASSSPRING_VERSION_MAJOR 0
#define MASSSPRING_VERSION_MINOR 1
#define MASSSPRING_VERSION_PATCH 0

namespace massspring {
/// @brief Version as a string, "major.minor.patch".
inline constexpr const char* version_string = "0.1.0";
}  // namespace massspring
