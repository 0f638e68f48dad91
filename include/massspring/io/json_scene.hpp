#pragma once
/// @file
/// @brief read_json_scene() and write_json_scene(): the JSON+OBJ scene format
/// (docs/scenes.md), read strictly with nlohmann-json.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/io/detail/text_file.hpp"
#include "massspring/io/json_colliders.hpp"
#include "massspring/io/obj.hpp"
#include "massspring/scene/scene_description.hpp"

namespace massspring::io {

namespace detail {

/// @brief A number's shortest round-trip decimal text (valid JSON for finite values).
template <class Scalar>
std::string json_number(Scalar x) {
  std::string out;
  append_number(out, x);
  return out;
}

/// @brief The Error `<json>: <parts...>` of the JSON+OBJ reader, `name` the JSON file.
template <class... Parts>
Error json_scene_error(const std::string& name, const Parts&... parts) {
  return Error(message(name, ": ", parts...));
}

/// @brief The JSON text parsed, refusing a key repeated at the top level, in "self_collision",
/// or in an object of "colliders" (nlohmann keeps the last silently).
/// @throws Error naming the key (and the collider's entry), or `not valid JSON: ` with nlohmann's
/// message (its line and column) for text that is not JSON.
inline nlohmann::json parse_json_scene_text(const std::string& text, const std::string& name) {
  using Json = nlohmann::json;
  std::set<std::string> seen, self_collision_keys;
  // Inside "colliders": the entry being read and the keys of each object open in it.
  std::string root_key;
  long long entry = -1;
  std::vector<std::set<std::string>> open;
  try {
    return Json::parse(text, [&](int depth, Json::parse_event_t event, Json& parsed) {
      using Event = Json::parse_event_t;
      if (depth == 1 && event == Event::key) {
        const std::string& key = parsed.get_ref<const std::string&>();
        if (!seen.insert(key).second)
          throw json_scene_error(name, "key \"", key, "\" appears twice");
        root_key = key;
      } else if (depth == 2 && root_key == "self_collision" && event == Event::key) {
        const std::string& key = parsed.get_ref<const std::string&>();
        if (!self_collision_keys.insert(key).second)
          throw json_scene_error(name, "key \"self_collision\": key \"", key, "\" appears twice");
      } else if (depth >= 2 && root_key == "colliders") {
        if (depth == 2 &&
            (event == Event::object_start || event == Event::array_start || event == Event::value))
          ++entry;  // the next element of the list
        if (event == Event::object_start) {
          open.emplace_back();
        } else if (event == Event::object_end && !open.empty()) {
          open.pop_back();
        } else if (event == Event::key && !open.empty() &&
                   !open.back().insert(parsed.get_ref<const std::string&>()).second) {
          throw json_scene_error(name, "colliders[", entry, "]: key \"",
                                 parsed.get_ref<const std::string&>(), "\" appears twice");
        }
      }
      return true;
    });
  } catch (const Json::exception& e) {
    std::string what = e.what();
    if (const auto close = what.find("] ");
        what.rfind("[json.exception.", 0) == 0 && close != std::string::npos)
      what = what.substr(close + 2);
    throw json_scene_error(name, "not valid JSON: ", what);
  }
}

/// @brief Checks the root of a JSON+OBJ scene: an object, not a state scene, without "bc", with
/// no key but obj, b, k, m, png, colliders, self_collision, gravity and dt.
/// @throws Error naming what it found instead.
inline void check_json_scene_keys(const nlohmann::json& root, const std::string& name) {
  if (!root.is_object())
    throw json_scene_error(name,
                           "expected a JSON object {\"obj\": ..., \"b\": [...], \"k\": ...}, got ",
                           root.type_name());
  if (root.contains("massspring_state"))
    throw json_scene_error(
        name,
        "a state scene (written by io::write_state), not a JSON+OBJ scene: load it with "
        "io::load_scene or io::read_state");
  for (const auto& item : root.items()) {
    const std::string& key = item.key();
    if (key == "bc")
      throw json_scene_error(name,
                             "key \"bc\" (pinned positions) is not supported: pinned vertices stay "
                             "at their rest positions");
    if (key != "obj" && key != "b" && key != "k" && key != "m" && key != "png" &&
        key != "colliders" && key != "self_collision" && key != "gravity" && key != "dt")
      throw json_scene_error(
          name, "unknown key \"", key,
          "\" (expected obj, b, k, m, png, colliders, self_collision, gravity, dt)");
  }
}

/// @brief The value of a key the scene must have.
/// @throws Error `missing key` naming it.
inline const nlohmann::json& json_scene_require(const nlohmann::json& root, const char* key,
                                                const std::string& name) {
  const auto it = root.find(key);
  if (it == root.end()) throw json_scene_error(name, "missing key \"", key, "\"");
  return *it;
}

/// @brief The number `value` of `key` as a Scalar, finite (in Scalar) and > 0 (`strict`) or >= 0.
/// @throws Error naming the key and the value.
template <class Scalar>
Scalar json_scene_number(const char* key, const nlohmann::json& value, bool strict,
                         const std::string& name) {
  if (!value.is_number())
    throw json_scene_error(name, "key \"", key, "\": expected a number ", strict ? "> 0" : ">= 0",
                           ", got ", describe_json(value));
  const double x = value.get<double>();
  const Scalar s = static_cast<Scalar>(x);
  if (!std::isfinite(s) || (strict ? !(s > 0) : !(s >= 0)))
    throw json_scene_error(
        name, "key \"", key, "\": expected a finite number ", strict ? "> 0" : ">= 0",
        (std::isfinite(s) ? "" : " (in this Scalar type)"), ", got ", value.dump());
  return s;
}

/// @brief "obj": the OBJ file's path, the name given taken relative to the JSON file's folder.
/// @throws Error for a missing key or a value that is not a non-empty string.
inline std::filesystem::path json_scene_obj_path(const nlohmann::json& root,
                                                 const std::filesystem::path& json,
                                                 const std::string& name) {
  const nlohmann::json& obj = json_scene_require(root, "obj", name);
  if (!obj.is_string() || obj.get_ref<const std::string&>().empty())
    throw json_scene_error(name, "key \"obj\": expected the name of an OBJ file (a string), got ",
                           describe_json(obj));
  return json.parent_path() / std::filesystem::path(obj.get_ref<const std::string&>());
}

/// @brief "b": the list of pins, an array of integers (their range is checked by
/// json_scene_pins() once the OBJ's vertices are counted).
/// @throws Error for a missing key, a value that is not an array, or an entry not an integer.
inline const nlohmann::json& json_scene_pin_list(const nlohmann::json& root,
                                                 const std::string& name) {
  const nlohmann::json& b = json_scene_require(root, "b", name);
  if (!b.is_array())
    throw json_scene_error(name, "key \"b\": expected an array of 1-based vertex ids, got ",
                           describe_json(b));
  for (std::size_t p = 0; p < b.size(); ++p)
    if (!b[p].is_number_integer())
      throw json_scene_error(name, "key \"b\": entry ", p, " (counting from 0) is ",
                             describe_json(b[p]), ", expected an integer vertex id (1-based)");
  return b;
}

/// @brief The pins of "b" (integers, 1-based) as 0-based indices of the OBJ's n vertices.
/// @throws Error for a pin out of [1, n], naming its position in "b" and the OBJ file.
inline std::vector<int> json_scene_pins(const nlohmann::json& b, std::int64_t n,
                                        const std::filesystem::path& obj_path,
                                        const std::string& name) {
  std::vector<int> pinned;
  pinned.reserve(b.size());
  for (std::size_t p = 0; p < b.size(); ++p) {
    const bool negative = !b[p].is_number_unsigned() && b[p].get<std::int64_t>() < 0;
    const bool too_big = !negative && b[p].get<std::uint64_t>() > std::uint64_t(n);
    if (negative || too_big || b[p].get<std::int64_t>() == 0)
      throw json_scene_error(name, "key \"b\": entry ", p, " (counting from 0) is ", b[p].dump(),
                             ", out of range [1, ", n, "]: vertex ids are 1-based and ",
                             obj_path.string(), " has ", n, " vertices");
    pinned.push_back(static_cast<int>(b[p].get<std::int64_t>() - 1));
  }
  return pinned;
}

/// @brief "self_collision": `{"thickness": T, "friction": MU}`, both optional, T [m] > 0 and
/// MU >= 0 (SelfCollision's defaults for what is absent).
/// @throws Error for a value that is not an object, an unknown key, or a value out of range.
template <class Scalar>
contact::SelfCollision<Scalar> json_scene_self_collision(const nlohmann::json& sc,
                                                         const std::string& name) {
  if (!sc.is_object())
    throw json_scene_error(
        name,
        "key \"self_collision\": expected an object {\"thickness\": T, \"friction\": MU}, got ",
        describe_json(sc));
  contact::SelfCollision<Scalar> parameters;
  for (const auto& item : sc.items()) {
    const std::string& key = item.key();
    const bool thickness = key == "thickness";
    if (!thickness && key != "friction")
      throw json_scene_error(name, "key \"self_collision\": unknown key \"", key,
                             "\" (expected thickness, friction)");
    const std::string path = "self_collision\": \"" + key;
    (thickness ? parameters.thickness : parameters.friction) =
        json_scene_number<Scalar>(path.c_str(), item.value(), thickness, name);
  }
  return parameters;
}

/// @brief "gravity": [gx, gy, gz], three numbers finite in Scalar [m/s^2].
/// @throws Error showing the value otherwise.
template <class Scalar>
Vector3<Scalar> json_scene_gravity(const nlohmann::json& g, const std::string& name) {
  if (!g.is_array() || g.size() != 3)
    throw json_scene_error(
        name, "key \"gravity\": expected [gx, gy, gz] (three numbers, m/s^2), got ", g.dump());
  Vector3<Scalar> gravity;
  for (std::size_t c = 0; c < 3; ++c) {
    const nlohmann::json& v = g[c];
    const Scalar x = v.is_number() ? static_cast<Scalar>(v.get<double>()) : Scalar(0);
    if (!v.is_number() || !std::isfinite(x))
      throw json_scene_error(
          name, "key \"gravity\": expected [gx, gy, gz] (three finite numbers, m/s^2), got ",
          g.dump());
    gravity(Eigen::Index(c)) = x;
  }
  return gravity;
}

}  // namespace detail

/// @brief The reader behind read_json_scene(), on text in memory. The keys are checked in this
/// order, so that of two faults the first reported is the same on every run: the JSON text and
/// its repeated keys, the root's keys, "obj" and "b" (their types), "k", "m", "png",
/// "self_collision", "dt", "gravity", then the OBJ file, the pins' range and "colliders".
/// @param[in] text      the JSON file's text
/// @param[in] json      its path: named in messages; the `"obj"` key is relative to its folder
/// @param[in] load_obj  `load_obj(path)` returns the OBJ file's ObjMesh<Scalar> (throwing Error
///                      naming its file and line), or std::nullopt when there is no such file.
///                      read_json_scene() passes read_obj(); a fuzzer or a test may parse text
///                      held in memory.
/// @throws Error as read_json_scene() does.
template <class Scalar, class LoadObj>
SceneDescription<Scalar> parse_json_scene(const std::string& text,
                                          const std::filesystem::path& json, LoadObj&& load_obj) {
  static_assert(std::is_floating_point_v<Scalar>,
                "parse_json_scene<Scalar>: Scalar must be float or double");
  using Json = nlohmann::json;
  const std::string name = json.string();
  const Json root = detail::parse_json_scene_text(text, name);
  detail::check_json_scene_keys(root, name);
  const std::filesystem::path obj_path = detail::json_scene_obj_path(root, json, name);
  const Json& b = detail::json_scene_pin_list(root, name);

  SceneDescription<Scalar> scene;
  scene.stiffness = detail::json_scene_number<Scalar>(
      "k", detail::json_scene_require(root, "k", name), false, name);
  if (const auto m = root.find("m"); m != root.end())
    scene.mass = detail::json_scene_number<Scalar>("m", *m, true, name);
  if (const auto png = root.find("png"); png != root.end() && !png->is_string())
    throw detail::json_scene_error(
        name, "key \"png\": expected the name of a texture image (a string), got ",
        detail::describe_json(*png));
  if (const auto sc = root.find("self_collision"); sc != root.end())
    scene.self_collision = detail::json_scene_self_collision<Scalar>(*sc, name);
  if (const auto dt = root.find("dt"); dt != root.end())
    scene.dt = detail::json_scene_number<Scalar>("dt", *dt, true, name);
  if (const auto g = root.find("gravity"); g != root.end())
    scene.gravity = detail::json_scene_gravity<Scalar>(*g, name);

  std::optional<ObjMesh<Scalar>> loaded = load_obj(obj_path);
  if (!loaded)
    throw detail::json_scene_error(name, "key \"obj\": OBJ file ", obj_path.string(), " not found");
  ObjMesh<Scalar> mesh = std::move(*loaded);
  const auto n = static_cast<std::int64_t>(mesh.vertices.rows());
  if (n == 0)
    throw detail::json_scene_error(name, "key \"obj\": OBJ file ", obj_path.string(),
                                   " has no vertices: a scene needs at least one point");
  scene.pinned = detail::json_scene_pins(b, n, obj_path, name);
  if (const auto colliders = root.find("colliders"); colliders != root.end())
    scene.colliders =
        detail::parse_json_colliders<Scalar>(*colliders, name, json.parent_path(), load_obj);
  scene.vertices = std::move(mesh.vertices);
  scene.faces = std::move(mesh.faces);
  scene.edges = std::move(mesh.edges);
  scene.source.file = obj_path.string();
  scene.source.vertex_lines = std::move(mesh.vertex_lines);
  scene.source.face_lines = std::move(mesh.face_lines);
  return scene;
}

/// @brief Reads a scene in the JSON+OBJ format.
///
/// The JSON object has the keys
/// - `"obj"` (required string): the OBJ file, relative to the JSON file's folder, read with
///   read_obj(); its polygons and 2-vertex faces become `faces` and `edges`;
/// - `"b"` (required array of integers): the pinned vertices, **1-based** (the description holds
///   them 0-based); may be empty;
/// - `"k"` (required number >= 0): the stiffness of every spring [N/m];
/// - `"m"` (optional number > 0): the mass of every vertex [kg]; when absent, make_system() gives
///   each vertex its lumped Voronoi area (density 1 kg/m^2);
/// - `"png"` (optional string): a texture, ignored;
/// - `"colliders"` (optional array of objects): obstacles, in order (docs/scenes.md lists their
///   keys); a mesh's `"obj"` is relative to the JSON file's folder, its polygons fan-triangulated;
/// - `"self_collision"` (optional object): self-collision of the cloth's surface, on when present:
///   `{"thickness": T, "friction": MU}`, both optional, thickness [m] > 0 (default 0.004), friction
///   >= 0 (default 0.2); make_system() refuses it for a scene without faces;
/// - `"gravity"` (optional array of 3 finite numbers): the acceleration of gravity [m/s^2];
///   make_system() adds it as a Gravity term;
/// - `"dt"` (optional number > 0): the time step the scene is meant to run at [s] (not part of a
///   system; massspring-simulate runs at it unless given --dt).
///
/// @tparam Scalar float or double
/// @param[in] json  the .json file
/// @throws Error naming the file and the key for a missing, unknown, repeated or mistyped key,
/// `"bc"` (pinned positions: not supported), a pin out of range (its 1-based value and its
/// position in "b"), a non-finite or negative stiffness, a mass that is not > 0; naming the file
/// with nlohmann's line and column when the text is not JSON; for a state scene (the key
/// "massspring_state": written by write_state(), read by load_scene() or read_state()); and
/// read_obj()'s errors (file and line) for the OBJ file; for "self_collision" that is not an
/// object, has a key other than thickness and friction, or a value out of range (naming it:
/// `<json>: key "self_collision": "thickness": expected a finite number > 0, got 0`); for a
/// collider, naming its entry:
/// `<json>: colliders[2] (sphere): "radius" must be finite and > 0, got -1`.
template <class Scalar = double>
SceneDescription<Scalar> read_json_scene(const std::filesystem::path& json) {
  const std::string text = detail::read_text_file(json, "JSON scene");
  return parse_json_scene<Scalar>(
      text, json, [](const std::filesystem::path& obj_path) -> std::optional<ObjMesh<Scalar>> {
        if (!std::filesystem::exists(obj_path)) return std::nullopt;
        return read_obj<Scalar>(obj_path);
      });
}

/// @brief Writes a scene in the JSON+OBJ format: `<stem>.obj` beside `json` (with
/// write_obj(): polygons as `f a b c ...`, edges as `f i j`), then `json` referencing it, pins
/// 1-based, `"m"` only when the mass is given, `"self_collision"` (both fields) only when it is
/// given, the colliders (a mesh collider's triangles in
/// `<stem>_collider<i>.obj` beside it, i its index). Each file is written atomically (`.tmp`,
/// then renamed). read_json_scene() gives the same description back, bit for bit.
/// @param[in] json   the .json file to write (its folder must exist); must not end in .obj
/// @param[in] scene  faces of 3 or more vertices, indices and pins in range, stiffness finite and
///                   >= 0, mass (when given) finite and > 0, self-collision (when given) with
///                   parameters SelfCollision::validate() accepts, colliders make_collider()
///                   accepts
/// @throws Error naming the file and the item for an invalid scene (nothing is written) or when
/// a file cannot be written.
template <class Scalar>
void write_json_scene(const std::filesystem::path& json, const SceneDescription<Scalar>& scene) {
  const std::string name = json.string();
  auto error = [&name](const auto&... parts) {
    return Error(detail::message(name, ": ", parts...));
  };
  std::filesystem::path obj_path = json;
  obj_path.replace_extension(".obj");
  if (obj_path == json) throw error("a JSON scene must not be named .obj: its OBJ file is ", name);
  if (!(std::isfinite(scene.stiffness) && scene.stiffness >= 0))
    throw error("stiffness must be finite and >= 0, got ", scene.stiffness);
  if (scene.mass && !(std::isfinite(*scene.mass) && *scene.mass > 0))
    throw error("mass must be finite and > 0, got ", *scene.mass);
  if (scene.dt && !(std::isfinite(*scene.dt) && *scene.dt > 0))
    throw error("dt must be finite and > 0, got ", *scene.dt);
  if (scene.gravity && !scene.gravity->allFinite())
    throw error("gravity must be finite, got ", massspring::detail::format_row(*scene.gravity));
  if (scene.self_collision) {
    try {
      scene.self_collision->validate();
    } catch (const Error& e) {
      throw error(e.what());
    }
  }
  const Eigen::Index n = scene.vertices.rows();
  for (std::size_t p = 0; p < scene.pinned.size(); ++p)
    if (scene.pinned[p] < 0 || scene.pinned[p] >= n)
      throw error("pin ", p, ": vertex index ", scene.pinned[p], " out of range [0, ", n, ")");

  for (std::size_t c = 0; c < scene.colliders.size(); ++c) {
    const ColliderDescription<Scalar>& d = scene.colliders[c];
    try {
      (void)make_collider<Scalar>(d);
    } catch (const Error& e) {
      throw error("colliders[", c, "] (", contact::to_string(d.shape), "): ", e.what());
    }
  }

  write_obj(obj_path, scene.vertices, scene.faces, scene.edges);
  for (std::size_t c = 0; c < scene.colliders.size(); ++c) {
    const ColliderDescription<Scalar>& d = scene.colliders[c];
    if (d.shape != contact::ColliderShape::Mesh) continue;
    std::vector<std::vector<int>> triangles(std::size_t(d.triangles.rows()));
    for (Eigen::Index t = 0; t < d.triangles.rows(); ++t)
      triangles[std::size_t(t)] = {d.triangles(t, 0), d.triangles(t, 1), d.triangles(t, 2)};
    write_obj(detail::collider_obj_path(json, c), d.vertices, triangles, Edges(0, 2));
  }

  std::string out = "{\n  \"obj\": ";
  out += nlohmann::json(obj_path.filename().string()).dump();
  out += ",\n  \"b\": [";
  for (std::size_t p = 0; p < scene.pinned.size(); ++p) {
    if (p) out += ", ";
    detail::append_index(out, scene.pinned[p] + 1);
  }
  out += "],\n  \"k\": " + detail::json_number(scene.stiffness);
  if (scene.mass) out += ",\n  \"m\": " + detail::json_number(*scene.mass);
  if (scene.self_collision)
    out += ",\n  \"self_collision\": {\"thickness\": " +
           detail::json_number(scene.self_collision->thickness) +
           ", \"friction\": " + detail::json_number(scene.self_collision->friction) + "}";
  if (scene.gravity) {
    out += ",\n  \"gravity\": [";
    for (Eigen::Index c = 0; c < 3; ++c)
      out += (c ? ", " : "") + detail::json_number((*scene.gravity)(c));
    out += ']';
  }
  if (scene.dt) out += ",\n  \"dt\": " + detail::json_number(*scene.dt);
  detail::append_json_colliders(out, json, scene.colliders);
  out += "\n}\n";
  detail::write_text_file_atomically(json, out);
}

}  // namespace massspring::io
