#pragma once
/// @file
/// @brief FastMassSpring: the local-global solver of Liu et al. 2013, "Fast Simulation of
/// Mass-Spring Systems", for one implicit-Euler step per call, with optional Chebyshev (Wang 2015)
/// or Anderson (Peng et al. 2018) acceleration. Its pieces are in this folder: options.hpp,
/// reduced_system.hpp (Q and the numbering of its unknowns), spring_pass.hpp (the local step),
/// guarded_loop.hpp, chebyshev.hpp and anderson.hpp (the iterations).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/springs.hpp"
#include "massspring/integrators/detail/commit_step.hpp"
#include "massspring/integrators/detail/energy_bound.hpp"
#include "massspring/integrators/local_global/anderson.hpp"
#include "massspring/integrators/local_global/chebyshev.hpp"
#include "massspring/integrators/local_global/contact_projection.hpp"
#include "massspring/integrators/local_global/fill_ordering.hpp"
#include "massspring/integrators/local_global/guarded_loop.hpp"
#include "massspring/integrators/local_global/inertial_term.hpp"
#include "massspring/integrators/local_global/options.hpp"
#include "massspring/integrators/local_global/reduced_system.hpp"
#include "massspring/integrators/local_global/spring_pass.hpp"
#include "massspring/integrators/step_report.hpp"
#include "massspring/storage/cholesky_concept.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Local-global ("fast mass-spring") integrator of Liu et al. 2013.
///
/// Each step minimises, over the new positions X,
///   E(X) = sum_e k_e/2 (|x_i - x_j| - r_e)^2 + 1/(2 dt^2) tr((X - Y)^T M (X - Y)) - tr(X^T F)
/// with Y = X^t + dt V^t and F the external forces, which is one step of implicit Euler. Each
/// iteration alternates a local step (d_e = r_e (x_i - x_j) / |x_i - x_j|, every spring) and a
/// global step (solve Q X = A^T K D + M Y / dt^2 + F with Q = A^T K A + M / dt^2, as
/// Q (X - X^t) = A^T K (D - A X^t) + M V^t / dt + F: a point on which nothing acts keeps its
/// position exactly, inertial_term.hpp); it never increases E. Afterwards V = (X - X^t) / dt.
///
/// Force terms of the system (system.add_force): a term that declares a uniform linear damping
/// (F = -beta v, dF/dv = -beta I constant: `LinearDrag`, see ForceConcept::linear_damping) folds
/// into Q exactly (the term beta/(2 dt) |X - X^t|^2 adds beta/dt to Q's diagonal and beta/dt X^t
/// to the right-hand side); every other term, and spring damping, is evaluated once per step at
/// (X^t, V^t) and added to F. That is exact for constant forces (Gravity, ConstantForce) and
/// explicit, first order, for the others (GravitationalAttraction, SpringDamping, user terms):
/// evaluating them at each iterate instead would move the energy each iteration descends, and
/// lose the monotone descent and the tolerance test. For implicit treatment of such terms use
/// BackwardEuler.
///
/// precompute() factorizes Q once (n x n, three right-hand sides). step() re-factorizes only when
/// the system's revision(), the time step or the pin options changed; it allocates nothing
/// otherwise, and never throws for a numerical failure: a failed re-factorization or a result that
/// is not finite is reported in the StepReport, the system keeping its state. A zero-length
/// spring keeps the direction it had at the end of the previous step.
///
/// Colliders (MassSpringSystem::add_collider, contact/colliders/collider_set.hpp) act inside the
/// iteration: each local step first projects the iterate out of them (with friction), so the
/// springs see where contact leaves the points; the end-of-step state then gets the same response
/// as in every other integrator (position, then velocity: restitution and friction). A collision
/// handler on the system (MassSpringSystem::set_collision_handler) is applied to the end-of-step
/// state only, as the explicit integrators apply it. Neither ever re-factorizes Q.
///
/// @tparam System a MassSpringSystem<Scalar, Storage>
/// @tparam Cholesky_ the factorization of Q: by default the Storage's (SparseCholesky or
/// DenseCholesky); any type with the members storage/cholesky_concept.hpp requires works (e.g.
/// CholmodCholesky from massspring/storage/cholmod.hpp).
template <class System, class Cholesky_ = typename System::Traits::Cholesky>
class FastMassSpring {
 public:
  using Scalar = typename System::Scalar;
  using Storage = typename System::Storage;
  using Traits = typename System::Traits;
  using Matrix = typename Traits::Matrix;
  using Cholesky = Cholesky_;
  using Triplet = typename Traits::Triplet;
  using PointsType = Points<Scalar>;
  using Options = FastMassSpringOptions<Scalar>;
  static_assert(require_cholesky<Cholesky, Matrix, Scalar>());

  /// @brief The options; read at every step.
  Options options;

  FastMassSpring() = default;
  explicit FastMassSpring(const Options& opts) : options(opts) {}

  /// @brief Builds and factorizes Q for this system and time step dt [s] (finite, > 0).
  /// Allocates every buffer step() needs. Throws massspring::Error on bad input or when Q cannot
  /// be factorized.
  void precompute(const System& system, Scalar dt);

  /// @brief Advances the system by one time step dt. Returns what happened: when Q had to be
  /// factorized again and could not be (report.factorization_failed), or when the result is not
  /// finite (report.finite false), the system keeps its previous state. Throws massspring::Error
  /// only for invalid options, or when precompute() was not called.
  StepReport step(System& system);

  /// @brief The time step of the last precompute() [s].
  [[nodiscard]] Scalar dt() const { return dt_; }
  /// @brief Q as factorized: over the free points with Exact pins (rows in free_points() order),
  /// over every point with Penalty pins.
  [[nodiscard]] const Matrix& system_matrix() const { return q_; }
  /// @brief Points whose positions are unknowns of the global step, in the order of Q's rows.
  [[nodiscard]] const std::vector<int>& free_points() const { return reduced_.free; }
  /// @brief Stored entries of the Cholesky factor of Q.
  [[nodiscard]] Eigen::Index factor_nonzeros() const { return llt_.factor_nonzeros(); }
  /// @brief The factorization of Q.
  [[nodiscard]] const Cholesky& factorization() const { return llt_; }
  /// @brief The rho Chebyshev uses: options.chebyshev_rho when > 0, else the solver's estimate
  /// (0 until the first Chebyshev step after a factorization has estimated it).
  [[nodiscard]] Scalar chebyshev_rho() const {
    return options.chebyshev_rho > 0 ? options.chebyshev_rho : rho_estimate_;
  }
  /// @brief Accelerated iterates replaced by the plain step because the energy rose (Chebyshev
  /// restarts, Anderson rejections), counted since construction.
  [[nodiscard]] std::size_t rejections() const { return rejections_; }
  /// @brief The contact term's dual variables u [m] (local_global/contact_projection.hpp), one row
  /// per point: what the next step's iteration starts from. Zero rows for points the term does
  /// not act on (pinned points; every point with contact_weight 0 or without colliders). With
  /// the positions and velocities they are all a step reads: a run saved with them and resumed
  /// through set_contact_duals() continues bit for bit.
  [[nodiscard]] PointsType contact_duals() const {
    PointsType u = PointsType::Zero(reduced_.n, 3);
    contact_.get_duals(u);
    return u;
  }
  /// @brief Sets the contact term's dual variables (after precompute(); a factorization sets them
  /// to 0 again). Throws Error, changing nothing, unless u has a finite row per point and a zero
  /// row for each point the term does not act on.
  void set_contact_duals(const PointsType& u);

 private:
  using Buffer = Vector<Scalar>;

  // What guarded_loop() calls.
  struct Iteration {
    FastMassSpring* solver;
    double local(Scalar* x, Scalar* w) { return solver->template local_step<true>(x, w); }
    void local_only(Scalar* x, Scalar* w) { solver->template local_step<false>(x, w); }
    void global(Scalar* w) { solver->global_step(w); }
    double energy(const Scalar* x) { return solver->energy_at(x); }
  };

  bool simd_allowed() const { return options.simd; }

  void check_options() const {
    massspring::check_options(options, cholesky_has_ordered_compute<Cholesky, Matrix>::value,
                              cholesky_has_threads<Cholesky>::value);
  }

  std::string factorization_message() const {
    const bool exact = pins_ == PinMode::Exact;
    return detail::message("FastMassSpring: Q = A^T K A + M / dt^2", exact ? "" : " + w C^T C",
                           " is not numerically positive definite (dt = ", dt_,
                           exact ? "" : detail::message(", penalty weight = ", weight_), ")");
  }

  // Factorizes Q in the order options.ordering asks for (fill_ordering.hpp).
  bool factorize(const System& system) {
    return local_global::factorize_in_order(llt_, q_, options.ordering, system.rest_positions(),
                                            reduced_.free);
  }

  // The solver's threads and the SIMD choice (the substitutions) to the options'
  // (SparseCholesky::set_threads checks for OpenMP).
  void apply_threads() {
    if constexpr (cholesky_has_threads<Cholesky>::value) {
      if (llt_.threads() != options.threads) llt_.set_threads(options.threads);
    }
    if constexpr (cholesky_has_simd<Cholesky>::value) llt_.set_simd(simd_allowed());
  }

  // ---- precompute -------------------------------------------------------------------------------

  // Q, its factor, the packed springs and every buffer step() uses. The only place that
  // allocates. False (the solver left to build again) when Q cannot be factorized.
  bool build(const System& system) {
    factored_ = false;
    pins_ = options.pins;
    weight_ = options.penalty_weight;
    revision_ = system.revision();
    rho_estimate_ = 0;
    rho_estimated_ = false;
    const bool exact = pins_ == PinMode::Exact;
    const Scalar inv_dt2 = Scalar(1) / (dt_ * dt_);

    // The system's force terms: a uniform linear damping folds into Q exactly (beta/(2 dt)
    // |X - X^t|^2 adds beta/dt to the diagonal); every other term is evaluated once per step (see
    // prepare()).
    drag_ = 0;
    other_terms_ = system.has_spring_damping();
    for (const auto& term : system.forces()) {
      if (term->linear_damping)
        drag_ += term->linear_damping_coefficient();
      else
        other_terms_ = true;
    }
    // Colliders: the contact term's weights on Q's diagonal (contact_projection.hpp).
    with_contact_ = !system.colliders().empty();
    contact_weight_ = with_contact_ ? options.contact_weight : Scalar(0);
    Vector<Scalar> point_weight;  // the term's weight per point [N/m]; empty when it is off
    if (contact_weight_ > 0) {
      detail::contact_weights(system, contact_weight_, dt_ * dt_, point_weight);
      point_weight *= inv_dt2;
    }
    q_ = reduced_.template assemble<Traits>(system, exact, inv_dt2, drag_ / dt_, weight_,
                                            point_weight);
    const int n = reduced_.n, nr = reduced_.nr;
    term_force_.setZero(other_terms_ ? n : 0, 3);
    apply_threads();
    ordering_ = options.ordering;
    if (!factorize(system)) return false;

    reduced_.renumber(system, llt_.permutation(), exact);
    const int nx = reduced_.nx;
    springs_.build(system, reduced_.row, nx);
    contact_.build(system, reduced_, point_weight);
    inertia_.build(system, reduced_, inv_dt2, drag_ / dt_);

    const Eigen::Index size = 3 * Eigen::Index(nx);
    for (Buffer& b : buffers_) b.setZero(size);
    x_end_.resize(n, 3);  // the end-of-step state a collision handler sees (commit())
    v_end_.resize(n, 3);
    anderson_.reserve(nr,
                      options.acceleration == Acceleration::Anderson ? options.anderson_window : 0);
    factored_ = true;
    return true;
  }

  // ---- per step ---------------------------------------------------------------------------------

  // The step's constants (inertial prediction, the right-hand side's constant part, pin
  // targets), the starting iterate (buffer 0) and the current rest lengths.
  void prepare(System& system) {
    if (other_terms_) {
      // Terms other than uniform damping (gravity, constant forces, attraction, spring damping,
      // the user's) at the step's start (x^t, v^t): constant over the step, so each iteration
      // still descends one fixed energy. Exact for constant forces; explicit (first order) for
      // the others.
      term_force_.setZero();
      const auto context = system.force_context(system.positions(), system.velocities());
      if (system.has_spring_damping()) SpringDamping<Scalar>{}.add_force(context, term_force_);
      for (const auto& term : system.forces())
        if (!term->linear_damping) term->add_force(context, term_force_);
    }
    inertia_.prepare(system, reduced_, dt_, drag_, pins_ == PinMode::Penalty ? weight_ : Scalar(0),
                     other_terms_ ? &term_force_ : nullptr,
                     options.initial_guess == InitialGuess::Inertial, buffers_[0].data());
    if (pins_ == PinMode::Exact)
      for (Buffer& b : buffers_) restore_pins(b.data());
    springs_.subtract_from(inertia_.origin.data(), inertia_.rhs0.data(), reduced_.nr);
    springs_.set_rest_lengths(system.rest_lengths());
    contact_.prepare(system, dt_, inertia_.rhs0, inertia_.origin);
  }

  // Pinned rows (exact pins) back to their targets, after a solve or a scatter wrote into them.
  void restore_pins(Scalar* x) const { inertia_.restore_pins(x, reduced_.nr); }

  template <bool Energy, bool Write = true>
  double start_rhs(const Scalar* x, Scalar* w) const {
    return inertia_.template start<Energy, Write>(x, w, reduced_);
  }

  // The local step at x into w (w = rhs0 + A^T K D); returns E(x) when Energy. With colliders, x
  // is first projected out of them (contact_projection.hpp).
  template <bool Energy>
  MASSSPRING_NOINLINE double local_step(Scalar* x, Scalar* w) {
    const double contact =
        contact_.active() ? contact_.template apply<Energy>(x, inertia_.rhs0) : 0.0;
    const double quadratic = contact + start_rhs<Energy>(x, w);
    return quadratic + springs_.template pass<true, Energy>(x, w, reduced_.nx);
  }

  // The global step in place: w = origin + Q^-1 w on the free rows (the solve gives the
  // displacement from the step's start, inertial_term.hpp); pinned rows restored.
  MASSSPRING_NOINLINE void global_step(Scalar* w) {
    llt_.solve_in_place(w);
    inertia_.add_origin(w, reduced_.nr);
    restore_pins(w);
  }

  // One whole iteration, w = G(x) = origin + Q^-1 (rhs0 + A^T K D(x)), returning E(x) when
  // Energy.
  template <bool Energy>
  double iteration(Scalar* x, Scalar* w) {
    const double energy = local_step<Energy>(x, w);
    global_step(w);
    return energy;
  }

  // E at x without touching any right-hand side (and recording the springs' directions).
  MASSSPRING_NOINLINE double energy_at(const Scalar* x) {
    const double contact = contact_.active() ? contact_.energy(x) : 0.0;
    return contact + start_rhs<true, false>(x, nullptr) +
           springs_.template pass<false, true>(x, nullptr, reduced_.nx);
  }

  // ---- the iterations ---------------------------------------------------------------------------

  // Plain local-global. Energy only where it is reported or the tolerance needs it.
  Scalar* run_plain(StepReport& report) {
    Scalar* x = buffers_[0].data();
    Scalar* w = buffers_[1].data();
    const int cap = options.iterations;
    const double tolerance = double(options.tolerance);
    const bool track = options.tolerance > 0;
    double e0 = 0, e_prev = 0;
    for (int k = 0; k < cap; ++k) {
      if (track || k == 0 || k == cap - 1) {
        const double e = iteration<true>(x, w);
        if (k == 0) e0 = e;
        // The tolerance is judged at x: w (one more solve, already done) is dropped.
        if (local_global::tolerance_met(report, tolerance, k, e0, e_prev, e)) break;
        e_prev = e;
      } else {
        iteration<false>(x, w);
      }
      std::swap(x, w);
      ++report.iterations;
    }
    // e_prev: the energy at the start of the last iteration (always evaluated).
    const double e = energy_at(x);
    report.energy = e;
    if (!report.converged) report.relative_decrease = local_global::relative(e_prev - e, e0 - e);
    return x;
  }

  // rho for Chebyshev, estimated from trial plain iterations from the prepared start (buffers 0
  // and 1: prepare() must run again afterwards). The contact term's dual variables are put back
  // afterwards: the step then starts from what it would have with rho given.
  void estimate_rho() {
    Iteration it{this};
    contact_.keep_duals();
    rho_estimate_ = Scalar(local_global::estimate_spectral_radius(
        it, buffers_[0].data(), buffers_[1].data(), 3 * Eigen::Index(reduced_.nr),
        options.chebyshev_estimate_iterations));
    contact_.restore_duals();
    rho_estimated_ = true;
  }

  // Ends the step from the iterate x (every point's row: nx == n): the proposed end state and
  // the velocities it implies go through detail::commit_step (pins, the collision response when
  // the system has one, the energy bound), which writes them into the system when the step
  // succeeded.
  StepReport commit(System& system, const Scalar* x, StepReport& report) {
    const auto& positions = system.positions();
    const Scalar inv_dt = Scalar(1) / dt_;
    for (int r = 0; r < reduced_.nx; ++r) {
      const int i = reduced_.point[std::size_t(r)];
      for (int c = 0; c < 3; ++c) {
        const Scalar value = x[3 * r + c];
        const Scalar velocity = (value - positions(i, c)) * inv_dt;
        if (!std::isfinite(value) || !std::isfinite(velocity)) {
          report.finite = false;
          return report;
        }
        x_end_(i, c) = value;
        v_end_(i, c) = velocity;
      }
    }
    // Friction was the contact term's, inside the iteration: not applied a second time. Penalty
    // pins stay where the solve left them unless a collision response runs.
    detail::commit_step(system, x_end_, v_end_, dt_, report, energy_bound_, !contact_.active(),
                        false, pins_ == PinMode::Exact || system.has_collision_response());
    return report;
  }

  Scalar dt_ = 0;
  Scalar weight_ = 0;
  Scalar rho_estimate_ = 0;
  bool rho_estimated_ = false;  // rho_estimate_ holds this factorization's estimate
  PinMode pins_ = PinMode::Exact;
  FillOrdering ordering_ = FillOrdering::Auto;
  std::uint64_t revision_ = 0;
  bool factored_ = false;  // the last build() factorized Q
  std::size_t rejections_ = 0;
  local_global::ReducedSystem<Scalar> reduced_;
  local_global::PackedSprings<Scalar> springs_;
  Matrix q_;
  Cholesky llt_;
  std::array<Buffer, 5> buffers_;
  local_global::InertialTerm<Scalar> inertia_;
  Scalar drag_ = 0;                           // sum of the terms' uniform linear damping [N s/m]
  bool other_terms_ = false;                  // the system has force terms other than that
  Points<Scalar> term_force_;                 // their force at the step's start
  Points<Scalar> x_end_, v_end_;              // the proposed end-of-step state (commit())
  detail::EnergyBound<System> energy_bound_;  // taken at precompute()
  local_global::Anderson<Scalar> anderson_;
  local_global::ContactProjection<Scalar> contact_;  // the contact term (colliders)
  bool with_contact_ = false;                        // Q was built for a system with colliders
  Scalar contact_weight_ = 0;                        // the contact weight alpha Q carries
};

template <class System, class Cholesky_>
void FastMassSpring<System, Cholesky_>::precompute(const System& system, Scalar dt) {
  if (!(std::isfinite(dt) && dt > 0))
    throw Error(detail::message("FastMassSpring: dt must be finite and > 0, got ", dt));
  check_options();
  dt_ = dt;
  if (!build(system)) throw Error(factorization_message());
  energy_bound_.reset(system, options.energy_growth);
}

template <class System, class Cholesky_>
void FastMassSpring<System, Cholesky_>::set_contact_duals(const PointsType& u) {
  if (!factored_) throw Error("FastMassSpring: set_contact_duals() before precompute()");
  detail::require_rows("FastMassSpring::set_contact_duals", u.rows(), reduced_.n, "point");
  detail::require_finite_rows("point", "contact dual", u);
  if (const int i = contact_.set_duals(u); i >= 0)
    throw Error(detail::message("FastMassSpring: set_contact_duals: row ", i,
                                " is not zero, but the contact term does not act on point ", i,
                                " (pinned, contact_weight 0 or no colliders)"));
}

template <class System, class Cholesky_>
StepReport FastMassSpring<System, Cholesky_>::step(System& system) {
  if (!(dt_ > 0)) throw Error("FastMassSpring: step() before precompute()");
  check_options();
  StepReport report;
  if (!factored_ || system.revision() != revision_ || system.num_points() != reduced_.n ||
      options.pins != pins_ || (pins_ == PinMode::Penalty && options.penalty_weight != weight_) ||
      options.ordering != ordering_ || system.colliders().empty() == with_contact_ ||
      (with_contact_ && options.contact_weight != contact_weight_)) {
    report.refactorized = true;
    if (!build(system)) {
      report.factorization_failed = true;
      return report;
    }
  }
  apply_threads();
  prepare(system);
  Scalar* result = nullptr;
  Iteration it{this};
  const int cap = options.iterations;
  const double tolerance = double(options.tolerance);
  switch (options.acceleration) {
    case Acceleration::None:
      result = run_plain(report);
      break;
    case Acceleration::Chebyshev: {
      // Estimated once per factorization (0, "no acceleration", when the trial iterations do
      // not give a rate in (0, 1), e.g. when they converge to rounding).
      if (!(options.chebyshev_rho > 0) && !rho_estimated_) {
        estimate_rho();
        prepare(system);
      }
      local_global::Chebyshev<Scalar> chebyshev(
          {buffers_[0].data(), buffers_[1].data(), buffers_[2].data(), buffers_[3].data()},
          reduced_.nr, reduced_.nx, double(chebyshev_rho()), double(options.chebyshev_gamma),
          options.chebyshev_delay);
      result = local_global::guarded_loop(it, chebyshev, cap, tolerance, report, rejections_);
      break;
    }
    case Acceleration::Anderson:
      anderson_.start({buffers_[0].data(), buffers_[1].data(), buffers_[2].data(),
                       buffers_[3].data(), buffers_[4].data()},
                      reduced_.nr, options.anderson_window);
      result = local_global::guarded_loop(it, anderson_, cap, tolerance, report, rejections_);
      break;
  }
  report.convergence = !(tolerance > 0)   ? Convergence::NotTested
                       : report.converged ? Convergence::Converged
                                          : Convergence::NotConverged;
  return commit(system, result, report);
}
// precompute() and step() are defined outside the class, so they are not inline: with
// MASSSPRING_EXTERN_TEMPLATES defined, a translation unit that steps one of the four systems below
// does not instantiate them (nor the solver machinery they call) and compiles in about the time of
// the headers alone. Exactly one translation unit of the program must then include
// massspring/integrators/local_global/instances.hpp, compiled with the same flags and configuration
// macros as the others, which instantiates them (C++17 [temp.explicit]; docs/fast_mass_spring.md,
// "Compile time").
#ifdef MASSSPRING_EXTERN_TEMPLATES
extern template class FastMassSpring<MassSpringSystem<double, Sparse>>;
extern template class FastMassSpring<MassSpringSystem<float, Sparse>>;
extern template class FastMassSpring<MassSpringSystem<double, Dense>>;
extern template class FastMassSpring<MassSpringSystem<float, Dense>>;
#endif

}  // namespace massspring
