#pragma once
/// @file
/// @brief DivergenceGuard: steps any integrator and reports an energy blow-up, restoring the last
/// good state.

#include <cmath>
#include <limits>

#include "massspring/detail/validate.hpp"
#include "massspring/diagnostics/energy.hpp"
#include "massspring/error.hpp"
#include "massspring/integrators/detail/energy_bound.hpp"
#include "massspring/integrators/step_report.hpp"

namespace massspring {

/// @brief Parameters of DivergenceGuard.
struct DivergenceOptions {
  /// @brief A step blows up when the total energy exceeds E(0) + growth * S (S: the guard's
  /// energy scale, see DivergenceGuard). Finite and > 0; default 100.
  double growth = 100;
};

/// @brief Wraps the steps of any integrator: a step whose result is not finite, or whose total
/// energy (kinetic plus potential, diagnostics/energy.hpp) exceeds a limit, is reported
/// (`report.finite` false or `report.blew_up` true) and the state before the step is restored,
/// so the system always holds the last good state.
///
/// The limit is E(0) + growth * S, where E(0) is the total energy when the guard was made and S
/// an energy scale of the scene, also taken then:
///
///     S = |E(0)| + K(0) + sum_e k_e l0_e^2 / 2 + D sum_i |F_i(x0, v0)|
///
/// (K the kinetic energy, the springs' energy when stretched to twice their rest length, and the
/// work the initial forces do over D, the diagonal of the initial bounding box). A motion that
/// stays bounded by the scene's own size cannot release that much energy; an explicit step past its
/// stability limit passes it within a few dozen steps, as the energy grows geometrically.
///
/// Cost per step: one copy of x and v, and one evaluation of the energy (about one pass over the
/// springs). Allocates nothing in step().
template <class System>
class DivergenceGuard {
 public:
  using Scalar = typename System::Scalar;
  using PointsType = typename System::PointsType;

  /// @brief Takes E(0) and S from the system's current state.
  /// @throws Error when growth is not finite and > 0, or the state's energy is not finite.
  explicit DivergenceGuard(const System& system, DivergenceOptions options = {})
      : options_(options) {
    detail::require_number("DivergenceGuard", "growth", options.growth, true);
    const int n = system.num_points();
    const double scale = detail::energy_scale(system, energy0_);
    if (!std::isfinite(energy0_) || !std::isfinite(scale))
      throw Error(detail::message("DivergenceGuard: the initial energy (", energy0_,
                                  ") or its scale (", scale, ") is not finite"));
    scale_ = scale;
    limit_ = energy0_ + options.growth * scale;
    energy_ = energy0_;
    x_.resize(n, 3);
    v_.resize(n, 3);
  }

  /// @brief One step of `integrator`, checked. When the step is not finite (the integrator left
  /// the state unchanged) or the new total energy exceeds limit(), the state before the step is
  /// restored (the colliders' poses too) and the report says so (`finite` false or `blew_up`
  /// true).
  template <class Integrator>
  StepReport step(Integrator& integrator, System& system) {
    if (system.num_points() != x_.rows())
      throw Error(detail::message("DivergenceGuard: the system has ", system.num_points(),
                                  " points, the guard was made for ", x_.rows()));
    x_ = system.positions();
    v_ = system.velocities();
    StepReport report = integrator.step(system);
    if (!report.finite) return report;
    const double e = double(total_energy(system));
    if (!(e <= limit_)) {  // NaN included
      system.positions() = x_;
      system.velocities() = v_;
      system.colliders().undo_step();  // the step moved them when it committed
      report.blew_up = true;
      report.finite = std::isfinite(e);
      return report;
    }
    energy_ = e;
    return report;
  }

  /// @brief E(0) [J].
  [[nodiscard]] double initial_energy() const { return energy0_; }
  /// @brief The scale S [J].
  [[nodiscard]] double scale() const { return scale_; }
  /// @brief The energy above which a step blows up, E(0) + growth S [J].
  [[nodiscard]] double limit() const { return limit_; }
  /// @brief Total energy after the last accepted step (E(0) before any) [J].
  [[nodiscard]] double energy() const { return energy_; }

 private:
  DivergenceOptions options_;
  double energy0_ = 0, scale_ = 0, limit_ = 0, energy_ = 0;
  PointsType x_, v_;
};

}  // namespace massspring
