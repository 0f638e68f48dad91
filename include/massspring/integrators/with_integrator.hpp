#pragma once
/// @file
/// @brief with_integrator(): builds the integrator an IntegratorKind names and hands it to a
/// generic callable (the one switch over the integrators that programs choosing one by name use).

#include <string>
#include <utility>

#include "massspring/error.hpp"
#include "massspring/integrators/backward_euler.hpp"
#include "massspring/integrators/fast_mass_spring.hpp"
#include "massspring/integrators/forward_euler.hpp"
#include "massspring/integrators/integrator_kind.hpp"
#include "massspring/integrators/rk4.hpp"
#include "massspring/integrators/symplectic_euler.hpp"

namespace massspring {

/// @brief Calls `f(integrator)` with a default-constructed integrator of `kind` for System
/// (BackwardEuler with options.mode set to the kind's mode; every other option at its default),
/// and returns what f returns. f is instantiated for every integrator, so each call must return
/// the same type; it may change the options before precompute().
/// @param[in] kind which integrator
/// @param[in] f    a generic callable, e.g. `[&](auto& integrator) { ... }`
/// @throws Error when `kind` is not one of IntegratorKind's values.
template <class System, class F>
decltype(auto) with_integrator(IntegratorKind kind, F&& f) {
  // the integrator as an lvalue, so that f may set its options
  auto call = [&f](auto integrator) -> decltype(auto) { return std::forward<F>(f)(integrator); };
  switch (kind) {
    case IntegratorKind::ForwardEuler:
      return call(ForwardEuler<System>());
    case IntegratorKind::SymplecticEuler:
      return call(SymplecticEuler<System>());
    case IntegratorKind::BackwardEuler:
    case IntegratorKind::LinearizedBackwardEuler: {
      BackwardEulerOptions<typename System::Scalar> options;
      options.mode = kind == IntegratorKind::BackwardEuler ? BackwardEulerMode::Newton
                                                           : BackwardEulerMode::Linearized;
      return call(BackwardEuler<System>(options));
    }
    case IntegratorKind::FastMassSpring:
      return call(FastMassSpring<System>());
    case IntegratorKind::RK4:
      return call(RK4<System>());
  }
  throw Error("with_integrator: IntegratorKind " + std::to_string(int(kind)) +
              " is not one of the integrators");
}

}  // namespace massspring
