#pragma once
/// @file
/// @brief SymplecticEuler: v' = v + h M^-1 F(x, v), then x' = x + h v'.

#include "massspring/integrators/detail/explicit_euler.hpp"

namespace massspring {

/// @brief Symplectic (semi-implicit) Euler: velocities first, then positions with the new
/// velocities. First order, explicit (same stability limit as ForwardEuler for springs), but for
/// conservative forces it keeps the energy bounded instead of letting it grow: orbits stay
/// closed.
///
/// Pinned points sit at their targets (velocity (target - x) / h). The system's collision handler,
/// if any, acts on the end-of-step state (contact/collision_handler.hpp). step() allocates nothing.
/// The members (precompute(), step(), dt(), set_swap_buffers(), set_energy_growth()) are
/// detail::ExplicitEuler's (integrators/detail/explicit_euler.hpp); its energy bound is off by
/// default.
/// @tparam System a MassSpringSystem<Scalar, Storage> (the storage is not used: no matrices)
template <class System>
class SymplecticEuler : public detail::ExplicitEuler<System, detail::EulerOrder::VelocitiesFirst> {
};

}  // namespace massspring
