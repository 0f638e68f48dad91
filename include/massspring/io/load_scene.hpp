#pragma once
/// @file
/// @brief load_scene(): a MassSpringSystem from a scene file, chosen by the file's extension.

#include <array>
#include <cctype>
#include <filesystem>
#include <string>

#include "massspring/error.hpp"
#include "massspring/io/fosssim_scene.hpp"
#include "massspring/io/json_scene.hpp"
#include "massspring/scene/make_system.hpp"

namespace massspring::io {

namespace detail {

/// @brief One scene file format: its extension (lower case, with the dot), what it is, and how a
/// System is loaded from it.
template <class System>
struct SceneFormat {
  const char* extension;
  const char* description;
  System (*load)(const std::filesystem::path&);
};

/// @brief The assignment's JSON+OBJ scenes: read_json_scene(), then make_system(), whose errors
/// get the scene's path in front.
template <class System>
System load_json_scene(const std::filesystem::path& path) {
  // Read in double whatever the System's Scalar: Voronoi masses are then summed in double.
  const SceneDescription<double> scene = read_json_scene<double>(path);
  try {
    return make_system<System>(scene);
  } catch (const Error& e) {
    throw Error(message(path.string(), ": ", e.what()));
  }
}

/// @brief FOSSSim's XML scenes: read_fosssim_scene(), then make_fosssim_system(), whose errors
/// get the scene's path in front.
template <class System>
System load_fosssim_xml_scene(const std::filesystem::path& path) {
  const FosssimScene scene = read_fosssim_scene(path);
  try {
    return make_fosssim_system<System>(scene);
  } catch (const Error& e) {
    throw Error(message(path.string(), ": ", e.what()));
  }
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

/// @brief Loads a scene file into a system, the format chosen by the extension (any case):
/// `.json` is the assignment's JSON+OBJ format (read_json_scene(), then make_system()); `.xml` is
/// FOSSSim's 2D XML format (read_fosssim_scene(), then make_fosssim_system(): the system carries
/// the scene's gravity, attraction and drag as force terms). The XML scene's integrator, time step
/// and duration are not part of a system: read them with read_fosssim_scene().
/// @tparam System a MassSpringSystem<Scalar, Storage>
/// @param[in] path  the scene file
/// @throws Error naming the path: for an unsupported extension (listing the supported ones), and
/// for every error of the reader or of make_system().
template <class System>
System load_scene(const std::filesystem::path& path) {
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

}  // namespace massspring::io
