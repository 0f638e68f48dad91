#pragma once
/// @file
/// @brief make_system(): a MassSpringSystem from a SceneDescription.

#include <cstddef>
#include <string>
#include <vector>

#include "massspring/contact/response/surface_contact.hpp"
#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/gravity.hpp"
#include "massspring/scene/face_springs.hpp"
#include "massspring/scene/scene_description.hpp"
#include "massspring/scene/voronoi_masses.hpp"

namespace massspring {

/// @brief The triangles of polygons split as fans: face (f0, f1, ..., fk) gives (f0, fi, fi+1)
/// for i = 1 .. k-1, in face order. `face_of`, when given, receives each triangle's face index.
inline Triangles fan_triangles(const std::vector<std::vector<int>>& faces,
                               std::vector<std::size_t>* face_of = nullptr) {
  std::size_t count = 0;
  for (const auto& face : faces) count += face.size() >= 3 ? face.size() - 2 : 0;
  Triangles triangles(Eigen::Index(count), 3);
  if (face_of) face_of->assign(count, 0);
  Eigen::Index t = 0;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (std::size_t i = 1; i + 1 < faces[f].size(); ++i, ++t) {
      triangles.row(t) << faces[f][0], faces[f][i], faces[f][i + 1];
      if (face_of) (*face_of)[std::size_t(t)] = f;
    }
  return triangles;
}

namespace detail {

/// @brief True when `source` gives a line for each of `count` items of `lines`' kind.
inline bool has_lines(const MeshSource& source, const std::vector<std::size_t>& lines,
                      std::size_t count) {
  return !source.file.empty() && lines.size() == count;
}

/// @brief Gives `system` the fan triangles of `faces` as its surface. A triangle
/// detail::surface_triangle_problem() refuses is named by its face: with a `source`, as
/// `<file>:<line>: face (1, 2, 3, 4): fan triangle (1, 3, 4): <what>` in the file's 1-based
/// indices (a triangle face without "fan triangle"); without, as `face 0 (0, 1, 2, 3): surface
/// triangle 1 = (0, 2, 3): <what>`, 0-based, as set_surface() numbers the triangles.
template <class System>
void set_face_surface(System& system, const std::vector<std::vector<int>>& faces,
                      const MeshSource& source) {
  std::vector<std::size_t> face_of;
  const Triangles triangles = fan_triangles(faces, &face_of);
  const bool in_file = has_lines(source, source.face_lines, faces.size());
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
    const std::string problem = surface_triangle_problem(a, b, c, system.rest_positions());
    if (problem.empty()) continue;
    const std::size_t f = face_of[std::size_t(t)];
    const std::vector<int>& face = faces[f];
    const int base = in_file ? 1 : 0;
    std::string vertices;
    for (std::size_t v = 0; v < face.size(); ++v)
      vertices += message(v ? ", " : "", face[v] + base);
    if (in_file)
      throw Error(message(source.file, ':', source.face_lines[f], ": face (", vertices, "): ",
                          face.size() > 3
                              ? message("fan triangle (", a + 1, ", ", b + 1, ", ", c + 1, "): ")
                              : std::string(),
                          problem));
    throw Error(message("face ", f, " (", vertices, "): surface triangle ", t, " = (", a, ", ", b,
                        ", ", c, "): ", problem));
  }
  system.set_surface(triangles);
}

}  // namespace detail

/// @brief Builds the system a scene describes: springs from face_springs(), rest lengths from the
/// vertices, uniform stiffness, the given uniform mass or else voronoi_masses(), pins at the rest
/// positions, the surface (the faces split into fans of triangles, fan_triangles(); none without
/// faces), self-collision when the scene asks for it, then the colliders in their order, and a
/// Gravity term when the scene has `gravity` (its `dt` is not part of a system).
/// @throws Error for invalid indices, a missing mass without faces, a vertex of zero mass, a face
/// with a fan triangle of zero area, self-collision asked for without faces or with parameters
/// out of range, or a collider make_collider() refuses (named `colliders[i] (shape): `). A vertex
/// or a face is named where the scene's `source` says it was written, `<file>:<line>: vertex 4`,
/// `<file>:<line>: face (1, 2, 3)` (the file's 1-based indices); in a scene built in code, by
/// its 0-based index, `point 3`, `face 0 (0, 1, 2)` (see detail::set_face_surface()).
template <class System, class Scalar>
System make_system(const SceneDescription<Scalar>& scene) {
  using S = typename System::Scalar;
  const int n = int(scene.vertices.rows());
  const Edges springs = face_springs(n, scene.faces, scene.edges);
  Vector<S> masses;
  if (scene.mass) {
    masses = Vector<S>::Constant(n, S(*scene.mass));
  } else {
    if (scene.faces.empty())
      throw Error("scene has no faces to take masses from: give a mass (\"m\")");
    masses = voronoi_masses(scene.vertices, scene.faces).template cast<S>();
    const bool in_file = detail::has_lines(scene.source, scene.source.vertex_lines, std::size_t(n));
    for (int i = 0; i < n; ++i)
      if (!(masses(i) > 0))
        throw Error(detail::message(
            in_file ? detail::message(scene.source.file, ':',
                                      scene.source.vertex_lines[std::size_t(i)], ": vertex ", i + 1)
                    : detail::message("point ", i),
            ": lies on no face of nonzero area, so its Voronoi mass is ", masses(i),
            "; give a mass (\"m\")"));
  }
  System system(scene.vertices.template cast<S>(), springs, masses,
                Vector<S>::Constant(springs.rows(), S(scene.stiffness)));
  system.pin(scene.pinned);
  if (!scene.faces.empty()) detail::set_face_surface(system, scene.faces, scene.source);
  if (scene.self_collision) {
    if (scene.faces.empty())
      throw Error(
          "self_collision: the scene has no faces, so no surface to collide (chains and nets "
          "have none)");
    contact::SelfCollision<S> parameters;
    parameters.thickness = S(scene.self_collision->thickness);
    parameters.friction = S(scene.self_collision->friction);
    system.set_self_collision(parameters);
  }
  for (std::size_t c = 0; c < scene.colliders.size(); ++c) {
    const ColliderDescription<Scalar>& d = scene.colliders[c];
    try {
      system.add_collider(make_collider<S>(d));
    } catch (const Error& e) {
      throw Error(
          detail::message("colliders[", c, "] (", contact::to_string(d.shape), "): ", e.what()));
    }
  }
  if (scene.gravity) system.add_force(Gravity<S>(scene.gravity->template cast<S>()));
  return system;
}

}  // namespace massspring
