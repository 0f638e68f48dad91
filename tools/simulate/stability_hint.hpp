#pragma once
// massspring-simulate's hint after an explicit integrator diverged: the time step
// stable_time_step() (diagnostics/stable_time_step.hpp) gives for the scene, computed at the run's
// first state, before the first step.

#include <cmath>
#include <cstdio>
#include <massspring/diagnostics/stable_time_step.hpp>
#include <massspring/integrators/integrator_kind.hpp>
#include <optional>
#include <string>

namespace simulate {

/// x rounded down to 3 significant digits, as text ("0.00123"): a step at most the one computed.
inline std::string three_digits_down(double x) {
  if (!(x > 0) || !std::isfinite(x)) return std::to_string(x);
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 2);
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", std::floor(x / unit) * unit);
  return text;
}

/// The stable steps of an explicit run, computed before its first step.
struct StabilityHint {
  massspring::IntegratorKind kind = massspring::IntegratorKind::FastMassSpring;
  std::optional<double> stable;             // stable_time_step() for the run's integrator [s]
  std::optional<double> stable_symplectic;  // and for symplectic Euler [s]

  /// Computes them for forward and symplectic Euler and RK4 (nothing for implicit integrators, or
  /// when the bound is not finite).
  template <class System>
  static StabilityHint at(massspring::IntegratorKind kind, const System& system) {
    using massspring::ExplicitMethod;
    using massspring::IntegratorKind;
    StabilityHint h;
    h.kind = kind;
    auto method = [&]() -> std::optional<ExplicitMethod> {
      switch (kind) {
        case IntegratorKind::ForwardEuler:
          return ExplicitMethod::ForwardEuler;
        case IntegratorKind::SymplecticEuler:
          return ExplicitMethod::SymplecticEuler;
        case IntegratorKind::RK4:
          return ExplicitMethod::RK4;
        default:
          return std::nullopt;
      }
    }();
    if (!method) return h;
    try {
      h.stable = massspring::stable_time_step(system, *method);
      h.stable_symplectic = massspring::stable_time_step(system, ExplicitMethod::SymplecticEuler);
    } catch (const massspring::Error&) {  // a non-finite bound: no hint
      h.stable.reset();
      h.stable_symplectic.reset();
    }
    return h;
  }

  /// The hint for a run at step `dt` [s] that diverged, or "" (an implicit integrator).
  [[nodiscard]] std::string text(double dt, const std::string& integrator) const {
    if (!stable || !stable_symplectic) return "";
    const std::string implicit =
        "an implicit integrator (--integrator backward-euler or "
        "fast-mass-spring) is stable at any --dt";
    if (*stable == 0)
      return "hint: " + integrator +
             " is unstable at every --dt on this scene (springs without linear drag); "
             "symplectic-euler is stable at --dt " +
             three_digits_down(*stable_symplectic) +
             " (stable_time_step() at the first state), or " + implicit;
    if (!std::isfinite(*stable)) return "";
    const std::string step = three_digits_down(*stable);
    if (dt > *stable)
      return "hint: --dt " + massspring::detail::message(dt) + " is above the step " + integrator +
             " is stable at on this scene: stable_time_step() gives " + step +
             " s at the first state; try --dt " + step + ", or " + implicit;
    return "hint: --dt " + massspring::detail::message(dt) +
           " is below the step stable_time_step() gives at the first state (" + step +
           " s), but the motion moved the limit (docs/stability.md): try a smaller --dt, or " +
           implicit;
  }
};

}  // namespace simulate
