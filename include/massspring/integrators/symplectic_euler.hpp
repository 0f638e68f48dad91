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
template <class System>
class SymplecticEuler {
 public:
  using Scalar = typename System::Scalar;

  /// @brief Sets the time step h [s] (finite, > 0) and sizes the work arrays for the system.
  void precompute(const System& system, Scalar dt) { s_.precompute(system, dt, "SymplecticEuler"); }

  /// @brief One step; a non-finite result leaves the system unchanged (report.finite false).
  StepReport step(System& system) {
    s_.check(system, "SymplecticEuler");
    const auto& x = system.positions();
    const auto& v = system.velocities();
    total_force(system, x, v, s_.f_);
    s_.kick(v);
    s_.x_ = x + s_.dt_ * s_.v_;
    return s_.commit(system);
  }

  /// @brief The time step [s].
  [[nodiscard]] Scalar dt() const { return s_.dt_; }

  /// @brief How step() hands its end state to the system: true (the default) swaps its work
  /// arrays with the system's positions and velocities (no copy; those arrays change memory);
  /// false copies into them (they keep their memory, so views of them stay valid, e.g. the
  /// Python module's numpy arrays). The values are the same either way.
  void set_swap_buffers(bool swap) { s_.swap_buffers_ = swap; }

  /// @brief A step whose end state's energy (kinetic of the free points plus potential) exceeds
  /// the step's start energy by more than growth (S + S_c), S the scale taken at precompute() and
  /// S_c the colliders' (integrators/detail/energy_bound.hpp), is
  /// reported as blown up (StepReport::blew_up) and not committed. growth finite and >= 0;
  /// default 0: off, as an explicit scheme past its stable step is expected to gain energy (wrap
  /// the steps in a DivergenceGuard, as massspring-simulate does, or set 100, the implicit
  /// integrators' default). Takes effect at the next precompute().
  void set_energy_growth(double growth) { s_.set_energy_growth(growth, "SymplecticEuler"); }

 private:
  detail::ExplicitStepper<System> s_;
};

}  // namespace massspring
