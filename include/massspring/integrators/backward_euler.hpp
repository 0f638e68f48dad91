#pragma once
/// @file
/// @brief BackwardEuler: implicit Euler, linearised (one Newton step, as FOSSSim defines it) or
/// solved by Newton's method to a tolerance with a line search.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/evaluate.hpp"
#include "massspring/integrators/detail/commit_step.hpp"
#include "massspring/integrators/detail/contact_dual.hpp"
#include "massspring/integrators/detail/energy_bound.hpp"
#include "massspring/integrators/detail/jacobian_assembly.hpp"
#include "massspring/integrators/detail/self_contact_term.hpp"
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
  /// @brief Weight alpha of contact inside the solve (dimensionless, finite, >= 0). Default 1, as
  /// FastMassSpring's (docs/contact.md, "Defaults"). 0: contact and friction are only the
  /// end-of-step response every integrator applies, which alone keeps the colliders'
  /// restitution (the term is inelastic). alpha > 0, for a system with colliders: each point that
  /// touches a
  /// collider gets the weight w_i = alpha sqrt(m_i (m_i + h^2 k_i)) [kg] (k_i the summed stiffness
  /// of its springs) on A's diagonal and the term w_i / (2 h^2) |x_i - (z_i - u_i)|^2 in the
  /// incremental potential, with z_i = P(x_i + u_i)
  /// its projection out of the colliders (normal push and Coulomb friction on the displacement
  /// over the step) and u_i its scaled dual variable, updated at every iterate and kept from step
  /// to step (the ADMM term of FastMassSpring: local_global/contact_projection.hpp). Converged,
  /// the step is implicit Euler with Signorini's condition and Coulomb's law; alpha sets how fast
  /// the dual converges, not where. With the system's self-collision on (and a surface), the
  /// term also keeps the surface's close pairs apart, P = P_colliders o P_self
  /// (detail/self_contact_term.hpp: point-triangle and edge-edge pairs, gathered at the step's
  /// start and again when an iterate outgrows them), on every point such a pair moves; the
  /// end-of-step surface pass stays the guarantee of no crossing. Newton's convergence then also
  /// asks ADMM's residuals, max_i |x_i - z_i| and the change of z_i over the iteration, divided by
  /// 1 - q (q the ratio of successive residuals: the distance to the limit of a linear rate), to be
  /// <= tolerance (1 + max |x|); Linearized solves its linear model with the term `iterations`
  /// times at most, to the same test.
  Scalar contact_weight = Scalar(1);
  /// @brief A step whose end state's energy (kinetic of the free points plus potential) exceeds
  /// the step's start energy by more than energy_growth (S + S_c), S the scale taken at
  /// precompute() and S_c the colliders' (integrators/detail/energy_bound.hpp), is reported as
  /// blown up (StepReport::blew_up) and not committed. So is a Linearized step without the
  /// contact term that ends with its incremental potential higher than at x + h v by more than
  /// 1e-6 S (EnergyBound::uphill(): its one linear solve went uphill). Finite and >= 0; default
  /// 100; 0 turns both checks off. Costs two passes over the springs per step (two more for a
  /// Linearized step).
  double energy_growth = 100;
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
/// (contact/collision_handler.hpp); with options.contact_weight > 0 the colliders' contact and
/// friction are inside the solve, and the end-of-step response only guarantees the normal push.
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
    dual_.setZero(n, 3);
    weight_.setZero(n);
    new_weight_.setZero(n);
    target_.setZero(n, 3);
    start_.setZero(n, 3);
    start_moved_.setZero(n, 3);
    rhs_.setZero(n, 3);
    touches_.assign(std::size_t(n), 0);
    edge_distance_.setZero(n);
    correction_.setZero(n, 3);
    probe_.setZero(n, 3);
    setup(system);
    detail::require_number("BackwardEuler", "energy_growth", options.energy_growth, false);
    energy_bound_.reset(system, options.energy_growth);
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
    detail::require_number("BackwardEuler", "contact_weight", double(options.contact_weight),
                           false);
    detail::require_number("BackwardEuler", "energy_growth", options.energy_growth, false);
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
    } else if (self_contact_.stale(system)) {
      self_contact_.build(system);  // self-collision or the surface changed: allocates
    }
    const Scalar h = dt_;
    const PointsType& x0 = system.positions();
    const PointsType& v0 = system.velocities();
    const bool newton = options.mode == BackwardEulerMode::Newton;
    const bool has_potential = newton && options.line_search && potential_objective(system);
    const bool self_contact =
        options.contact_weight > 0 && self_contact_.built() && system.self_collision().has_value();
    contact_ = options.contact_weight > 0 && (!system.colliders().empty() || self_contact);
    if (contact_) {
      system.colliders().begin_step(h);
      contact_weights(system);
      detail::edge_distances(system, edge_distance_);  // sized in precompute(): no allocation
    }

    x_ = x0 + h * v0;  // the inertial prediction: x + h v
    moved_.setZero();  // x' - (x + h v), accumulated: v' = v + moved / h keeps v exactly when
                       // nothing acts (computing (x' - x) / h would lose eps |x| / h)
    const auto& pinned = system.pinned();
    for (std::size_t r = 0; r < pinned.size(); ++r) {
      x_.row(pinned[r]) = system.pin_targets().row(Eigen::Index(r));
      moved_.row(pinned[r]) = x_.row(pinned[r]) - x0.row(pinned[r]) - h * v0.row(pinned[r]);
    }
    if (contact_ && !newton) {
      start_ = x_;
      start_moved_ = moved_;
    }
    self_active_ = self_contact;
    if (self_active_) self_contact_.prepare(system, x_.data());

    // The linearised step with contact keeps its linear model: A and r at x + h v, the term's
    // targets updated at each iterate, x = x + h v + (A + W)^-1 (r + W (target - x - h v)).
    const int iterations = newton || contact_ ? options.iterations : 1;
    // The linearised step without the contact term is one Newton step on the incremental
    // potential phi from x + h v: when it ends with phi higher than there, its linear model
    // failed; reported as a blow-up (EnergyBound::uphill()), nothing changed. Not evaluated
    // when the bound is off.
    const bool check_model =
        energy_bound_.on() && !newton && !contact_ && potential_objective(system);
    const double phi_guess = check_model ? double(objective(system, x_, moved_)) : 0.0;
    Scalar last_contact_residual = 0;
    for (int it = 0; it < iterations; ++it) {
      // ADMM converges linearly: with q the ratio of successive residuals, the iterate is within
      // about residual / (1 - q) of the limit, which the tolerance test takes (infinite while the
      // residual does not shrink).
      Scalar contact_error = 0;
      if (contact_) {
        const Scalar residual = update_contact(system);
        const Scalar q =
            it > 0 && last_contact_residual > 0 ? residual / last_contact_residual : Scalar(0);
        contact_error = q < 1 ? residual / (1 - q) : std::numeric_limits<Scalar>::infinity();
        last_contact_residual = residual;
      }
      if (newton || it == 0) {
        residual(system, x_, moved_, r_, newton);
        report.residual = double(r_.cwiseAbs().maxCoeff() / (h * h));
      }
      report.iterations = it + 1;
      const bool solved = newton ? solve(system, true, x_, moved_, r_) : solve_linearized(system);
      if (!solved) {
        report.finite = false;
        return report;
      }
      Scalar alpha = 1;
      if (newton && options.line_search) alpha = line_search(system, has_potential);
      Flat(x_.data(), dx_.size()) += alpha * dx_;
      Flat(moved_.data(), dx_.size()) += alpha * dx_;
      const Scalar scale = 1 + x_.cwiseAbs().maxCoeff();
      if ((newton || contact_) && alpha * dx_.cwiseAbs().maxCoeff() <= options.tolerance * scale &&
          contact_error <= options.tolerance * scale) {
        report.converged = true;
        break;
      }
    }
    // Newton and the contact iteration test their tolerance every iteration; the linearised step
    // without contact is one solve.
    report.convergence = !newton && !contact_ ? Convergence::NotTested
                         : report.converged   ? Convergence::Converged
                                              : Convergence::NotConverged;
    if (has_potential) report.energy = double(objective(system, x_, moved_));
    if (check_model && energy_bound_.uphill(phi_guess, double(objective(system, x_, moved_)))) {
      report.blew_up = true;
      return report;
    }
    v_ = v0 + moved_ / h;
    // Friction was the contact term's, inside the solve: not applied a second time.
    detail::commit_step(system, x_, v_, h, report, energy_bound_, !contact_);
    return report;
  }

  /// @brief The time step [s].
  [[nodiscard]] Scalar dt() const { return dt_; }

  /// @brief The contact term's scaled dual variables u [m] (options.contact_weight), one row per
  /// point, zero where no collider acts; the contact force on point i is -w_i u_i / h^2
  /// [N]. Kept from step to step, so a run continued by another solver through
  /// set_contact_duals() continues bit for bit. Zero after precompute().
  [[nodiscard]] const PointsType& contact_duals() const { return dual_; }
  /// @brief Sets the dual variables, taken at the current options.contact_weight (after
  /// precompute()). Throws Error, changing nothing, before precompute(), for a wrong row count,
  /// a value that is not finite, or a pinned point's row that is not zero.
  void set_contact_duals(const PointsType& u) {
    if (!ready_) throw Error("BackwardEuler: set_contact_duals() before precompute()");
    detail::require_rows("BackwardEuler::set_contact_duals", u.rows(), dual_.rows(), "point");
    detail::require_finite_rows("point", "contact dual", u);
    const auto& pinned = assembly_.pinned_coordinates();
    for (Eigen::Index i = 0; i < u.rows(); ++i)
      if (pinned[std::size_t(3 * i)] && !u.row(i).isZero(0))
        throw Error(detail::message("BackwardEuler: set_contact_duals: row ", i,
                                    " is not zero, but point ", i, " is pinned"));
    dual_ = u;
    weight_.setZero();  // the next step's weights are the ones u was taken at
  }
  /// @brief The factorization the last solve used (Cholesky unless A was indefinite or not
  /// symmetric).
  [[nodiscard]] LinearSolverPath last_solver_path() const { return solver_.path(); }
  /// @brief The last assembled matrix A.
  [[nodiscard]] const auto& system_matrix() const { return assembly_.matrix(); }

 private:
  void setup(const System& system) {
    assembly_.record(system);
    self_contact_.build(system);  // off without self-collision on a surface
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
  /// recomputed from x); zero on pinned rows. With `with_contact` (and the term on), plus
  /// w_i (target_i - x_i) on the points that touch.
  void residual(const System& system, const PointsType& x, const PointsType& moved, PointsType& r,
                bool with_contact = true) {
    const Scalar h = dt_;
    v_ = system.velocities() + moved / h;
    total_force(system, x, v_, f_);
    r = h * h * f_ - (moved.array().colwise() * system.masses().array()).matrix();
    for (int i : system.pinned()) r.row(i).setZero();
    if (contact_ && with_contact)
      for (Eigen::Index i = 0; i < x.rows(); ++i)
        if (touches_[std::size_t(i)]) r.row(i) += weight_(i) * (target_.row(i) - x.row(i));
  }

  /// @brief dx = (A + W)^-1 rhs with A at (x, moved), W the contact term's weights on the points
  /// that touch (definite projection in Newton mode when A is indefinite).
  bool solve(const System& system, bool newton, const PointsType& x, const PointsType& moved,
             PointsType& rhs) {
    v_ = system.velocities() + moved / dt_;
    assembly_.assemble(system, x, v_, dt_, false);
    add_contact_weights();
    // Newton: a failed Cholesky means A is indefinite; its definite projection is cheaper and
    // descends, where a pivoting fallback would give a direction that may not.
    const bool projectable = newton && symmetric_;
    bool ok = solver_.factorize(assembly_.matrix(), symmetric_, !projectable);
    if (projectable && !ok) {
      assembly_.assemble(system, x, v_, dt_, true);
      add_contact_weights();
      ok = solver_.factorize(assembly_.matrix(), symmetric_);
    }
    if (!ok) return false;
    const Flat r(rhs.data(), dx_.size());
    solver_.solve(r, dx_);
    return dx_.allFinite();
  }

  /// @brief The linearised step's contact iteration: x + h v + (A + W)^-1 (r + W (target - x -
  /// h v)), A and r at x + h v (r_ without the term), as the update dx from x_.
  bool solve_linearized(const System& system) {
    if (!contact_) return solve(system, false, x_, moved_, r_);
    rhs_ = r_;
    for (Eigen::Index i = 0; i < x_.rows(); ++i)
      if (touches_[std::size_t(i)]) rhs_.row(i) += weight_(i) * (target_.row(i) - start_.row(i));
    if (!solve(system, false, start_, start_moved_, rhs_)) return false;
    Flat(dx_.data(), dx_.size()) += Flat(start_.data(), dx_.size()) - Flat(x_.data(), dx_.size());
    return true;
  }

  /// @brief This step's weights (detail::contact_weights) into weight_. The scaled duals
  /// u = lambda / w are rescaled where a weight changed, so the forces lambda carry over.
  void contact_weights(const System& system) {
    detail::contact_weights(system, options.contact_weight, dt_ * dt_, new_weight_);
    for (Eigen::Index i = 0; i < new_weight_.size(); ++i) {
      const Scalar w = new_weight_(i);
      if (weight_(i) > 0 && weight_(i) != w) dual_.row(i) *= weight_(i) / w;
      weight_(i) = w;
    }
  }

  /// @brief W on A's diagonal: w_i on the three rows of each point that touches.
  void add_contact_weights() {
    if (!contact_) return;
    for (std::size_t i = 0; i < touches_.size(); ++i)
      if (touches_[i]) assembly_.add_to_diagonal(int(i), weight_(Eigen::Index(i)));
  }

  /// @brief The contact term's local step at x_ for every point not pinned
  /// (detail::contact_dual_update): targets, touches_ and the dual variables. Returns the larger
  /// of ADMM's primal and dual residuals (Boyd et al. 2011, section 3.3) in position:
  /// max_i |x_i - z_i| (the change of u_i) and max_i |z_i - z_i'|, z_i' the last iterate's.
  Scalar update_contact(const System& system) {
    const auto& pinned = assembly_.pinned_coordinates();
    const Scalar* x0 = system.positions().data();
    Scalar residual = 0;
    // Self-contact's corrections at x + u, its pairs gathered again from there when x + u has
    // left the motion they were gathered for.
    const Scalar* shift = nullptr;
    if (self_active_) {
      probe_ = x_ + dual_;  // same size: no allocation
      if (self_contact_.outgrown(probe_.data())) self_contact_.prepare(system, probe_.data());
      if (self_contact_.active() &&
          self_contact_.correct(x_.data(), dual_.data(), int(x_.rows()), correction_.data()))
        shift = correction_.data();
    }
    for (Eigen::Index i = 0; i < x_.rows(); ++i) {
      Scalar* u = dual_.data() + 3 * i;
      if (pinned[std::size_t(3 * i)]) {
        touches_[std::size_t(i)] = 0;
        continue;
      }
      Scalar* target = target_.data() + 3 * i;
      // The last iterate's z = target + u (x there when it touched nothing).
      const Scalar u_before[3] = {u[0], u[1], u[2]};
      const Scalar z_before[3] = {target[0] + u[0], target[1] + u[1], target[2] + u[2]};
      const bool touches = detail::contact_dual_update(
          system.colliders(), x0 + 3 * i, x_.data() + 3 * i, u, dt_, target, Scalar(0),
          edge_distance_(i), shift ? shift + 3 * i : nullptr);
      touches_[std::size_t(i)] = touches ? 1 : 0;
      for (int c = 0; c < 3; ++c) {
        residual = std::max(residual, std::abs(u[c] - u_before[c]));
        residual = std::max(residual, std::abs(target[c] + u[c] - z_before[c]));
      }
    }
    return residual;
  }

  /// @brief The contact term's part of the incremental potential at x,
  /// sum_i w_i / (2 h^2) |x_i - target_i|^2 over the points that touch [J].
  Scalar contact_energy(const PointsType& x) const {
    Scalar e = 0;
    if (!contact_) return e;
    for (Eigen::Index i = 0; i < x.rows(); ++i)
      if (touches_[std::size_t(i)]) e += weight_(i) * (x.row(i) - target_.row(i)).squaredNorm();
    return e / (2 * dt_ * dt_);
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
    const Scalar f0 =
        has_potential ? objective(system, x_, moved_) + contact_energy(x_) : r.squaredNorm();
    Scalar alpha = 1;
    for (int k = 0; k < 40; ++k, alpha /= 2) {
      trial_ = x_;
      Flat(trial_.data(), dx_.size()) += alpha * dx_;
      trial_moved_ = moved_;
      Flat(trial_moved_.data(), dx_.size()) += alpha * dx_;
      Scalar f1;
      if (has_potential) {
        f1 = objective(system, trial_, trial_moved_) + contact_energy(trial_);
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
  bool ready_ = false, symmetric_ = true, contact_ = false;
  Scalar drag_ = 0;
  PointsType x_, v_, f_, r_, trial_, f_trial_, moved_, trial_moved_;
  // The contact term (options.contact_weight): dual variables u [m], targets z - u [m], which
  // points touch; the linearised step's start x + h v, its displacement and right-hand side.
  PointsType dual_, target_, start_, start_moved_, rhs_;
  Vector<Scalar> weight_, new_weight_;  // w_i this step [kg]; scratch
  std::vector<char> touches_;
  Vector<Scalar> edge_distance_;  // detail::edge_distances() at the step's start, per point [m]
  // Self-contact inside the term (options.contact_weight, the system's self-collision): its
  // pairs, whether this step uses it, its corrections and the iterate x + u it was evaluated at.
  detail::SelfContactTerm<Scalar> self_contact_;
  bool self_active_ = false;
  PointsType correction_, probe_;
  Vector<Scalar> dx_;
  detail::JacobianAssembly<System> assembly_;
  detail::EnergyBound<System> energy_bound_;  // S taken at precompute()
  LinearSolver<Storage, Scalar> solver_;
};

}  // namespace massspring
