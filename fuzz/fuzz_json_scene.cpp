/// @file
/// @brief libFuzzer target: see massspring::fuzz::run_json_scene_input() in scene_targets.hpp.
/// massspring::Error is the one expected outcome of a bad input: anything else (a crash, another
/// exception, an AddressSanitizer or UBSan report) is a finding.

#include <cstddef>
#include <cstdint>

#include "scene_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return massspring::fuzz::fuzz_input(massspring::fuzz::run_json_scene_input, data, size);
}
