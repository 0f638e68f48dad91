#pragma once
/// @file
/// @brief ForwardEuler: explicit Euler, x' = x + h v, v' = v + h M^-1 F(x, v).

#include "massspring/integrators/detail/explicit_euler.hpp"

namespace massspring {

/// @brief Explicit (forward) Euler. First order; unstable for stiff springs beyond
/// h ~ 2 / omega_max, and it adds energy to orbits and oscillators at every step.
///
/// Pinned points sit at their targets (velocity (target - x) / h). The system's collision handler,
/// if any, acts on the end-of-step state (contact/collision_handler.hpp). step() allocates nothing.
/// The members (precompute(), step(), dt(), set_swap_buffers(), set_energy_growth()) are
/// detail::ExplicitEuler's (integrators/detail/explicit_euler.hpp); its energy bound is off by
/// default.
/// @tparam System a MassSpringSystem<Scalar, Storage> (the storage is not used: no matrices)
template <class System>
class ForwardEuler : public detail::ExplicitEuler<System, detail::EulerOrder::PositionsFirst> {};

}  // namespace massspring
