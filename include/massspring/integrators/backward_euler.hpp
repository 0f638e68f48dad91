#pragma once
/// @file
/// @brief BackwardEuler: implicit Euler, linearised (one Newton step, as FOSSSim defines it) or
/// solved by Newton's method to a tolerance with a line search.

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/evaluate.hpp"
#include "massspring/integrators/detail/commit_step.hpp"
#include "massspring/integrators/detail/jacobian_assembly.hpp"
#include "massspring/integrators/step_report.hpp"
#include "massspring/storage/linear_solver.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief How BackwardEuler solves x' = x + h v', v' = v + h M^-1 F(x', v').
enum class BackwardEulerMode {
  /// One Newton step from (x + h v, v): (M - h dF/dv - h^2 dF/dx) dv = h F(x + h v, v),
  /// v' = v + dv, x' = x + h v'. Exact for linear forces; FOSSSim's "linearized implicit
  /// Euler".
  Linearized,
  /// Newton's method on the same equations, from x + h v, until the update is below the
  /// tolerance; with a backtracking line search on the incremental potential when every force
  /// has an energy (linear drag allowed), on the squared residual otherwise.
  Newton,
};

/// @brief Options of BackwardEuler; they take effect at the next step.
template <class Scalar>
struct BackwardEulerOptions {
  /// @brief Linearized or Newton (default Newton).
  BackwardEulerMode mode = BackwardEulerMode::Newton;
  /// @brief Newton: most iterations per step (>= 1). Default 20.
  int iterations = 20;
  /// @brief Newton: stop when max_i |dx_i| <= tolerance * (1 + max_i |x_i|). Default 1e-10
  /// (use about 1e-5 in float).
  Scalar tolerance = Scalar(1e-10);
  /// @brief Newton: backtracking line search (default on).
  bool line_search = true;
};

/// @brief Backward (implicit) Euler on the 3n x 3n system A = M - h dF/dv - h^2 dF/dx.
///
/// Linear solves go through the storage policy (storage/linear_solver.hpp): Cholesky, with an LDLT
/// or LU fallback when A is indefinite (compressed springs, attraction) or not symmetric (spring
/// damping off the spring axis). In Newton mode an indefinite A is replaced by its definite
/// projection (compressed springs' transverse stiffness clamped to 0) so each direction descends.
/// The pattern of A is recorded in precompute() (and again after the system's revision changes);
/// each step assembles values into it and factorizes numerically.
///
/// The system's collision handler, if any, acts on the end-of-step state before it is committed
/// (contact/collision_handler.hpp).
///
/// Pinned points sit at their targets (velocity (target - x) / h): their rows and columns are the
/// identity with a zero right-hand side.
template <class System>
class BackwardEuler {
 public:
  using Scalar = typename System::Scalar;
  using Storage = typename System::Storage;
  using PointsType = typename System::PointsType;
  using Flat = Eigen::Map<Vector<Scalar>>;

  BackwardEulerOptions<Scalar> options;

  BackwardEuler() = default;
  explicit BackwardEuler(BackwardEulerOptions<Scalar> o) : options(o) {}

  /// @brief Sets h [s] (finite, > 0), records the pattern of A and analyses it (allocates).
  void precompute(const System& system, Scalar dt) {
    detail::require_number("BackwardEuler", "dt", double(dt), true);
    dt_ = dt;
    const int n = system.num_points();
    x_.setZero(n, 3);
    v_.setZero(n, 3);
    f_.setZero(n, 3);
    r_.setZero(n, 3);
    dx_.setZero(3 * n);
    trial_.setZero(n, 3);
    f_trial_.setZero(n, 3);
    moved_.setZero(n, 3);
    trial_moved_.setZero(n, 3);
    setup(system);
    ready_ = true;
  }

  /// @brief One implicit step. A non-finite result leaves the system unchanged.
  StepReport step(System& system) {
    if (!ready_) throw Error("BackwardEuler: step() before precompute()");
    if (system.num_points() * 3 != dx_.size())
      throw Error(detail::message("BackwardEuler: the system has ", system.num_points(),
                                  " points, precompute() saw ", dx_.size() / 3,
                                  "; call precompute() again"));
    if (options.iterations < 1)
      throw Error(
          detail::message("BackwardEuler: iterations must be >= 1, got ", options.iterations));
    detail::require_number("BackwardEuler", "tolerance", double(options.tolerance), false);
    StepReport report;
    if (system.num_points() == 0) {  // nothing moves; max over an empty residual is undefined
      report.converged = true;
      report.convergence = Convergence::Converged;
      report.residual = 0;
      return report;
    }
    if (assembly_.stale(system)) {
      setup(system);
      report.refactorized = true;
    }
    const Scalar h = dt_;
    const PointsType& x0 = system.positions();
    const PointsType& v0 = system.velocities();
    const bool newton = options.mode == BackwardEulerMode::Newton;
    const bool has_potential = newton && options.line_search && potential_objective(system);

    x_ = x0 + h * v0;  // the inertial prediction: x + h v
    moved_.setZero();  // x' - (x + h v), accumulated: v' = v + moved / h keeps v exactly when
                       // nothing acts (computing (x' - x) / h would lose eps |x| / h)
    const auto& pinned = system.pinned();
    for (std::size_t r = 0; r < pinned.size(); ++r) {
      x_.row(pinned[r]) = system.pin_targets().row(Eigen::Index(r));
      moved_.row(pinned[r]) = x_.row(pinned[r]) - x0.row(pinned[r]) - h * v0.row(pinned[r]);
    }

    const int iterations = newton ? options.iterations : 1;
    for (int it = 0; it < iterations; ++it) {
      residual(system, x_, moved_, r_);
      report.residual = double(r_.cwiseAbs().maxCoeff() / (h * h));
      report.iterations = it + 1;
      if (!solve(system, newton)) {
        report.finite = false;
        return report;
      }
      Scalar alpha = 1;
      if (newton && options.line_search) alpha = line_search(system, has_potential);
      Flat(x_.data(), dx_.size()) += alpha * dx_;
      Flat(moved_.data(), dx_.size()) += alpha * dx_;
      const Scalar scale = 1 + x_.cwiseAbs().maxCoeff();
      if (newton && alpha * dx_.cwiseAbs().maxCoeff() <= options.tolerance * scale) {
        report.converged = true;
        break;
      }
    }
    // Newton tests its tolerance every iteration; the linearised step is one solve.
    report.convergence = !newton            ? Convergence::NotTested
                         : report.converged ? Convergence::Converged
                                            : Convergence::NotConverged;
    if (has_potential) report.energy = double(objective(system, x_, moved_));
    v_ = v0 + moved_ / h;
    detail::commit_step(system, x_, v_, h, report);
    return report;
  }

  /// @brief The time step [s].
  [[nodiscard]] Scalar dt() const { return dt_; }
  /// @brief The factorization the last solve used (Cholesky unless A was indefinite or not
  /// symmetric).
  [[nodiscard]] LinearSolverPath last_solver_path() const { return solver_.path(); }
  /// @brief The last assembled matrix A.
  [[nodiscard]] const auto& system_matrix() const { return assembly_.matrix(); }

 private:
  void setup(const System& system) {
    assembly_.record(system);
    solver_.analyze(assembly_.matrix());
    symmetric_ = jacobians_symmetric(system);
    drag_ = 0;
    for (const auto& term : system.forces())
      if (term->linear_damping) drag_ += term->linear_damping_coefficient();
  }

  /// @brief True when the incremental potential is an objective: every force has an energy or is
  /// linear drag.
  static bool potential_objective(const System& system) {
    if (system.has_spring_damping()) return false;
    for (const auto& term : system.forces())
      if (!term->has_energy && !term->linear_damping) return false;
    return true;
  }

  /// @brief r = h^2 F(x, v0 + moved/h) - M moved, with moved = x - x0 - h v0 kept exactly (not
  /// recomputed from x); zero on pinned rows.
  void residual(const System& system, const PointsType& x, const PointsType& moved, PointsType& r) {
    const Scalar h = dt_;
    v_ = system.velocities() + moved / h;
    total_force(system, x, v_, f_);
    r = h * h * f_ - (moved.array().colwise() * system.masses().array()).matrix();
    for (int i : system.pinned()) r.row(i).setZero();
  }

  /// @brief dx = A^-1 r at x_ (definite projection in Newton mode when A is indefinite).
  bool solve(const System& system, bool newton) {
    v_ = system.velocities() + moved_ / dt_;
    assembly_.assemble(system, x_, v_, dt_, false);
    // Newton: a failed Cholesky means A is indefinite; its definite projection is cheaper and
    // descends, where a pivoting fallback would give a direction that may not.
    const bool projectable = newton && symmetric_;
    bool ok = solver_.factorize(assembly_.matrix(), symmetric_, !projectable);
    if (projectable && !ok) {
      assembly_.assemble(system, x_, v_, dt_, true);
      ok = solver_.factorize(assembly_.matrix(), symmetric_);
    }
    if (!ok) return false;
    const Flat r(r_.data(), dx_.size());
    solver_.solve(r, dx_);
    return dx_.allFinite();
  }

  /// @brief Incremental potential 1/(2h^2) |moved|_M^2 + E(x) + beta/(2h) |x - x0|^2.
  Scalar objective(const System& system, const PointsType& x, const PointsType& moved) const {
    const Scalar h = dt_;
    const PointsType& x0 = system.positions();
    Scalar inertia = 0;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      inertia += system.masses()(i) * moved.row(i).squaredNorm();
    return inertia / (2 * h * h) + potential_energy(system, x) +
           drag_ / (2 * h) * (x - x0).squaredNorm();
  }

  /// @brief Backtracking: Armijo on the incremental potential, or decrease of |r|^2.
  Scalar line_search(const System& system, bool has_potential) {
    const Flat r(r_.data(), dx_.size());
    const Scalar slope = r.dot(dx_);  // -h^2 times the directional derivative of the objective
    const Scalar f0 = has_potential ? objective(system, x_, moved_) : r.squaredNorm();
    Scalar alpha = 1;
    for (int k = 0; k < 40; ++k, alpha /= 2) {
      trial_ = x_;
      Flat(trial_.data(), dx_.size()) += alpha * dx_;
      trial_moved_ = moved_;
      Flat(trial_moved_.data(), dx_.size()) += alpha * dx_;
      Scalar f1;
      if (has_potential) {
        f1 = objective(system, trial_, trial_moved_);
        if (f1 <= f0 - Scalar(1e-4) * alpha * slope / (dt_ * dt_)) return alpha;
        // Near the solution the objective's rounding (~eps |E|) hides the decrease: accept a
        // full step whose change is within that rounding.
        if (k == 0 && std::abs(f1 - f0) <= 100 * std::numeric_limits<Scalar>::epsilon() *
                                               (std::abs(f0) + std::abs(f1)))
          return alpha;
      } else {
        residual(system, trial_, trial_moved_, f_trial_);
        f1 = f_trial_.squaredNorm();
        if (f1 < f0 || f0 == 0) return alpha;
      }
    }
    return alpha;
  }

  Scalar dt_ = 0;
  bool ready_ = false, symmetric_ = true;
  Scalar drag_ = 0;
  PointsType x_, v_, f_, r_, trial_, f_trial_, moved_, trial_moved_;
  Vector<Scalar> dx_;
  detail::JacobianAssembly<System> assembly_;
  LinearSolver<Storage, Scalar> solver_;
};

}  // namespace massspring
