#pragma once
/// @file
/// @brief A system's surface and self-collision in a state scene (io/state_scene.hpp):
///
///     "surface": [[a, b, c], ...],                        // optional: #triangles rows, 0-based
///     "self_collision": {"thickness": h, "friction": mu}  // optional: present when it is on
///
/// Both keys are written only when the system has them; a file without them (one written before
/// they existed, too) reads as a system without a surface, self-collision off. Numbers are written
/// so that they read back bit for bit (json_text.hpp).

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "massspring/contact/response/surface_contact.hpp"
#include "massspring/contact/self_collision.hpp"
#include "massspring/error.hpp"
#include "massspring/io/detail/json_text.hpp"
#include "massspring/io/detail/text_file.hpp"
#include "massspring/types.hpp"

namespace massspring::io::detail {

/// @brief Appends `,\n  "surface": ...` and `,\n  "self_collision": ...` for what `system` has.
template <class System>
void append_state_surface(std::string& out, const System& system) {
  if (system.surface().rows() > 0) {
    out += ",\n  \"surface\": ";
    append_rows(out, system.surface());
  }
  if (const auto& sc = system.self_collision()) {
    out += ",\n  \"self_collision\": {\"thickness\": ";
    append_real(out, double(sc->thickness));
    out += ", \"friction\": ";
    append_real(out, double(sc->friction));
    out += '}';
  }
}

/// @brief Reads the keys "surface" and "self_collision" of a state scene's `root` (when present)
/// into `system`, whose points are already set.
/// @throws Error naming the key (and the entry or field): a value of the wrong type or shape, an
/// unknown field, and the system's own errors (a triangle out of range, with a repeated point or
/// of zero area; a parameter out of range; self-collision without a surface). The caller puts the
/// file's name in front.
template <class System>
void parse_state_surface(const nlohmann::json& root, System& system) {
  using Scalar = typename System::Scalar;
  using Json = nlohmann::json;
  if (const auto surface = root.find("surface"); surface != root.end()) {
    if (!surface->is_array())
      throw Error(
          message("key \"surface\": expected an array of [a, b, c], got ", surface->type_name()));
    Triangles triangles(Eigen::Index(surface->size()), 3);
    for (std::size_t t = 0; t < surface->size(); ++t) {
      const Json& row = (*surface)[t];
      if (!row.is_array() || row.size() != 3)
        throw Error(message("key \"surface\": entry ", t,
                            " (counting from 0): expected [a, b, c], got ", row.dump()));
      for (std::size_t c = 0; c < 3; ++c) {
        const Json& v = row[c];
        if (!v.is_number_integer() || v.get<long long>() < 0 ||
            v.get<long long>() > std::numeric_limits<int>::max())
          throw Error(message("key \"surface\": entry ", t,
                              " (counting from 0): expected a point index (an integer >= 0), got ",
                              v.dump()));
        triangles(Eigen::Index(t), Eigen::Index(c)) = int(v.get<long long>());
      }
    }
    try {
      system.set_surface(triangles);
    } catch (const Error& e) {
      throw Error(message("key \"surface\": ", e.what()));
    }
  }
  if (const auto sc = root.find("self_collision"); sc != root.end()) {
    if (!sc->is_object())
      throw Error(
          message("key \"self_collision\": expected {\"thickness\": h, \"friction\": mu}, got ",
                  sc->type_name()));
    contact::SelfCollision<Scalar> parameters;
    for (const auto& item : sc->items()) {
      const bool thickness = item.key() == "thickness";
      if (!thickness && item.key() != "friction")
        throw Error(message("key \"self_collision\": unknown key \"", item.key(),
                            "\" (expected thickness, friction)"));
      if (!item.value().is_number())
        throw Error(message("key \"self_collision\": \"", item.key(), "\": expected a number, got ",
                            item.value().dump()));
      (thickness ? parameters.thickness : parameters.friction) = Scalar(item.value().get<double>());
    }
    if (!sc->contains("thickness") || !sc->contains("friction"))
      throw Error(message("key \"self_collision\": expected both \"thickness\" and \"friction\""));
    try {
      system.set_self_collision(parameters);
    } catch (const Error& e) {
      throw Error(message("key \"self_collision\": ", e.what()));
    }
  }
}

}  // namespace massspring::io::detail
