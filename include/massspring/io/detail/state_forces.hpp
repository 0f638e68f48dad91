#pragma once
/// @file
/// @brief A system's force terms in a state scene (io/state_scene.hpp), in their order:
///
///     "forces": [{"type": "gravity", "g": [gx, gy, gz]},                 // m/s^2
///                {"type": "constant force", "force": [fx, fy, fz]},      // N on every point
///                {"type": "linear drag", "beta": b},                     // N s/m
///                {"type": "gravitational attraction",                    // G in N m^2/kg^2,
///                 "pairs": [[i, j, G], ...], "softening": eps},          // eps in m
///                {"type": "vortex force", "pairs": [[i, j, kbs, kvc], ...]}]
///
/// Point indices are 0-based. Numbers are written so that they read back bit for bit
/// (json_text.hpp). Other terms (your own, FOSSSim's penalty contact) cannot be written.

#include <cstddef>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <typeinfo>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/forces/gravitational_attraction.hpp"
#include "massspring/forces/gravity.hpp"
#include "massspring/forces/linear_drag.hpp"
#include "massspring/forces/vortex.hpp"
#include "massspring/io/detail/json_text.hpp"
#include "massspring/types.hpp"

namespace massspring::io::detail {

/// @brief The force terms a state scene holds, by their ForceTerm name (Gravity,
/// ConstantForce, LinearDrag, GravitationalAttraction, VortexForce): the one list, read through
/// io::state_force_terms() (io/state_scene.hpp).
inline constexpr const char* kStateForceTermNames[] = {"gravity", "constant force", "linear drag",
                                                       "gravitational attraction", "vortex force"};

/// @brief "gravity, constant force, ... and vortex force": kStateForceTermNames for messages.
inline std::string state_force_terms_text() {
  std::string out;
  const std::size_t n = std::size(kStateForceTermNames);
  for (std::size_t k = 0; k < n; ++k)
    out += std::string(k == 0 ? "" : k + 1 == n ? " and " : ", ") + kStateForceTermNames[k];
  return out;
}

/// @brief Appends the JSON array of `system`'s force terms.
/// @throws Error "force term k (name) cannot be written: ..." for a term of another type (nothing
/// appended that the caller keeps: it writes nothing then).
template <class System>
void append_state_forces(std::string& out, const System& system) {
  using Scalar = typename System::Scalar;
  const auto& terms = system.forces();
  out += '[';
  for (int k = 0; k < terms.size(); ++k) {
    if (k) out += ",\n    ";
    if (const auto* g =
            static_cast<const Gravity<Scalar>*>(terms[k].target(typeid(Gravity<Scalar>)))) {
      out += "{\"type\": \"gravity\", \"g\": ";
      append_list(out, g->g);
    } else if (const auto* f = static_cast<const ConstantForce<Scalar>*>(
                   terms[k].target(typeid(ConstantForce<Scalar>)))) {
      out += "{\"type\": \"constant force\", \"force\": ";
      append_list(out, f->force);
    } else if (const auto* d = static_cast<const LinearDrag<Scalar>*>(
                   terms[k].target(typeid(LinearDrag<Scalar>)))) {
      out += "{\"type\": \"linear drag\", \"beta\": ";
      append_real(out, double(d->beta));
    } else if (const auto* a = static_cast<const GravitationalAttraction<Scalar>*>(
                   terms[k].target(typeid(GravitationalAttraction<Scalar>)))) {
      out += "{\"type\": \"gravitational attraction\", \"pairs\": [";
      for (std::size_t p = 0; p < a->pairs().size(); ++p) {
        const auto& pair = a->pairs()[p];
        out += p ? ", [" : "[";
        append_index(out, pair.i);
        out += ", ";
        append_index(out, pair.j);
        out += ", ";
        append_real(out, double(pair.G));
        out += ']';
      }
      out += "], \"softening\": ";
      append_real(out, double(a->softening()));
    } else if (const auto* v = static_cast<const VortexForce<Scalar>*>(
                   terms[k].target(typeid(VortexForce<Scalar>)))) {
      out += "{\"type\": \"vortex force\", \"pairs\": [";
      for (std::size_t p = 0; p < v->pairs().size(); ++p) {
        const auto& pair = v->pairs()[p];
        out += p ? ", [" : "[";
        append_index(out, pair.i);
        out += ", ";
        append_index(out, pair.j);
        out += ", ";
        append_real(out, double(pair.kbs));
        out += ", ";
        append_real(out, double(pair.kvc));
        out += ']';
      }
      out += ']';
    } else {
      throw Error(massspring::detail::message("force term ", k, " (", terms[k].name,
                                              ") cannot be written: a state scene holds ",
                                              state_force_terms_text(), " terms"));
    }
    out += '}';
  }
  out += ']';
}

/// @brief Adds the terms of a state scene's "forces" array (already checked to be an array) to
/// `system`, in order.
/// @throws Error "key \"forces\": entry k: ..." for an entry of unknown type, a missing, extra or
/// mistyped field, and every error of the term's constructor (a point index out of range, i == j,
/// a negative G, ...).
template <class System>
void parse_state_forces(const nlohmann::json& forces, System& system) {
  using Scalar = typename System::Scalar;
  using Json = nlohmann::json;
  using massspring::detail::message;
  for (std::size_t k = 0; k < forces.size(); ++k) {
    const Json& f = forces[k];
    auto fail = [k](const auto&... parts) {
      return Error(message("key \"forces\": entry ", k, ": ", parts...));
    };
    const auto type = f.is_object() ? f.find("type") : f.end();
    if (!f.is_object() || type == f.end() || !type->is_string())
      throw fail(
          "expected {\"type\": \"gravity\", \"g\": [...]}, {\"type\": \"constant force\", "
          "\"force\": [...]}, {\"type\": \"linear drag\", \"beta\": b}, {\"type\": "
          "\"gravitational attraction\", \"pairs\": [...], \"softening\": eps} or {\"type\": "
          "\"vortex force\", \"pairs\": [...]}");
    auto number = [&](const Json& v, const char* what) {
      if (!v.is_number()) throw fail("\"", what, "\" must be a number, got ", v.dump());
      return Scalar(v.get<double>());
    };
    auto vector3 = [&](const char* key) {
      const Json& v = f.at(key);
      if (!v.is_array() || v.size() != 3) throw fail("\"", key, "\" must be [x, y, z]");
      Vector3<Scalar> out;
      for (std::size_t c = 0; c < 3; ++c) out(Eigen::Index(c)) = number(v[c], key);
      return out;
    };
    auto index = [&](const Json& v) {
      if (!v.is_number_integer() || v.get<long long>() < 0 ||
          v.get<long long>() > std::numeric_limits<int>::max())
        throw fail("expected a point index (an integer >= 0), got ", v.dump());
      return int(v.get<long long>());
    };
    // "pairs": [[i, j, x...], ...] with `values` numbers after the two indices.
    auto pairs = [&](std::size_t values, const char* shape) {
      const Json& list = f.at("pairs");
      if (!list.is_array()) throw fail("\"pairs\" must be an array of ", shape);
      std::vector<std::vector<double>> out;
      for (const Json& p : list) {
        if (!p.is_array() || p.size() != 2 + values)
          throw fail("\"pairs\": expected ", shape, ", got ", p.dump());
        std::vector<double> row{double(index(p[0])), double(index(p[1]))};
        for (std::size_t c = 0; c < values; ++c) row.push_back(double(number(p[2 + c], "pairs")));
        out.push_back(std::move(row));
      }
      return out;
    };
    auto has = [&](std::initializer_list<const char*> keys) {
      if (f.size() != keys.size() + 1) return false;
      for (const char* key : keys)
        if (!f.contains(key)) return false;
      return true;
    };
    const std::string t = type->get<std::string>();
    try {
      if (t == "gravity" && has({"g"})) {
        system.add_force(Gravity<Scalar>(vector3("g")));
      } else if (t == "constant force" && has({"force"})) {
        system.add_force(ConstantForce<Scalar>(vector3("force")));
      } else if (t == "linear drag" && has({"beta"})) {
        system.add_force(LinearDrag<Scalar>(number(f["beta"], "beta")));
      } else if (t == "gravitational attraction" && has({"pairs", "softening"})) {
        std::vector<typename GravitationalAttraction<Scalar>::Pair> list;
        for (const auto& p : pairs(1, "[i, j, G]"))
          list.push_back({int(p[0]), int(p[1]), Scalar(p[2])});
        system.add_force(
            GravitationalAttraction<Scalar>(std::move(list), number(f["softening"], "softening")));
      } else if (t == "vortex force" && has({"pairs"})) {
        std::vector<typename VortexForce<Scalar>::Pair> list;
        for (const auto& p : pairs(2, "[i, j, kbs, kvc]"))
          list.push_back({int(p[0]), int(p[1]), Scalar(p[2]), Scalar(p[3])});
        system.add_force(VortexForce<Scalar>(std::move(list)));
      } else {
        throw fail("unknown force term ", f.dump());
      }
    } catch (const Error& e) {
      const std::string what = e.what();
      if (what.rfind("key \"forces\"", 0) == 0) throw;
      throw fail(what);
    }
  }
}

}  // namespace massspring::io::detail
