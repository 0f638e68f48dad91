#pragma once
/// @file
/// @brief A system's colliders in a state scene (io/state_scene.hpp): each one's shape in its own
/// frame, its current pose, material and velocities, written so that reading them back gives
/// colliders equal to the written ones bit for bit (a resumed run continues exactly).
///
///     {"type": "sphere", "radius": r,             // plane: "normal"; capsule: "half_axis",
///      "rotation": [[...], [...], [...]],         //   "radius"; box: "half_extents";
///      "translation": [x, y, z],                  //   mesh: "vertices", "triangles"
///      "friction": {"static": a, "kinetic": b}, "restitution": e, "thickness": h,
///      "velocity": [...], "angular_velocity": [...]}
///
/// Collider's factories normalise a plane's normal and re-centre a mesh: the writer gives them
/// inputs for which that changes nothing. A plane's normal is written as a multiple of the unit
/// normal that the factory maps back to it exactly (plane_normal_for(): all but about 3 in 10^5
/// unit normals have one); a mesh whose vertices
/// are not centred to the last bit gets two unused vertices at opposite corners of a box centred
/// at 0 (mesh_vertices_for()).

#include <Eigen/Core>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "massspring/contact/colliders/colliders.hpp"
#include "massspring/error.hpp"
#include "massspring/io/detail/json_text.hpp"

namespace massspring::io::detail {

/// @brief A normal n with Collider::plane(p, n).axis() == unit, bit for bit (unit: a plane's
/// axis()). The factory divides n by its computed norm, whose rounding differs from one multiple
/// of `unit` to the next: the first of 4096 multiples that gives `unit` back is returned (about 3
/// unit normals in 10^5 have none; `unit` itself is returned for them, and the plane read back
/// may differ from the written one by a rounding unit of its normal).
template <class Scalar>
Vector3<Scalar> plane_normal_for(const Vector3<Scalar>& unit) {
  for (int k = 0; k < 4096; ++k) {
    const Vector3<Scalar> n = unit * Scalar(1 + k * 0.0123456789);
    if (contact::Collider<Scalar>::plane(Vector3<Scalar>::Zero(), n).axis() == unit) return n;
  }
  return unit;
}

/// @brief Vertices that Collider::mesh() re-centres by exactly 0, keeping `local` (a mesh
/// collider's vertices, in its frame) bit for bit: `local` when its bounding box is centred at 0
/// to the last bit, else `local` and two unused vertices at -m and +m (m the largest |coordinate|
/// per axis).
template <class Scalar>
Points<Scalar> mesh_vertices_for(const Points<Scalar>& local) {
  const Eigen::Matrix<Scalar, 1, 3> lo = local.colwise().minCoeff(),
                                    hi = local.colwise().maxCoeff();
  if (((lo + hi) / 2).isZero(0)) return local;
  const Eigen::Matrix<Scalar, 1, 3> m = lo.cwiseAbs().cwiseMax(hi.cwiseAbs());
  Points<Scalar> out(local.rows() + 2, 3);
  out.topRows(local.rows()) = local;
  out.row(local.rows()) = -m;
  out.row(local.rows() + 1) = m;
  return out;
}

/// @brief Appends the value of a state scene's "colliders" key: a JSON array.
template <class Scalar>
void append_state_colliders(std::string& out, const contact::ColliderSet<Scalar>& colliders) {
  using contact::ColliderShape;
  out += '[';
  for (int i = 0; i < colliders.size(); ++i) {
    const contact::Collider<Scalar>& c = colliders[i];
    out += i ? ",\n    {\"type\": \"" : "\n    {\"type\": \"";
    out += contact::to_string(c.shape());
    out += '"';
    auto key = [&out](const char* k) { out += message(", \"", k, "\": "); };
    switch (c.shape()) {
      case ColliderShape::Plane:
        key("normal");
        append_list(out, plane_normal_for<Scalar>(c.axis()));
        break;
      case ColliderShape::Sphere:
        break;
      case ColliderShape::Capsule:
        key("half_axis");
        append_list(out, c.axis());
        break;
      case ColliderShape::Box:
        key("half_extents");
        append_list(out, c.axis());
        break;
      case ColliderShape::Mesh:
        key("vertices");
        append_rows(out, mesh_vertices_for(c.triangle_mesh()->vertices()));
        key("triangles");
        append_rows(out, c.triangle_mesh()->triangles());
        break;
    }
    if (c.shape() == ColliderShape::Sphere || c.shape() == ColliderShape::Capsule) {
      key("radius");
      append_real(out, double(c.radius()));
    }
    key("rotation");
    append_rows(out, c.rotation());
    key("translation");
    append_list(out, c.translation());
    out += ", \"friction\": {\"static\": ";
    append_real(out, double(c.static_friction()));
    out += ", \"kinetic\": ";
    append_real(out, double(c.kinetic_friction()));
    out += '}';
    key("restitution");
    append_real(out, double(c.restitution()));
    key("thickness");
    append_real(out, double(c.thickness()));
    key("velocity");
    append_list(out, c.velocity());
    key("angular_velocity");
    append_list(out, c.angular_velocity());
    out += '}';
  }
  out += colliders.size() ? "\n  ]" : "]";
}

/// @brief Reads a state scene's "colliders" (append_state_colliders()'s form), strictly.
/// @throws Error `key "colliders": entry i (type): ...` (the caller puts the file in front).
template <class Scalar>
std::vector<contact::Collider<Scalar>> parse_state_colliders(const nlohmann::json& list) {
  using Json = nlohmann::json;
  using V3 = Vector3<Scalar>;
  using C = contact::Collider<Scalar>;
  using contact::ColliderShape;
  if (!list.is_array())
    throw Error(message("key \"colliders\": expected an array, got ", list.type_name()));
  std::vector<C> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Json& e = list[i];
    std::string where = message("key \"colliders\": entry ", i);
    auto fail = [&where](const auto&... parts) { return Error(message(where, ": ", parts...)); };
    const auto type = e.is_object() ? e.find("type") : e.end();
    if (!e.is_object() || type == e.end() || !type->is_string())
      throw fail("expected an object with a \"type\"");
    const std::string& t = type->get_ref<const std::string&>();
    where += message(" (", t, ")");
    const char* shape_keys = t == "plane"     ? "normal"
                             : t == "sphere"  ? "radius"
                             : t == "capsule" ? "half_axis radius"
                             : t == "box"     ? "half_extents"
                             : t == "mesh"    ? "vertices triangles"
                                              : nullptr;
    if (!shape_keys) throw fail("unknown collider type");
    const std::string keys = std::string(
                                 " type rotation translation friction restitution "
                                 "thickness velocity angular_velocity ") +
                             shape_keys + ' ';
    for (const auto& item : e.items())
      if (keys.find(' ' + item.key() + ' ') == std::string::npos)
        throw fail("unknown key \"", item.key(), "\"");
    auto require = [&](const char* key) -> const Json& {
      const auto it = e.find(key);
      if (it == e.end()) throw fail("missing key \"", key, "\"");
      return *it;
    };
    auto number = [&](const char* key, const Json& v) {
      if (!v.is_number()) throw fail("\"", key, "\": expected a number, got ", v.type_name());
      return Scalar(v.get<double>());
    };
    auto matrix = [&](const char* key, const Json& v, Eigen::Index cols) {
      if (!v.is_array()) throw fail("\"", key, "\": expected an array of rows");
      Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> m(
          Eigen::Index(v.size()), cols);
      for (std::size_t r = 0; r < v.size(); ++r) {
        if (!v[r].is_array() || Eigen::Index(v[r].size()) != cols)
          throw fail("\"", key, "\": row ", r, ": expected ", cols, " numbers");
        for (Eigen::Index c = 0; c < cols; ++c)
          m(Eigen::Index(r), c) = number(key, v[r][std::size_t(c)]);
      }
      return m;
    };
    auto vec3 = [&](const char* key, const Json& v) -> V3 {
      if (!v.is_array() || v.size() != 3) throw fail("\"", key, "\": expected [x, y, z]");
      return V3(number(key, v[0]), number(key, v[1]), number(key, v[2]));
    };
    try {
      C c = [&] {
        if (t == "plane") return C::plane(V3::Zero(), vec3("normal", require("normal")));
        if (t == "sphere") return C::sphere(V3::Zero(), number("radius", require("radius")));
        if (t == "capsule") {
          const V3 h = vec3("half_axis", require("half_axis"));
          return C::capsule(-h, h, number("radius", require("radius")));
        }
        if (t == "box") return C::box(V3::Zero(), vec3("half_extents", require("half_extents")));
        const auto v = matrix("vertices", require("vertices"), 3);
        const Json& tris = require("triangles");
        contact::Triangles f(Eigen::Index(tris.size()), 3);
        for (std::size_t r = 0; r < tris.size(); ++r) {
          if (!tris[r].is_array() || tris[r].size() != 3)
            throw fail("\"triangles\": row ", r, ": expected 3 vertex indices");
          for (std::size_t k = 0; k < 3; ++k) {
            if (!tris[r][k].is_number_integer() || tris[r][k].get<long long>() < 0 ||
                tris[r][k].get<long long>() >= v.rows())
              throw fail("\"triangles\": row ", r, ": expected vertex indices in [0, ", v.rows(),
                         "), got ", tris[r].dump());
            f(Eigen::Index(r), Eigen::Index(k)) = int(tris[r][k].get<long long>());
          }
        }
        return C::mesh(v, f);
      }();
      const Json& friction = require("friction");
      if (!friction.is_object() || friction.size() != 2 || !friction.contains("static") ||
          !friction.contains("kinetic"))
        throw fail("\"friction\": expected {\"static\": a, \"kinetic\": b}");
      c.set_pose(matrix("rotation", require("rotation"), 3),
                 vec3("translation", require("translation")));
      c.set_friction(number("friction", friction["static"]),
                     number("friction", friction["kinetic"]));
      c.set_restitution(number("restitution", require("restitution")));
      c.set_thickness(number("thickness", require("thickness")));
      c.set_velocity(vec3("velocity", require("velocity")));
      c.set_angular_velocity(vec3("angular_velocity", require("angular_velocity")));
      out.push_back(std::move(c));
    } catch (const Error& err) {
      const std::string what = err.what();
      if (what.rfind(where, 0) == 0) throw;
      throw fail(what);
    }
  }
  return out;
}

}  // namespace massspring::io::detail
