#pragma once
/// @file
/// @brief write_state() and read_state(): a system's whole model and state as one JSON file
/// (a "state scene"), so that a run can be saved and resumed.
///
/// The file is one JSON object, every index 0-based (unlike the JSON+OBJ scenes' 1-based pins):
///
///     {"massspring_state": 1,                       // the format's version
///      "rest_positions": [[x, y, z], ...],          // #points rows [m]
///      "springs": [[i, j], ...],                    // #springs rows
///      "masses": [...], "stiffness": [...], "rest_lengths": [...], "damping": [...],
///      "pinned": [i, ...], "pin_targets": [[x, y, z], ...],   // ascending, row r for pinned[r]
///      "positions": [[...], ...], "velocities": [[...], ...],
///      "forces": [{"type": "gravity", "g": [gx, gy, gz]}, ...],  // io/detail/state_forces.hpp
///      "colliders": [{"type": "plane", ...}, ...],  // optional: io/detail/state_colliders.hpp
///      "surface": [[a, b, c], ...],                 // optional: io/detail/state_surface.hpp
///      "self_collision": {"thickness": h, "friction": mu},   // optional: on when present
///      "faces": [[a, b, c, ...], ...], "edges": [[i, j], ...],  // optional: for drawing only
///      "run": {...}}                                // optional: the caller's, kept as it is
///
/// Numbers are written as the shortest decimal text that reads back to the same double (floats
/// are widened to double first, so they read back exactly too): loading the file gives a system
/// equal to the written one in every field, bit for bit (masses, stiffness, rest lengths,
/// damping, pins and their targets, positions, velocities, the force terms in order, the
/// colliders with their current pose and velocities, the surface and the self-collision
/// parameters). Only the
/// revision() differs: a loaded system is a new model.

#include <cmath>
#include <filesystem>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/forces/gravity.hpp"
#include "massspring/forces/linear_drag.hpp"
#include "massspring/io/detail/json_text.hpp"
#include "massspring/io/detail/state_colliders.hpp"
#include "massspring/io/detail/state_forces.hpp"
#include "massspring/io/detail/state_surface.hpp"
#include "massspring/io/detail/text_file.hpp"
#include "massspring/io/obj.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "massspring/types.hpp"

namespace massspring::io {

/// @brief What a state scene carries besides the system: a drawing and the caller's own data.
struct StateSceneExtras {
  /// @brief Polygons to draw (0-based point indices); not springs.
  std::vector<std::vector<int>> faces;
  /// @brief Segments to draw (0-based point indices); not springs.
  Edges edges = Edges(0, 2);
  /// @brief The caller's data (an object, or null for none), written and read back unchanged;
  /// massspring-simulate keeps the frame number, time step and integrator there.
  nlohmann::json run;
};

/// @brief A state scene read back: the system and the extras.
template <class System>
struct StateScene {
  System system;
  StateSceneExtras extras;
};

namespace detail {

/// @brief The key that marks a JSON file as a state scene; its value is the format's version.
inline constexpr const char* kStateSceneKey = "massspring_state";

}  // namespace detail

/// @brief The names (ForceConcept::name, each term's name()) of the force terms a state scene can
/// hold, in the order of the file's comment: "gravity", "constant force", "linear drag",
/// "gravitational attraction", "vortex force". write_state() refuses a system with any other
/// term.
inline std::vector<std::string> state_force_terms() {
  return {std::begin(detail::kStateForceTermNames), std::end(detail::kStateForceTermNames)};
}

/// @brief True when a state scene can hold a force term named `name` (ForceConcept::name).
inline bool state_holds_force_term(const std::string& name) {
  for (const char* term : detail::kStateForceTermNames)
    if (name == term) return true;
  return false;
}

/// @brief The terms of state_force_terms() as one phrase for messages: "gravity, constant
/// force, linear drag, gravitational attraction and vortex force".
inline std::string state_force_terms_text() { return detail::state_force_terms_text(); }

/// @brief Writes a system's whole model and state as a state scene (see the file's comment),
/// atomically: to `<path>.tmp`, then renamed over `path`.
/// @param[in] system  any MassSpringSystem; its force terms must be Gravity, ConstantForce,
///                    LinearDrag, GravitationalAttraction or VortexForce (other terms cannot be
///                    written: Error, nothing written)
/// @param[in] path    the file to write (its folder must exist)
/// @param[in] extras  drawing and caller data to store with it (indices checked against the system)
/// @throws Error naming the path: a force term that cannot be written, a drawing index out of
/// range, a file that cannot be written, a rename that failed (the `.tmp` is then kept, whole, and
/// the message names it).
template <class System>
void write_state(const System& system, const std::filesystem::path& path,
                 const StateSceneExtras& extras = {}) {
  using detail::append_list;
  using detail::append_rows;
  const std::string name = path.string();
  auto error = [&name](const auto&... parts) {
    return Error(detail::message(name, ": ", parts...));
  };
  const int n = system.num_points();
  for (std::size_t f = 0; f < extras.faces.size(); ++f)
    for (int v : extras.faces[f])
      if (v < 0 || v >= n)
        throw error("face ", f, ": point index ", v, " out of range [0, ", n, ")");
  for (Eigen::Index e = 0; e < extras.edges.rows(); ++e)
    for (int c = 0; c < 2; ++c)
      if (extras.edges(e, c) < 0 || extras.edges(e, c) >= n)
        throw error("edge ", e, ": point index ", extras.edges(e, c), " out of range [0, ", n, ")");
  if (!extras.run.is_null() && !extras.run.is_object())
    throw error("the run data must be a JSON object or null, got ", extras.run.type_name());

  std::string forces;
  try {
    detail::append_state_forces(forces, system);
  } catch (const Error& e) {
    throw error(e.what());
  }

  std::string out = "{\n  \"massspring_state\": 1,\n  \"rest_positions\": ";
  append_rows(out, system.rest_positions());
  out += ",\n  \"springs\": ";
  append_rows(out, system.springs());
  out += ",\n  \"masses\": ";
  append_list(out, system.masses());
  out += ",\n  \"stiffness\": ";
  append_list(out, system.stiffness());
  out += ",\n  \"rest_lengths\": ";
  append_list(out, system.rest_lengths());
  out += ",\n  \"damping\": ";
  append_list(out, system.damping());
  out += ",\n  \"pinned\": [";
  for (std::size_t r = 0; r < system.pinned().size(); ++r) {
    if (r) out += ", ";
    detail::append_index(out, system.pinned()[r]);
  }
  out += "],\n  \"pin_targets\": ";
  append_rows(out, system.pin_targets());
  out += ",\n  \"positions\": ";
  append_rows(out, system.positions());
  out += ",\n  \"velocities\": ";
  append_rows(out, system.velocities());
  out += ",\n  \"forces\": " + forces;
  if (!system.colliders().empty()) {
    out += ",\n  \"colliders\": ";
    detail::append_state_colliders(out, system.colliders());
  }
  detail::append_state_surface(out, system);
  if (!extras.faces.empty()) {
    out += ",\n  \"faces\": [";
    for (std::size_t f = 0; f < extras.faces.size(); ++f) {
      out += f ? ", [" : "[";
      for (std::size_t v = 0; v < extras.faces[f].size(); ++v) {
        if (v) out += ", ";
        detail::append_index(out, extras.faces[f][v]);
      }
      out += ']';
    }
    out += ']';
  }
  if (extras.edges.rows() > 0) {
    out += ",\n  \"edges\": ";
    append_rows(out, extras.edges);
  }
  if (extras.run.is_object()) out += ",\n  \"run\": " + extras.run.dump();
  out += "\n}\n";
  detail::write_text_file_atomically(path, out);
}

/// @brief True when `root` (a parsed JSON value) is a state scene: an object with the key
/// "massspring_state".
inline bool is_state_scene(const nlohmann::json& root) {
  return root.is_object() && root.contains(detail::kStateSceneKey);
}

/// @brief The reader behind read_state(), on parsed JSON.
/// @param[in] root  the file's JSON value
/// @param[in] path  the file, named in every message
/// @throws Error as read_state() does.
template <class System>
StateScene<System> parse_state_scene(const nlohmann::json& root,
                                     const std::filesystem::path& path) {
  using Scalar = typename System::Scalar;
  using Json = nlohmann::json;
  const std::string name = path.string();
  auto error = [&name](const auto&... parts) {
    return Error(detail::message(name, ": ", parts...));
  };
  if (!is_state_scene(root))
    throw error("not a state scene (a JSON object with the key \"massspring_state\")");
  const Json& version = root.at(detail::kStateSceneKey);
  if (!version.is_number_integer() || version.get<long long>() != 1)
    throw error("key \"massspring_state\": this reader knows version 1, got ", version.dump());
  static const char* const known[] = {
      "massspring_state", "rest_positions", "springs",       "masses",      "stiffness",
      "rest_lengths",     "damping",        "pinned",        "pin_targets", "positions",
      "velocities",       "forces",         "faces",         "edges",       "run",
      "colliders",        "surface",        "self_collision"};
  for (const auto& item : root.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || item.key() == k;
    if (!ok) throw error("unknown key \"", item.key(), "\"");
  }
  auto require = [&](const char* key) -> const Json& {
    const auto it = root.find(key);
    if (it == root.end()) throw error("missing key \"", key, "\"");
    if (!it->is_array()) throw error("key \"", key, "\": expected an array, got ", it->type_name());
    return *it;
  };
  auto number = [&](const char* key, const Json& v, std::size_t row) {
    if (!v.is_number())
      throw error("key \"", key, "\": entry ", row, " (counting from 0): expected a number, got ",
                  v.type_name());
    return Scalar(v.get<double>());
  };
  auto index = [&](const char* key, const Json& v, std::size_t row) {
    if (!v.is_number_integer() || v.get<long long>() < 0 ||
        v.get<long long>() > std::numeric_limits<int>::max())
      throw error("key \"", key, "\": entry ", row,
                  " (counting from 0): expected a point index (an integer >= 0), got ", v.dump());
    return int(v.get<long long>());
  };
  // Entry i of array a, an array of out.cols() values each read by read(key, value, i), as row i
  // of out (sized a.size() by its columns).
  auto fill_rows = [&](auto& out, const char* key, const Json& a, const char* shape, auto read) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (!a[i].is_array() || a[i].size() != std::size_t(out.cols()))
        throw error("key \"", key, "\": entry ", i, " (counting from 0): expected ", shape);
      for (std::size_t c = 0; c < a[i].size(); ++c)
        out(Eigen::Index(i), Eigen::Index(c)) = read(key, a[i][c], i);
    }
  };
  auto rows = [&](const char* key, std::size_t expected_rows, bool check_rows) {
    const Json& a = require(key);
    if (check_rows && a.size() != expected_rows)
      throw error("key \"", key, "\": expected ", expected_rows, " rows, got ", a.size());
    Points<Scalar> m(Eigen::Index(a.size()), 3);
    fill_rows(m, key, a, "[x, y, z]", number);
    return m;
  };
  auto pairs = [&](const char* key, const Json& a) {
    Edges e(Eigen::Index(a.size()), 2);
    fill_rows(e, key, a, "[i, j]", index);
    return e;
  };
  auto list = [&](const char* key, std::size_t expected) {
    const Json& a = require(key);
    if (a.size() != expected)
      throw error("key \"", key, "\": expected ", expected, " values, got ", a.size());
    Vector<Scalar> v(Eigen::Index(a.size()));
    for (std::size_t i = 0; i < a.size(); ++i) v(Eigen::Index(i)) = number(key, a[i], i);
    return v;
  };

  const Points<Scalar> rest = rows("rest_positions", 0, false);
  const auto n = std::size_t(rest.rows());
  const Edges springs = pairs("springs", require("springs"));
  const auto m = std::size_t(springs.rows());
  const Vector<Scalar> masses = list("masses", n), stiffness = list("stiffness", m);
  const Vector<Scalar> rest_lengths = list("rest_lengths", m), damping = list("damping", m);
  const Json& pinned = require("pinned");
  const Points<Scalar> targets = rows("pin_targets", pinned.size(), true);
  const Points<Scalar> positions = rows("positions", n, true);
  const Points<Scalar> velocities = rows("velocities", n, true);
  StateScene<System> out;
  try {
    out.system = System(rest, springs, masses, stiffness);
    out.system.set_rest_lengths(rest_lengths);
    out.system.set_damping(damping);
    for (std::size_t r = 0; r < pinned.size(); ++r)
      out.system.pin(index("pinned", pinned[r], r), targets.row(Eigen::Index(r)).transpose());
    out.system.set_positions(positions);
    out.system.set_velocities(velocities);
    detail::parse_state_forces(require("forces"), out.system);
    if (const auto colliders = root.find("colliders"); colliders != root.end())
      for (auto& c : detail::parse_state_colliders<Scalar>(*colliders))
        out.system.add_collider(std::move(c));
    detail::parse_state_surface(root, out.system);
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind(name + ": ", 0) == 0) throw;
    throw error(what);
  }
  if (const auto faces = root.find("faces"); faces != root.end()) {
    if (!faces->is_array()) throw error("key \"faces\": expected an array");
    for (std::size_t f = 0; f < faces->size(); ++f) {
      const Json& face = (*faces)[f];
      if (!face.is_array() || face.size() < 3)
        throw error("key \"faces\": entry ", f, " (counting from 0): expected 3 or more indices");
      std::vector<int> ids;
      for (const Json& v : face) {
        const int i = index("faces", v, f);
        if (std::size_t(i) >= n)
          throw error("key \"faces\": entry ", f, ": point index ", i, " out of range [0, ", n,
                      ")");
        ids.push_back(i);
      }
      out.extras.faces.push_back(std::move(ids));
    }
  }
  if (const auto edges = root.find("edges"); edges != root.end()) {
    if (!edges->is_array()) throw error("key \"edges\": expected an array");
    out.extras.edges = pairs("edges", *edges);
    if (out.extras.edges.size() > 0 && std::size_t(out.extras.edges.maxCoeff()) >= n)
      throw error("key \"edges\": point index ", out.extras.edges.maxCoeff(), " out of range [0, ",
                  n, ")");
  }
  if (const auto run = root.find("run"); run != root.end()) {
    if (!run->is_object()) throw error("key \"run\": expected an object, got ", run->type_name());
    out.extras.run = *run;
  }
  return out;
}

/// @brief Reads a state scene written by write_state().
/// @tparam System a MassSpringSystem<Scalar, Storage>
/// @param[in] path  the .json file
/// @throws Error naming the path: not JSON, not a state scene, an unknown version or key, a
/// missing or mistyped key, a count that does not match the points or springs, and every error of
/// the system's constructor and setters (a mass <= 0, a spring out of range, a surface triangle
/// out of range or of zero area, self-collision without a surface, ...).
template <class System>
StateScene<System> read_state(const std::filesystem::path& path) {
  const std::string text = detail::read_text_file(path, "state scene");
  nlohmann::json root;
  try {
    root = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw Error(detail::message(path.string(), ": not valid JSON: ", e.what()));
  }
  return parse_state_scene<System>(root, path);
}

}  // namespace massspring::io
