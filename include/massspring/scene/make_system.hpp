#pragma once
/// @file
/// @brief make_system(): a MassSpringSystem from a SceneDescription.

#include <cstddef>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/scene/face_springs.hpp"
#include "massspring/scene/scene_description.hpp"
#include "massspring/scene/voronoi_masses.hpp"

namespace massspring {

/// @brief Builds the system a scene describes: springs from face_springs(), rest lengths from the
/// vertices, uniform stiffness, the given uniform mass or else voronoi_masses(), pins at the rest
/// positions, then the colliders in their order.
/// @throws Error for invalid indices, a missing mass without faces, a vertex of zero mass, or a
/// collider make_collider() refuses (named `colliders[i] (shape): `).
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
    for (int i = 0; i < n; ++i)
      if (!(masses(i) > 0))
        throw Error(detail::message("point ", i, " (OBJ vertex ", i + 1,
                                    "): lies on no face of nonzero area, so its Voronoi mass is ",
                                    masses(i), "; give a mass (\"m\")"));
  }
  System system(scene.vertices.template cast<S>(), springs, masses,
                Vector<S>::Constant(springs.rows(), S(scene.stiffness)));
  system.pin(scene.pinned);
  for (std::size_t c = 0; c < scene.colliders.size(); ++c) {
    const ColliderDescription<Scalar>& d = scene.colliders[c];
    try {
      system.add_collider(make_collider<S>(d));
    } catch (const Error& e) {
      throw Error(
          detail::message("colliders[", c, "] (", contact::to_string(d.shape), "): ", e.what()));
    }
  }
  return system;
}

}  // namespace massspring
