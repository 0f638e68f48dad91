#pragma once
/// @file
/// @brief The shared machinery of the explicit integrators (ForwardEuler, SymplecticEuler, RK4):
/// ExplicitStepper, their work arrays and commit; ExplicitEuler, the two Euler schemes but for
/// their update.

#include <Eigen/Core>
#include <cmath>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/evaluate.hpp"
#include "massspring/integrators/detail/commit_step.hpp"
#include "massspring/integrators/detail/energy_bound.hpp"
#include "massspring/integrators/step_report.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "massspring/types.hpp"

namespace massspring::detail {

/// @brief Holds the work arrays of an explicit step and commits its result.
template <class System>
class ExplicitStepper {
 public:
  using Scalar = typename System::Scalar;
  using PointsType = typename System::PointsType;

  void precompute(const System& system, Scalar dt, const char* who) {
    require_number(who, "dt", double(dt), true);
    dt_ = dt;
    n_ = system.num_points();
    x_.setZero(n_, 3);
    v_.setZero(n_, 3);
    f_.setZero(n_, 3);
    inverse_mass_ = system.masses().cwiseInverse();
    revision_ = system.revision();
    bound_.reset(system, energy_growth_);
    ready_ = true;
  }

  /// @brief The energy bound's growth factor (energy_bound.hpp): finite and >= 0, 0 turns the
  /// check off. Takes effect at the next precompute().
  void set_energy_growth(double growth, const char* who) {
    require_number(who, "energy_growth", growth, false);
    energy_growth_ = growth;
  }

  void check(const System& system, const char* who) {
    if (!ready_) throw Error(message(who, ": step() before precompute()"));
    if (system.num_points() != n_)
      throw Error(message(who, ": the system has ", system.num_points(),
                          " points, precompute() saw ", n_, "; call precompute() again"));
    if (system.revision() != revision_) {
      inverse_mass_ = system.masses().cwiseInverse();  // same size: no allocation
      revision_ = system.revision();
    }
  }

  /// @brief v_ = v + h M^-1 f_, row by row.
  void kick(const PointsType& v) {
    for (int i = 0; i < n_; ++i) v_.row(i) = v.row(i) + (dt_ * inverse_mass_(i)) * f_.row(i);
  }

  /// @brief Ends the step (commit_step.hpp): x_ and v_ hold the candidate state. With
  /// swap_buffers_ they are swapped into the system, else copied.
  StepReport commit(System& system) {
    StepReport report;
    commit_step(system, x_, v_, dt_, report, bound_, true, swap_buffers_);
    return report;
  }

  Scalar dt_ = 0;
  int n_ = 0;
  bool ready_ = false;
  bool swap_buffers_ = true;
  std::uint64_t revision_ = 0;
  double energy_growth_ = 0;  // off: see set_energy_growth()
  EnergyBound<System> bound_;
  PointsType x_, v_, f_;
  Vector<Scalar> inverse_mass_;
};

/// @brief The order of an explicit Euler step's two updates.
enum class EulerOrder {
  PositionsFirst,   ///< forward: x' = x + h v, v' = v + h M^-1 F(x, v)
  VelocitiesFirst,  ///< symplectic: v' = v + h M^-1 F(x, v), then x' = x + h v'
};

/// @brief ForwardEuler (EulerOrder::PositionsFirst) and SymplecticEuler (VelocitiesFirst), whose
/// members these are.
template <class System, EulerOrder order>
class ExplicitEuler {
 public:
  using Scalar = typename System::Scalar;

  /// @brief Sets the time step h [s] (finite, > 0) and sizes the work arrays for the system.
  void precompute(const System& system, Scalar dt) { s_.precompute(system, dt, kName); }

  /// @brief One step; a non-finite result leaves the system unchanged (report.finite false).
  StepReport step(System& system) {
    s_.check(system, kName);
    const auto& x = system.positions();
    const auto& v = system.velocities();
    total_force(system, x, v, s_.f_);
    if constexpr (order == EulerOrder::PositionsFirst) {
      s_.x_ = x + s_.dt_ * v;
      s_.kick(v);
    } else {
      s_.kick(v);
      s_.x_ = x + s_.dt_ * s_.v_;
    }
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
  void set_energy_growth(double growth) { s_.set_energy_growth(growth, kName); }

 private:
  static constexpr const char* kName =
      order == EulerOrder::PositionsFirst ? "ForwardEuler" : "SymplecticEuler";
  ExplicitStepper<System> s_;
};

}  // namespace massspring::detail
