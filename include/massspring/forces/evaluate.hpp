#pragma once
/// @file
/// @brief Evaluating all of a system's forces: its springs (Hooke, plus damping where some b > 0)
/// and the terms added with add_force(), in that order. Integrators and diagnostics use these.

#include <Eigen/Core>

#include "massspring/forces/force_term.hpp"
#include "massspring/forces/springs.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief f = F(x, v): the total force on every point [N] (#points by 3; f is resized if needed).
template <class System>
void total_force(const System& system, const typename System::PointsType& x,
                 const typename System::PointsType& v, typename System::PointsType& f) {
  using Scalar = typename System::Scalar;
  f.setZero(system.num_points(), 3);
  const ForceContext<Scalar> c = system.force_context(x, v);
  if (system.num_springs() > 0) Springs<Scalar>{}.add_force(c, f);
  if (system.has_spring_damping()) SpringDamping<Scalar>{}.add_force(c, f);
  for (const auto& term : system.forces()) term->add_force(c, f);
}

/// @brief Potential energy at positions x [J]: the springs' plus every term that has one.
template <class System>
typename System::Scalar potential_energy(const System& system,
                                         const typename System::PointsType& x) {
  using Scalar = typename System::Scalar;
  const ForceContext<Scalar> c = system.force_context(x, system.velocities());
  Scalar e = system.num_springs() > 0 ? Springs<Scalar>{}.energy(c) : Scalar(0);
  for (const auto& term : system.forces())
    if (term->has_energy) e += term->energy(c);
  return e;
}

/// @brief True when every force has an energy and none depends on velocity (no spring damping,
/// no drag, no term without an energy): then total energy is conserved by the exact flow.
template <class System>
bool is_conservative(const System& system) {
  if (system.has_spring_damping()) return false;
  for (const auto& term : system.forces())
    if (!term->has_energy || term->velocity_dependent) return false;
  return true;
}

/// @brief Visits dF/dx and dF/dv of every force, in a fixed order (springs, damping if any, then
/// the terms), emitting into the two sinks. Terms without a Jacobian emit nothing.
template <class System>
void add_jacobians(const System& system, const ForceContext<typename System::Scalar>& c,
                   JacobianSink<typename System::Scalar>& dfdx,
                   JacobianSink<typename System::Scalar>& dfdv) {
  using Scalar = typename System::Scalar;
  if (system.num_springs() > 0) Springs<Scalar>{}.add_dfdx(c, dfdx);
  if (system.has_spring_damping()) {
    SpringDamping<Scalar>{}.add_dfdx(c, dfdx);
    SpringDamping<Scalar>{}.add_dfdv(c, dfdv);
  }
  for (const auto& term : system.forces()) {
    if (term->has_dfdx) term->add_dfdx(c, dfdx);
    if (term->has_dfdv) term->add_dfdv(c, dfdv);
  }
}

/// @brief True when every Jacobian the system's forces emit is symmetric.
template <class System>
bool jacobians_symmetric(const System& system) {
  if (system.has_spring_damping()) return false;
  for (const auto& term : system.forces())
    if (!term->symmetric) return false;
  return true;
}

}  // namespace massspring
