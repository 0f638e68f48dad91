#pragma once
/// @file
/// @brief load_scene(): a MassSpringSystem from a scene file, chosen by the file's extension.

#include <array>
#include <cctype>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/io/fosssim_scene.hpp"
#include "massspring/io/json_scene.hpp"
#include "massspring/io/state_scene.hpp"
#include "massspring/scene/make_system.hpp"

namespace massspring::io {

/// @brief A scene file loaded: the system, what to draw, which files were read, and what the
/// format carries besides a system.
template <class System>
struct LoadedScene {
  /// @brief The system, as load_scene() returns it.
  System system;
  /// @brief Polygons to draw (0-based): the OBJ's polygons (JSON+OBJ), a state scene's faces.
  std::vector<std::vector<int>> faces;
  /// @brief Segments to draw (0-based): the OBJ's 2-vertex faces (JSON+OBJ), every `<edge>` (XML,
  /// springs or not), a state scene's edges.
  Edges edges = Edges(0, 2);
  /// @brief Every file the loader read: the scene, and for a JSON+OBJ scene its OBJ file.
  std::vector<std::filesystem::path> files;
  /// @brief A JSON+OBJ scene's "dt": the time step it is meant to run at [s]; absent otherwise.
  std::optional<double> dt;
  /// @brief The FOSSSim XML scene (its integrator, time step, duration), for .xml files.
  std::optional<FosssimScene> fosssim;
  /// @brief A state scene's "run" object (null otherwise, or when it has none).
  nlohmann::json run;
  /// @brief True for a state scene (written by write_state()).
  bool state = false;
};

namespace detail {

/// @brief One scene file format: its extension (lower case, with the dot), what it is, and how a
/// System is loaded from it.
template <class System>
struct SceneFormat {
  const char* extension;
  const char* description;
  LoadedScene<System> (*load)(const std::filesystem::path&);
};

/// @brief A .json file: a state scene (write_state(): an object with "massspring_state") is read
/// with parse_state_scene(); anything else as the JSON+OBJ scene: read_json_scene(),
/// then make_system(), whose errors get the scene's path in front.
template <class System>
LoadedScene<System> load_json_scene(const std::filesystem::path& path) {
  const std::string text = read_text_file(path, "JSON scene");
  LoadedScene<System> out;
  out.files.push_back(path);
  if (const nlohmann::json root = nlohmann::json::parse(text, nullptr, false);
      is_state_scene(root)) {
    StateScene<System> state = parse_state_scene<System>(root, path);
    out.system = std::move(state.system);
    out.faces = std::move(state.extras.faces);
    out.edges = std::move(state.extras.edges);
    out.run = std::move(state.extras.run);
    out.state = true;
    return out;
  }
  // Read in double whatever the System's Scalar: Voronoi masses are then summed in double.
  SceneDescription<double> scene = parse_json_scene<double>(
      text, path, [&out](const std::filesystem::path& obj) -> std::optional<ObjMesh<double>> {
        if (!std::filesystem::exists(obj)) return std::nullopt;
        out.files.push_back(obj);
        return read_obj<double>(obj);
      });
  try {
    out.system = make_system<System>(scene);
  } catch (const Error& e) {
    throw Error(message(path.string(), ": ", e.what()));
  }
  out.faces = std::move(scene.faces);
  out.edges = std::move(scene.edges);
  out.dt = scene.dt;
  return out;
}

/// @brief FOSSSim's XML scenes: read_fosssim_scene(), then make_fosssim_system(), whose errors
/// get the scene's path in front.
template <class System>
LoadedScene<System> load_fosssim_xml_scene(const std::filesystem::path& path) {
  LoadedScene<System> out;
  out.files.push_back(path);
  out.fosssim = read_fosssim_scene(path);
  try {
    out.system = make_fosssim_system<System>(*out.fosssim);
  } catch (const Error& e) {
    throw Error(message(path.string(), ": ", e.what()));
  }
  out.edges = out.fosssim->edges;
  return out;
}

/// @brief Every format load_scene() knows; a new format is one more entry here.
template <class System>
const auto& scene_formats() {
  static const std::array<SceneFormat<System>, 2> formats = {{
      {".json", "JSON+OBJ scene", &load_json_scene<System>},
      {".xml", "FOSSSim XML scene", &load_fosssim_xml_scene<System>},
  }};
  return formats;
}

}  // namespace detail

/// @brief load_scene() with everything the file holds besides the system (see LoadedScene).
/// @throws Error as load_scene() does.
template <class System>
LoadedScene<System> load_scene_file(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const auto& formats = detail::scene_formats<System>();
  std::string supported;
  for (const auto& format : formats) {
    if (extension == format.extension) return format.load(path);
    supported += detail::message(supported.empty() ? "" : ", ", format.extension, " (",
                                 format.description, ")");
  }
  throw Error(detail::message(path.string(), ": unsupported scene format \"", extension,
                              "\": supported are ", supported));
}

/// @brief Loads a scene file into a system, the format chosen by the extension (any case):
/// `.json` is the JSON+OBJ format (read_json_scene(), then make_system()) or a state
/// scene written by write_state() (an object with the key "massspring_state": the system exactly
/// as written); `.xml` is FOSSSim's 2D XML format (read_fosssim_scene(), then
/// make_fosssim_system(): the system carries the scene's gravity, attraction and drag as force
/// terms). The XML scene's integrator, time step and duration are not part of a system: read them
/// with load_scene_file() or read_fosssim_scene().
/// @tparam System a MassSpringSystem<Scalar, Storage>
/// @param[in] path  the scene file
/// @throws Error naming the path: for an unsupported extension (listing the supported ones), and
/// for every error of the reader or of make_system().
template <class System>
System load_scene(const std::filesystem::path& path) {
  return load_scene_file<System>(path).system;
}

}  // namespace massspring::io
