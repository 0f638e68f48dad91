#pragma once
/// @file
/// @brief The key "colliders" of a JSON+OBJ scene (docs/scenes.md): its strict reader and its
/// writer, both used by json_scene.hpp.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/io/detail/json_text.hpp"
#include "massspring/io/obj.hpp"
#include "massspring/scene/collider_description.hpp"

namespace massspring::io::detail {

/// @brief A JSON value for a message: its type and, when short, its text.
inline std::string describe_json(const nlohmann::json& value) {
  std::string text = value.dump();
  if (text.size() > 40) text = text.substr(0, 37) + "...";
  return message(value.type_name(), ' ', text);
}

/// @brief The keys a collider of type `shape` takes besides the common ones, as a message lists
/// them, and whether `key` is one of them or of the common ones.
inline const char* collider_keys(contact::ColliderShape shape) {
  switch (shape) {
    case contact::ColliderShape::Plane:
      return "point, normal";
    case contact::ColliderShape::Sphere:
      return "center, radius";
    case contact::ColliderShape::Capsule:
      return "a, b, radius";
    case contact::ColliderShape::Box:
      return "center, half_extents, rotation";
    case contact::ColliderShape::Mesh:
      return "obj";
  }
  return "";
}
inline bool is_collider_key(contact::ColliderShape shape, const std::string& key) {
  for (const char* k :
       {"type", "friction", "restitution", "thickness", "velocity", "angular_velocity"})
    if (key == k) return true;
  const std::string keys = std::string(", ") + collider_keys(shape) + ",";
  return keys.find(", " + key + ",") != std::string::npos;
}

/// @brief The message for polygon f of an OBJ collider mesh whose fan triangle (a, b, c) (0-based)
/// has zero area: `<obj>:<line>: face (1, 2, 3, 4): fan triangle (1, 3, 4) has zero area`, in
/// the file's 1-based indices (a triangle face says `face (1, 2, 3) has zero area`); without the
/// polygon's line (a mesh not read by read_obj()), `<obj>: face ...`.
template <class Scalar>
std::string zero_area_face(const std::string& obj, const ObjMesh<Scalar>& mesh, std::size_t f,
                           int a, int b, int c) {
  const std::vector<int>& face = mesh.faces[f];
  std::string out = obj;
  if (mesh.face_lines.size() == mesh.faces.size()) out += message(':', mesh.face_lines[f]);
  out += ": face (";
  for (std::size_t v = 0; v < face.size(); ++v) out += message(v ? ", " : "", face[v] + 1);
  out += ')';
  if (face.size() > 3) out += message(": fan triangle (", a + 1, ", ", b + 1, ", ", c + 1, ')');
  return out + " has zero area";
}

/// @brief Reads the value of the key "colliders" of a JSON+OBJ scene: a list of collider objects
/// (docs/scenes.md), checked strictly; nothing is built but a trial collider per entry.
/// @param[in] list      the key's value
/// @param[in] name      the JSON file, named in every message
/// @param[in] folder    the JSON file's folder: a mesh's "obj" is relative to it
/// @param[in] load_obj  as parse_json_scene()'s: `load_obj(path)` gives the OBJ's ObjMesh<Scalar>,
///                      or std::nullopt when there is no such file
/// @throws Error `<json>: colliders[i] (type): ...` naming the key and the value at fault.
template <class Scalar, class LoadObj>
std::vector<ColliderDescription<Scalar>> parse_json_colliders(const nlohmann::json& list,
                                                              const std::string& name,
                                                              const std::filesystem::path& folder,
                                                              LoadObj& load_obj) {
  using Json = nlohmann::json;
  using V3 = Vector3<Scalar>;
  using contact::ColliderShape;
  if (!list.is_array())
    throw Error(message(name, ": key \"colliders\": expected an array of collider objects, got ",
                        describe_json(list)));
  std::vector<ColliderDescription<Scalar>> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Json& entry = list[i];
    std::string where = message(name, ": colliders[", i, "]");
    auto fail = [&where](const auto&... parts) { return Error(message(where, ": ", parts...)); };
    if (!entry.is_object())
      throw fail("expected an object with a \"type\" (plane, sphere, capsule, box or mesh), got ",
                 describe_json(entry));
    const auto type = entry.find("type");
    if (type == entry.end())
      throw fail("missing key \"type\" (plane, sphere, capsule, box or mesh)");
    if (!type->is_string())
      throw fail("\"type\" must be a string (plane, sphere, capsule, box or mesh), got ",
                 describe_json(*type));
    const std::string& t = type->get_ref<const std::string&>();
    ColliderDescription<Scalar> d;
    bool known = false;
    for (ColliderShape s : {ColliderShape::Plane, ColliderShape::Sphere, ColliderShape::Capsule,
                            ColliderShape::Box, ColliderShape::Mesh})
      if (t == contact::to_string(s)) d.shape = s, known = true;
    if (!known)
      throw fail("unknown type ", type->dump(), " (expected plane, sphere, capsule, box or mesh)");
    where += message(" (", t, ")");
    for (const auto& item : entry.items())
      if (!is_collider_key(d.shape, item.key()))
        throw fail("unknown key \"", item.key(), "\" (a ", t, " takes ", collider_keys(d.shape),
                   "; friction, restitution, thickness, velocity, angular_velocity)");

    auto require = [&](const char* key) -> const Json& {
      const auto it = entry.find(key);
      if (it == entry.end()) throw fail("missing key \"", key, "\"");
      return *it;
    };
    // A number, finite in Scalar, with `ok` true; `what` says what ok means.
    auto number = [&](const char* key, const Json& v, bool (*ok)(Scalar), const char* what) {
      if (!v.is_number())
        throw fail('"', key, "\" must be a number ", what, ", got ", describe_json(v));
      const Scalar x = static_cast<Scalar>(v.get<double>());
      if (!std::isfinite(x) || !ok(x))
        throw fail('"', key, "\" must be finite and ", what,
                   std::isfinite(x) ? "" : " (in this Scalar type)", ", got ", v.dump());
      return x;
    };
    auto vector = [&](const char* key, const Json& v, std::size_t size, const char* form) {
      Eigen::Matrix<Scalar, Eigen::Dynamic, 1> x(Eigen::Index(size), 1);
      if (v.is_array() && v.size() == size)
        for (std::size_t c = 0; c < size; ++c)
          if (v[c].is_number()) x(Eigen::Index(c)) = static_cast<Scalar>(v[c].get<double>());
      bool numbers = v.is_array() && v.size() == size;
      for (std::size_t c = 0; numbers && c < size; ++c) numbers = v[c].is_number();
      if (!numbers)
        throw fail('"', key, "\" must be ", form, " (", size, " numbers), got ", describe_json(v));
      if (!x.allFinite())
        throw fail('"', key, "\" must be finite (in this Scalar type), got ", v.dump());
      return x;
    };
    auto vec3 = [&](const char* key) -> V3 { return vector(key, require(key), 3, "[x, y, z]"); };
    auto positive = [](Scalar x) { return x > 0; };
    auto non_negative = [](Scalar x) { return x >= 0; };

    switch (d.shape) {
      case ColliderShape::Plane:
        d.point = vec3("point");
        d.normal = vec3("normal");
        if (!(d.normal.norm() > 0))
          throw fail("\"normal\" must not be zero, got ", require("normal").dump());
        break;
      case ColliderShape::Sphere:
        d.center = vec3("center");
        d.radius = number("radius", require("radius"), positive, "> 0");
        break;
      case ColliderShape::Capsule:
        d.a = vec3("a");
        d.b = vec3("b");
        d.radius = number("radius", require("radius"), positive, "> 0");
        break;
      case ColliderShape::Box:
        d.center = vec3("center");
        d.half_extents = vec3("half_extents");
        if (!(d.half_extents.array() > 0).all())
          throw fail("\"half_extents\" must be 3 numbers > 0, got ",
                     require("half_extents").dump());
        if (const auto r = entry.find("rotation"); r != entry.end()) {
          d.rotation = vector("rotation", *r, 4, "a quaternion [w, x, y, z]");
          if (!(d.rotation.norm() > 0))
            throw fail("\"rotation\" must be a quaternion [w, x, y, z], not zero, got ", r->dump());
        }
        break;
      case ColliderShape::Mesh: {
        const Json& obj = require("obj");
        if (!obj.is_string() || obj.get_ref<const std::string&>().empty())
          throw fail("\"obj\" must be the name of an OBJ file (a string), got ",
                     describe_json(obj));
        const std::filesystem::path path =
            folder / std::filesystem::path(obj.get_ref<const std::string&>());
        std::optional<ObjMesh<Scalar>> mesh;
        try {
          mesh = load_obj(path);
        } catch (const Error& e) {
          throw fail(e.what());
        }
        if (!mesh) throw fail("\"obj\": OBJ file ", path.string(), " not found");
        if (mesh->edges.rows() > 0)
          throw fail("\"obj\": ", path.string(),
                     " has 2-vertex faces or lines: a collider mesh takes polygons only");
        if (mesh->faces.empty())
          throw fail("\"obj\": ", path.string(), " has no polygons: a collider mesh needs some");
        std::size_t triangles = 0;
        for (const auto& f : mesh->faces) triangles += f.size() - 2;
        d.triangles.resize(Eigen::Index(triangles), 3);
        Eigen::Index row = 0;
        for (std::size_t f = 0; f < mesh->faces.size(); ++f) {
          const std::vector<int>& face = mesh->faces[f];
          for (std::size_t k = 1; k + 1 < face.size(); ++k, ++row) {
            d.triangles.row(row) << face[0], face[k], face[k + 1];
            // Zero area as contact::TriangleMesh measures it: 2 area <= eps (longest edge)^2.
            const V3 p0 = mesh->vertices.row(face[0]).transpose();
            const V3 e1 = V3(mesh->vertices.row(face[k]).transpose()) - p0;
            const V3 e2 = V3(mesh->vertices.row(face[k + 1]).transpose()) - p0;
            const Scalar edge2 =
                std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
            if (!(e1.cross(e2).norm() > std::numeric_limits<Scalar>::epsilon() * edge2))
              throw fail(zero_area_face(path.string(), *mesh, f, face[0], face[k], face[k + 1]));
          }
        }
        d.vertices = std::move(mesh->vertices);
        break;
      }
    }

    if (const auto f = entry.find("friction"); f != entry.end()) {
      if (f->is_object()) {
        if (f->size() != 2 || !f->contains("static") || !f->contains("kinetic"))
          throw fail("\"friction\" must be a number >= 0 or {\"static\": a, \"kinetic\": b}, got ",
                     describe_json(*f));
        d.static_friction = number("friction\": \"static", f->at("static"), non_negative, ">= 0");
        d.kinetic_friction =
            number("friction\": \"kinetic", f->at("kinetic"), non_negative, ">= 0");
        if (d.kinetic_friction > d.static_friction)
          throw fail("\"friction\": kinetic ", f->at("kinetic").dump(), " exceeds static ",
                     f->at("static").dump(), " (Coulomb: kinetic <= static)");
      } else {
        d.static_friction = d.kinetic_friction =
            number("friction", *f, non_negative, ">= 0 (or {\"static\": a, \"kinetic\": b})");
      }
    }
    if (const auto e = entry.find("restitution"); e != entry.end())
      d.restitution = number(
          "restitution", *e, [](Scalar x) { return x >= 0 && x <= 1; }, "in [0, 1]");
    if (const auto h = entry.find("thickness"); h != entry.end())
      d.thickness = number("thickness", *h, non_negative, ">= 0");
    if (entry.contains("velocity")) d.velocity = vec3("velocity");
    if (entry.contains("angular_velocity")) d.angular_velocity = vec3("angular_velocity");

    try {  // what the checks above left to the collider (nothing, unless they missed a case)
      (void)make_collider<Scalar>(d);
    } catch (const Error& e) {
      throw fail(e.what());
    }
    out.push_back(std::move(d));
  }
  return out;
}

/// @brief A number for a JSON file, as the shortest text that reads back to the same Scalar
/// (-0 as "-0.0": nlohmann reads "-0" as the integer 0).
template <class Scalar>
void append_json_scalar(std::string& out, Scalar x) {
  if (x == 0 && std::signbit(x))
    out += "-0.0";
  else
    append_number(out, x);
}

template <class Derived>
void append_json_vector(std::string& out, const Eigen::MatrixBase<Derived>& v) {
  out += '[';
  for (Eigen::Index c = 0; c < v.size(); ++c) {
    if (c) out += ", ";
    append_json_scalar(out, v(c));
  }
  out += ']';
}

/// @brief The file write_json_scene() writes the mesh of collider i to: `<stem>_collider<i>.obj`
/// beside the JSON file.
inline std::filesystem::path collider_obj_path(const std::filesystem::path& json, std::size_t i) {
  std::filesystem::path p = json;
  p.replace_filename(json.stem().string() + "_collider" + std::to_string(i) + ".obj");
  return p;
}

/// @brief Appends `,\n  "colliders": [...]` (nothing for no colliders) as parse_json_colliders()
/// reads it back, bit for bit; only the keys that differ from their defaults are written.
/// A mesh's "obj" is collider_obj_path(json, i), which the caller writes.
template <class Scalar>
void append_json_colliders(std::string& out, const std::filesystem::path& json,
                           const std::vector<ColliderDescription<Scalar>>& colliders) {
  if (colliders.empty()) return;
  using contact::ColliderShape;
  out += ",\n  \"colliders\": [";
  for (std::size_t i = 0; i < colliders.size(); ++i) {
    const ColliderDescription<Scalar>& d = colliders[i];
    out += i ? ",\n    {\"type\": \"" : "\n    {\"type\": \"";
    out += contact::to_string(d.shape);
    out += '"';
    auto key = [&out](const char* k) { out += message(", \"", k, "\": "); };
    auto vec = [&](const char* k, const auto& v) {
      key(k);
      append_json_vector(out, v);
    };
    auto num = [&](const char* k, Scalar x) {
      key(k);
      append_json_scalar(out, x);
    };
    switch (d.shape) {
      case ColliderShape::Plane:
        vec("point", d.point);
        vec("normal", d.normal);
        break;
      case ColliderShape::Sphere:
        vec("center", d.center);
        num("radius", d.radius);
        break;
      case ColliderShape::Capsule:
        vec("a", d.a);
        vec("b", d.b);
        num("radius", d.radius);
        break;
      case ColliderShape::Box:
        vec("center", d.center);
        vec("half_extents", d.half_extents);
        vec("rotation", d.rotation);
        break;
      case ColliderShape::Mesh:
        key("obj");
        out += nlohmann::json(collider_obj_path(json, i).filename().string()).dump();
        break;
    }
    if (d.static_friction == d.kinetic_friction) {
      if (d.static_friction != 0 || std::signbit(d.static_friction))
        num("friction", d.static_friction);
    } else {
      key("friction");
      out += "{\"static\": ";
      append_json_scalar(out, d.static_friction);
      out += ", \"kinetic\": ";
      append_json_scalar(out, d.kinetic_friction);
      out += '}';
    }
    if (d.restitution != 0 || std::signbit(d.restitution)) num("restitution", d.restitution);
    if (d.thickness != 0 || std::signbit(d.thickness)) num("thickness", d.thickness);
    auto zero = [](const Vector3<Scalar>& v) {
      return v.isZero(0) && !std::signbit(v(0)) && !std::signbit(v(1)) && !std::signbit(v(2));
    };
    if (!zero(d.velocity)) vec("velocity", d.velocity);
    if (!zero(d.angular_velocity)) vec("angular_velocity", d.angular_velocity);
    out += '}';
  }
  out += "\n  ]";
}

}  // namespace massspring::io::detail
