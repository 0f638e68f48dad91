#pragma once
/// @file
/// @brief The mesh collider's geometry: Collider::mesh() and the contact of a path with a static,
/// two-sided triangle mesh (contact/colliders/triangle_mesh.hpp: continuous detection of the
/// path's crossing, then the closest point within the thickness). Included by the headers that
/// make mesh colliders; contact/colliders/collider.hpp reaches it through a table of pointers
/// mesh() sets.

#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <memory>
#include <utility>

#include "massspring/contact/colliders/collider.hpp"
#include "massspring/contact/colliders/triangle_mesh.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Collider::mesh() and the mesh's part of Collider::contact() and its quick rejection.
template <class Scalar>
struct MeshShape {
  using V3 = Vector3<Scalar>;

  /// @brief Collider::mesh(): the mesh's frame centred on its bounding box.
  static Collider<Scalar> make(Points<Scalar> vertices, Triangles triangles) {
    static constexpr typename Collider<Scalar>::Geometry kGeometry{nullptr, &MeshShape::contact,
                                                                   &MeshShape::bound, nullptr};
    if (vertices.rows() > 0 && vertices.allFinite()) {
      const V3 center =
          (vertices.colwise().minCoeff() + vertices.colwise().maxCoeff()).transpose() / 2;
      vertices.rowwise() -= center.transpose();
      Collider<Scalar> c(ColliderShape::Mesh, center);
      c.mesh_ =
          std::make_shared<const TriangleMesh<Scalar>>(std::move(vertices), std::move(triangles));
      c.geometry_ = &kGeometry;
      return c;
    }
    throw Error(vertices.rows() == 0 ? "mesh collider: no vertices"
                                     : "mesh collider: a vertex is not finite");
  }

  /// @brief Continuous detection of the local path a -> b (x_start in the start frame, b = x_end
  /// in the end frame), then the closest point within the thickness.
  static bool contact(const Collider<Scalar>& self, const V3& x_start, const V3& b, Scalar slop,
                      ColliderContact<Scalar>& c) {
    const V3 a = self.rotation_.transpose() * (x_start - self.translation_);
    const TriangleMesh<Scalar>& mesh = *self.mesh_;
    Scalar t = 0;
    int tri = -1;
    if (mesh.first_crossing(a, b, t, tri)) {
      const V3 n = mesh.normal(tri), v0 = mesh.vertex(tri, 0);
      const Scalar side_a = (a - v0).dot(n), side_b = (b - v0).dot(n);
      // The side the point came from (a on the plane: the side opposite its motion).
      const V3 ns = (side_a > 0 || (side_a == 0 && side_b < 0)) ? n : V3(-n);
      // Back to that side, at the thickness and at least a few rounding units away, so that the
      // next step knows the side.
      const Scalar offset = self.thickness_ + 64 * std::numeric_limits<Scalar>::epsilon() *
                                                  (1 + b.cwiseAbs().maxCoeff());
      c.depth = offset - (b - v0).dot(ns);
      c.normal = self.end_rotation_ * ns;
      c.velocity = self.surface_velocity(self.end_rotation_ * b + self.end_translation_);
      return true;
    }
    if (!(self.thickness_ + slop > 0)) return false;
    V3 q;
    if (!mesh.closest_within(b, self.thickness_ + slop, q, tri)) return false;
    const Scalar d = (b - q).norm();
    V3 n = d > 0 ? V3((b - q) / d) : mesh.normal(tri);
    if (d == 0 && (a - q).dot(n) < 0) n = -n;
    c.depth = self.thickness_ - d;
    c.normal = self.end_rotation_ * n;
    c.velocity = self.surface_velocity(self.end_rotation_ * b + self.end_translation_);
    return true;
  }

  /// @brief The radius of a ball about the mesh's centre that holds it.
  static Scalar bound(const Collider<Scalar>& self) {
    return std::max(self.mesh_->lower().norm(), self.mesh_->upper().norm());
  }
};

}  // namespace massspring::contact
