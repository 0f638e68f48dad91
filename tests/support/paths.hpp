#pragma once
// Where the tests find scenes: ../shared (not ours, read in place) and the project's own.
#include <filesystem>

namespace massspring::test {

/// @brief The folder holding scenes/jacobson and scenes/fosssim (MASSSPRING_SHARED_DIR).
std::filesystem::path shared_dir();
/// @brief The project's source tree (for examples/scenes).
std::filesystem::path source_dir();
/// @brief ../shared/scenes/jacobson
inline std::filesystem::path jacobson_dir() { return shared_dir() / "scenes" / "jacobson"; }
/// @brief True when ../shared/scenes/jacobson is there (CI requires it: MASSSPRING_REQUIRE_SHARED).
inline bool have_jacobson() { return std::filesystem::is_directory(jacobson_dir()); }

}  // namespace massspring::test
