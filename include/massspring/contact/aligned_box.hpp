#pragma once
/// @file
/// @brief AlignedBox3: the one axis-aligned box of contact/: the boxes the spatial hash stores
/// (broad_phase/box_hash.hpp), the nodes of the normal-cone tree (broad_phase/
/// normal_cone_tree.hpp) and of a mesh collider's hierarchy (colliders/triangle_mesh.hpp), through
/// the one tree they share (broad_phase/box_tree.hpp).

#include <Eigen/Core>
#include <limits>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief The axis-aligned box [lo, hi] (coordinates in m); empty when lo > hi along some axis.
template <class Scalar>
struct AlignedBox3 {
  Vector3<Scalar> lo, hi;

  /// @brief The empty box (lo = +infinity, hi = -infinity), which extend() grows.
  [[nodiscard]] static AlignedBox3 empty() {
    const Vector3<Scalar> inf = Vector3<Scalar>::Constant(std::numeric_limits<Scalar>::infinity());
    return {inf, -inf};
  }
  /// @brief Grows the box to hold the point p.
  void extend(const Vector3<Scalar>& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  /// @brief The smallest box holding this one and o.
  [[nodiscard]] AlignedBox3 merged(const AlignedBox3& o) const {
    return {lo.cwiseMin(o.lo), hi.cwiseMax(o.hi)};
  }
  /// @brief True when the two boxes share a point (touching counts).
  [[nodiscard]] bool overlaps(const AlignedBox3& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
  /// @brief The box's centre, (lo + hi) / 2.
  [[nodiscard]] Vector3<Scalar> centre() const { return (lo + hi) / 2; }
  /// @brief The squared distance [m^2] from p to the box, 0 inside it.
  [[nodiscard]] Scalar squared_distance(const Vector3<Scalar>& p) const {
    return (lo - p).cwiseMax(p - hi).cwiseMax(Vector3<Scalar>::Zero()).squaredNorm();
  }
};

}  // namespace massspring::contact
