#pragma once
/// @file
/// @brief The shared machinery of ForwardEuler and SymplecticEuler.

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

}  // namespace massspring::detail
