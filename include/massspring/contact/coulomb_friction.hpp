#pragma once
/// @file
/// @brief coulomb_removed_fraction(): Coulomb's law of dry friction, written once for every
/// response that applies it (the colliders' position and velocity responses, surface contact's
/// impulses).

#include <cmath>

namespace massspring::contact {

/// @brief The fraction of a tangential motion t that Coulomb friction takes away, t a
/// displacement [m] or a velocity [m/s] relative to the other side, under a normal magnitude
/// `normal` >= 0 in the same units (the normal push, or the normal impulse per unit mass):
///
///   1                                 when |t| <= mu_static normal   (the point sticks),
///   mu_kinetic normal / |t|  (< 1)    otherwise                      (it slides, and loses
///                                                                     mu_kinetic normal of t).
///
/// The caller subtracts the fraction times t. `t_squared` = |t|^2 > 0; 0 <= mu_kinetic <=
/// mu_static (Collider::set_friction() checks it). Sticking, the common case, takes no square
/// root. Bridson, Fedkiw and Anderson 2002, "Robust treatment of collisions, contact and friction
/// for cloth animation", section 7.2; at position level, Macklin et al. 2014, "Unified particle
/// physics for real-time applications", section 6.1.
template <class Scalar>
[[nodiscard]] Scalar coulomb_removed_fraction(Scalar t_squared, Scalar normal, Scalar mu_static,
                                              Scalar mu_kinetic) {
  const Scalar cone = mu_static * normal;
  if (t_squared <= cone * cone) return Scalar(1);
  return mu_kinetic * normal / std::sqrt(t_squared);
}

}  // namespace massspring::contact
