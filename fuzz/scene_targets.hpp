#pragma once
/// @file
/// @brief What the fuzz targets do with one input, shared with the regression test that replays
/// tests/data/fuzz/ in the normal test suite (tests/io/test_error_catalogue.cpp).
///
/// Each function reads a scene from text in memory, builds its system and takes one step. A bad
/// input must end in massspring::Error (which the caller catches); anything else is a bug.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <massspring/integrators/with_integrator.hpp>
#include <massspring/io/fosssim_scene.hpp>
#include <massspring/io/json_scene.hpp>
#include <massspring/massspring.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace massspring::fuzz {

using FuzzSystem = MassSpringSystem<double, Sparse>;

/// @brief The JSON+OBJ target: `input` is the JSON text, a NUL byte, then the OBJ text (no NUL:
/// the OBJ file is empty). Whatever file the JSON's "obj" key names, the OBJ text is what is read
/// (in memory: no file is touched). Then make_system() and one FastMassSpring step.
inline void run_json_scene_input(std::string_view input) {
  const std::size_t nul = input.find('\0');
  const std::string json(input.substr(0, nul));
  const std::string obj(nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1));
  const SceneDescription<double> scene = io::parse_json_scene<double>(
      json, "fuzz/scene.json",
      [&obj](const std::filesystem::path& path) -> std::optional<io::ObjMesh<double>> {
        return io::detail::parse_obj<double>(obj, path.string());
      });
  FuzzSystem system = make_system<FuzzSystem>(scene);
  system.add_force(Gravity<double>(Vector3<double>(0, -9.8, 0)));
  // A step exercises what the loader let through (zero-length springs, isolated points, ...).
  FastMassSpring<FuzzSystem> solver;
  solver.options.iterations = 2;
  solver.precompute(system, 1.0 / 30);
  (void)solver.step(system);
}

/// @brief The FOSSSim XML target: parse_fosssim_scene(), make_fosssim_system() and one step of
/// the integrator the scene names, with its dt.
inline void run_fosssim_scene_input(std::string_view input) {
  const io::FosssimScene scene = io::parse_fosssim_scene(std::string(input), "fuzz/scene.xml");
  (void)scene.steps();
  FuzzSystem system = io::make_fosssim_system<FuzzSystem>(scene);
  with_integrator<FuzzSystem>(io::integrator_kind(scene.integrator), [&](auto& integrator) {
    integrator.precompute(system, scene.dt);
    (void)integrator.step(system);
  });
}

/// @brief A libFuzzer entry point's body: runs `target` on the input; massspring::Error (a clear
/// refusal) is fine, anything else escapes and is a finding. Returns 0, as libFuzzer expects.
inline int fuzz_input(void (*target)(std::string_view), const std::uint8_t* data,
                      std::size_t size) {
  try {
    target(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const Error&) {
    // refused clearly: fine
  }
  return 0;
}

}  // namespace massspring::fuzz
