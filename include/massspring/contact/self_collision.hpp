#pragma once
/// @file
/// @brief SelfCollision: the parameters of contact between the parts of one cloth surface
/// (MassSpringSystem::set_self_collision(); the response is contact/response/surface_contact.hpp,
/// the model docs/contact.md).

#include <cmath>

#include "massspring/detail/validate.hpp"

namespace massspring::contact {

/// @brief Self-collision of a system's surface (its triangles and their edges).
///
/// Two parts of the surface that are not neighbours (a point and a triangle it is not a corner of,
/// two edges that share no point) repel when they come closer than `thickness`, and are never let
/// closer than `thickness / 10`: no edge ever crosses a triangle. Parts of one patch that stays
/// unfolded over a step (contact/broad_phase/normal_cone_tree.hpp) are not tested: they lie side
/// by side on one layer and cannot cross. Sliding contact obeys Coulomb's law with coefficient
/// `friction`.
template <class Scalar>
struct SelfCollision {
  /// @brief The distance at which layers repel [m], > 0. At rest, folded layers lie about this
  /// far apart. Default 4 mm, a tenth to a fifth of a cloth's typical edge length.
  Scalar thickness = Scalar(0.004);
  /// @brief Coulomb's coefficient between layers (dimensionless), >= 0. Default 0.2.
  Scalar friction = Scalar(0.2);

  /// @brief Throws Error naming the field when a value is out of range or not finite.
  void validate() const {
    massspring::detail::require_number("self-collision", "thickness", double(thickness), true);
    massspring::detail::require_number("self-collision", "friction", double(friction), false);
  }
};

}  // namespace massspring::contact
