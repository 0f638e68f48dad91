#pragma once
/// @file
/// @brief RK4: the classical fourth-order Runge-Kutta method on (x, v).

#include "massspring/integrators/detail/explicit_euler.hpp"

namespace massspring {

/// @brief The classical Runge-Kutta method of order 4 on the first-order system x' = v,
/// v' = M^-1 F(x, v): four force evaluations per step, global error O(h^4).
///
/// Explicit: stable for springs while h |lambda| stays inside its stability region (up to
/// h omega = 2 sqrt 2 on an undamped spring; stable_time_step() gives a safe bound). Inside it
/// the method loses a little energy per step, (h omega)^6 / 72 relatively, so it neither spirals
/// out like ForwardEuler nor needs a solve like BackwardEuler. The library uses it for reference
/// solutions (diagnostics/reference_solution.hpp); it is also a good choice on its own when
/// accuracy matters more than stiffness.
///
/// Pinned points stay at their targets in every stage (velocity and acceleration zero). The
/// system's collision handler, if any, acts on the end-of-step state. step()
/// allocates nothing; a non-finite result leaves the system unchanged.
template <class System>
class RK4 {
 public:
  using Scalar = typename System::Scalar;
  using PointsType = typename System::PointsType;

  /// @brief Sets the time step h [s] (finite, > 0) and sizes the work arrays for the system.
  void precompute(const System& system, Scalar dt) {
    s_.precompute(system, dt, "RK4");
    const int n = system.num_points();
    xs_.setZero(n, 3);
    vs_.setZero(n, 3);
    a_.setZero(n, 3);
  }

  /// @brief One step; a non-finite result leaves the system unchanged (report.finite false).
  StepReport step(System& system) {
    s_.check(system, "RK4");
    const Scalar h = s_.dt_;
    const PointsType& x = system.positions();
    const PointsType& v = system.velocities();
    // s_.x_ and s_.v_ accumulate the weighted sums of the stage derivatives (k1 + 2 k2 + 2 k3
    // + k4); xs_, vs_ hold the state each stage is evaluated at.
    // Stage 1 at (x, v).
    acceleration(system, x, v);
    s_.x_ = v;
    s_.v_ = a_;
    // Stage 2 at (x + h/2 v, v + h/2 a1).
    xs_ = x + (h / 2) * v;
    vs_ = v + (h / 2) * a_;
    stage(system, 2);
    // Stage 3 at (x + h/2 v2, v + h/2 a2): v2 is vs_, a2 is a_.
    xs_ = x + (h / 2) * vs_;
    vs_ = v + (h / 2) * a_;
    stage(system, 2);
    // Stage 4 at (x + h v3, v + h a3).
    xs_ = x + h * vs_;
    vs_ = v + h * a_;
    stage(system, 1);
    s_.x_ = x + (h / 6) * s_.x_;
    s_.v_ = v + (h / 6) * s_.v_;
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
  void set_energy_growth(double growth) { s_.set_energy_growth(growth, "RK4"); }

 private:
  /// @brief a_ = M^-1 F(x, v), zero at pinned points.
  template <class X, class V>
  void acceleration(const System& system, const X& x, const V& v) {
    total_force(system, x, v, s_.f_);
    for (int i = 0; i < s_.n_; ++i) a_.row(i) = s_.inverse_mass_(i) * s_.f_.row(i);
    for (const int i : system.pinned()) a_.row(i).setZero();
  }

  /// @brief Evaluates the stage at (xs_, vs_) (pinned points held at their targets, at rest) and
  /// adds weight * (vs_, a_) to the sums.
  void stage(const System& system, int weight) {
    const auto& pinned = system.pinned();
    for (std::size_t r = 0; r < pinned.size(); ++r) {
      xs_.row(pinned[r]) = system.pin_targets().row(Eigen::Index(r));
      vs_.row(pinned[r]).setZero();
    }
    acceleration(system, xs_, vs_);
    s_.x_ += Scalar(weight) * vs_;
    s_.v_ += Scalar(weight) * a_;
  }

  detail::ExplicitStepper<System> s_;
  PointsType xs_, vs_, a_;
};

}  // namespace massspring
