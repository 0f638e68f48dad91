#pragma once
/// @file
/// @brief FastMassSpring: the local-global solver of Liu et al. 2013, "Fast Simulation of
/// Mass-Spring Systems", for one implicit-Euler step per call.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/integrators/step_report.hpp"
#include "massspring/system/detail/validate.hpp"
#include "massspring/system/mass_spring_system.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief How pinned points are held.
enum class PinMode {
  /// Pinned rows and columns are eliminated; the factor covers the free points only. Pinned points
  /// sit exactly at their targets. Well conditioned; works in float.
  Exact,
  /// The seed's penalty: Q += w C^T C and the right-hand side += w C^T X_target. Pinned points
  /// move by about |force| / w. Needs double: in float, w = 1e10 swamps the rest of Q.
  Penalty,
};

/// @brief Where each step's iterations start.
enum class InitialGuess {
  /// From the current positions X^t (what the assignment's completed solutions do).
  Current,
  /// From the inertial prediction X^t + dt V^t.
  Inertial,
};

/// @brief Options of FastMassSpring. Changing `pins` or `penalty_weight` makes the next step
/// factorise again; the others take effect at the next step for free.
template <class Scalar>
struct FastMassSpringOptions {
  /// @brief Most local-global iterations per step (>= 1). Default 50, as the assignment suggests.
  int iterations = 50;
  /// @brief Stop early when the relative energy decrease of an iteration,
  /// (E_{k-1} - E_k) / (E_0 - E_k), is <= tolerance. 0 (the default) runs every iteration.
  Scalar tolerance = 0;
  /// @brief How pinned points are held (default Exact).
  PinMode pins = PinMode::Exact;
  /// @brief Penalty weight w for PinMode::Penalty [N/m], > 0. Default 1e10 (the seed's).
  Scalar penalty_weight = Scalar(1e10);
  /// @brief A force applied to every point [N], whatever its mass. The assignment's scenes use
  /// (0, -9.8, 0). Default zero.
  Vector3<Scalar> external_force = Vector3<Scalar>::Zero();
  /// @brief An acceleration applied to every point [m/s^2] (a force m_i g). Default zero.
  Vector3<Scalar> gravity = Vector3<Scalar>::Zero();
  /// @brief Where iterations start (default Current).
  InitialGuess initial_guess = InitialGuess::Current;
};

/// @brief Local-global ("fast mass-spring") integrator of Liu et al. 2013.
///
/// Each step minimises, over the new positions X,
///   E(X) = sum_e k_e/2 (|x_i - x_j| - r_e)^2 + 1/(2 dt^2) tr((X - Y)^T M (X - Y)) - tr(X^T F)
/// with Y = X^t + dt V^t and F the external forces, which is one step of implicit Euler. Each
/// iteration alternates a local step (d_e = r_e (x_i - x_j) / |x_i - x_j|, every spring) and a
/// global step (solve Q X = A^T K D + M Y / dt^2 + F with Q = A^T K A + M / dt^2); it never
/// increases E. Afterwards V = (X - X^t) / dt.
///
/// precompute() factorises Q once (n x n, three right-hand sides). step() re-factorises only when
/// the system's revision(), the time step or the pin options changed; it allocates nothing
/// otherwise. A zero-length spring keeps the direction it had at the end of the previous step.
///
/// @tparam System a MassSpringSystem<Scalar, Storage>
template <class System>
class FastMassSpring {
 public:
  using Scalar = typename System::Scalar;
  using Storage = typename System::Storage;
  using Traits = typename System::Traits;
  using Matrix = typename Traits::Matrix;
  using Cholesky = typename Traits::Cholesky;
  using Triplet = typename Traits::Triplet;
  using PointsType = Points<Scalar>;
  using Options = FastMassSpringOptions<Scalar>;

  /// @brief The options; read at every step.
  Options options;

  FastMassSpring() = default;
  explicit FastMassSpring(const Options& opts) : options(opts) {}

  /// @brief Builds and factorises Q for this system and time step dt [s] (finite, > 0).
  /// Allocates every buffer step() needs. Throws massspring::Error on bad input or when Q cannot
  /// be factorised.
  void precompute(const System& system, Scalar dt) {
    if (!(std::isfinite(dt) && dt > 0))
      throw Error(detail::message("precompute: time step dt must be finite and > 0, got ", dt));
    check_options();
    dt_ = dt;
    build(system);
  }

  /// @brief Advances the system by one time step dt. Returns what happened; when the result is not
  /// finite, the report says so and the system keeps its previous state.
  StepReport step(System& system) {
    if (!(dt_ > 0)) throw Error("step: call precompute(system, dt) first");
    check_options();
    StepReport report;
    if (system.revision() != revision_ || system.num_points() != n_ || options.pins != pins_ ||
        (pins_ == PinMode::Penalty && options.penalty_weight != weight_)) {
      build(system);
      report.refactorized = true;
    }
    prepare(system);
    const int cap = options.iterations;
    const bool track = options.tolerance > 0;
    double e0 = 0, e_prev = 0, e_last = 0;
    for (int k = 0; k < cap; ++k) {
      const Scalar spring_energy = spring_pass<true>(system);
      if (track || k == 0 || k == cap - 1) {
        const double e = double(spring_energy) + double(quadratic_energy(system));
        if (k == 0) e0 = e;
        if (track && k > 0) {
          report.relative_decrease = relative(e_prev - e, e0 - e);
          if (report.relative_decrease <= double(options.tolerance)) {
            report.converged = true;
            break;
          }
        }
        e_prev = e;
        e_last = e;
      }
      global_step();
      ++report.iterations;
    }
    const double e_final = double(spring_pass<false>(system)) + double(quadratic_energy(system));
    report.energy = e_final;
    if (!report.converged) report.relative_decrease = relative(e_last - e_final, e0 - e_final);

    // Commit only a finite result: positions and the velocities they imply (which can overflow
    // even when the positions do not).
    if (!x_.allFinite() || !((x_ - system.positions()) / dt_).allFinite()) {
      report.finite = false;
      return report;
    }
    system.velocities() = (x_ - system.positions()) / dt_;
    system.positions() = x_;
    return report;
  }

  /// @brief The time step of the last precompute() [s].
  [[nodiscard]] Scalar dt() const { return dt_; }
  /// @brief Q as factorised: over the free points with Exact pins (rows in free_points() order),
  /// over every point with Penalty pins.
  [[nodiscard]] const Matrix& system_matrix() const { return q_; }
  /// @brief Points whose positions are unknowns of the global step, in the order of Q's rows.
  [[nodiscard]] const std::vector<int>& free_points() const { return free_; }
  /// @brief Stored entries of the Cholesky factor of Q.
  [[nodiscard]] Eigen::Index factor_nonzeros() const { return llt_.factor_nonzeros(); }

 private:
  static double relative(double decrease, double total) {
    return total > 0 ? decrease / total : 0.0;
  }

  void check_options() const {
    if (options.iterations < 1)
      throw Error(detail::message("FastMassSpring: options.iterations must be >= 1, got ",
                                  options.iterations));
    if (!(std::isfinite(options.tolerance) && options.tolerance >= 0))
      throw Error(detail::message("FastMassSpring: options.tolerance must be finite and >= 0, got ",
                                  options.tolerance));
    if (!(std::isfinite(options.penalty_weight) && options.penalty_weight > 0))
      throw Error(
          detail::message("FastMassSpring: options.penalty_weight must be finite and > 0, got ",
                          options.penalty_weight));
    if (!options.external_force.allFinite())
      throw Error("FastMassSpring: options.external_force must be finite");
    if (!options.gravity.allFinite()) throw Error("FastMassSpring: options.gravity must be finite");
  }

  // Q, its factor and every buffer step() uses. The only place that allocates.
  void build(const System& system) {
    n_ = system.num_points();
    pins_ = options.pins;
    weight_ = options.penalty_weight;
    revision_ = system.revision();
    const bool exact = pins_ == PinMode::Exact;
    const int m = system.num_springs();
    const auto& springs = system.springs();
    const auto& k = system.stiffness();
    const auto& mass = system.masses();
    const Scalar inv_dt2 = Scalar(1) / (dt_ * dt_);

    // Reduced row of each point; with exact pins, pinned points go to the spare row n_red.
    std::vector<int> row(std::size_t(n_), 0);
    free_.clear();
    for (int i = 0; i < n_; ++i)
      if (!(exact && system.is_pinned(i))) {
        row[std::size_t(i)] = int(free_.size());
        free_.push_back(i);
      }
    n_red_ = int(free_.size());
    for (int i = 0; i < n_; ++i)
      if (exact && system.is_pinned(i)) row[std::size_t(i)] = n_red_;

    std::vector<Triplet> t;
    t.reserve(std::size_t(4 * m + n_));
    spring_rows_.resize(m, 2);
    coupling_.clear();
    for (int e = 0; e < m; ++e) {
      const int i = springs(e, 0), j = springs(e, 1);
      const int ri = row[std::size_t(i)], rj = row[std::size_t(j)];
      spring_rows_(e, 0) = ri;
      spring_rows_(e, 1) = rj;
      const bool fi = ri < n_red_, fj = rj < n_red_;
      if (fi) t.emplace_back(ri, ri, k(e));
      if (fj) t.emplace_back(rj, rj, k(e));
      if (fi && fj) {
        t.emplace_back(ri, rj, -k(e));
        t.emplace_back(rj, ri, -k(e));
      }
      // -Q_FP X_P: a free point joined to a pinned one is pulled by k x_pinned.
      if (fi && !fj) coupling_.push_back({ri, system.pin_row(j), k(e)});
      if (fj && !fi) coupling_.push_back({rj, system.pin_row(i), k(e)});
    }
    for (int r = 0; r < n_red_; ++r) t.emplace_back(r, r, mass(free_[std::size_t(r)]) * inv_dt2);
    if (!exact)
      for (int p : system.pinned()) t.emplace_back(p, p, weight_);
    q_ = Traits::from_triplets(n_red_, n_red_, t);
    if (!llt_.compute(q_))
      throw Error(detail::message("precompute: Q = A^T K A + M / dt^2", exact ? "" : " + w C^T C",
                                  " is not numerically positive definite (dt = ", dt_,
                                  exact ? "" : detail::message(", penalty weight = ", weight_),
                                  ")"));

    x_.resize(n_, 3);
    inertial_.resize(n_, 3);
    rhs0_.resize(n_red_ + 1, 3);
    rhs_.resize(n_red_ + 1, 3);
    solution_.resize(n_red_, 3);
    direction_.resize(m, 3);
    for (int e = 0; e < m; ++e) {
      Vector3<Scalar> u =
          (system.positions().row(springs(e, 0)) - system.positions().row(springs(e, 1)))
              .transpose();
      if (!(u.norm() > 0))
        u = (system.rest_positions().row(springs(e, 0)) -
             system.rest_positions().row(springs(e, 1)))
                .transpose();
      if (u.norm() > 0) u.normalize();
      direction_.row(e) = u.transpose();
    }
  }

  Vector3<Scalar> force_on(const System& system, int i) const {
    return options.external_force + system.masses()(i) * options.gravity;
  }

  // Inertial prediction, constant part of the right-hand side, starting iterate.
  void prepare(const System& system) {
    const auto& x = system.positions();
    const auto& v = system.velocities();
    const auto& mass = system.masses();
    const Scalar inv_dt2 = Scalar(1) / (dt_ * dt_);
    inertial_ = x + dt_ * v;
    for (int r = 0; r < n_red_; ++r) {
      const int i = free_[std::size_t(r)];
      rhs0_.row(r) = (mass(i) * inv_dt2) * inertial_.row(i) + force_on(system, i).transpose();
    }
    rhs0_.row(n_red_).setZero();
    const auto& targets = system.pin_targets();
    if (pins_ == PinMode::Penalty) {
      for (int r = 0; r < system.num_pinned(); ++r)
        rhs0_.row(system.pinned()[std::size_t(r)]) += weight_ * targets.row(r);
    } else {
      for (const Coupling& c : coupling_) rhs0_.row(c.row) += c.k * targets.row(c.pin);
    }
    x_ = options.initial_guess == InitialGuess::Current ? x : inertial_;
    if (pins_ == PinMode::Exact)
      for (int r = 0; r < system.num_pinned(); ++r)
        x_.row(system.pinned()[std::size_t(r)]) = targets.row(r);
  }

  // One pass over the springs at the current iterate; returns their energy. With Scatter (the
  // local step) it also sets rhs = rhs0 + A^T K D; without (after the last iteration) it records
  // each spring's direction, which a spring of zero length keeps at the next step.
  template <bool Scatter>
  Scalar spring_pass(const System& system) {
    if constexpr (Scatter) rhs_ = rhs0_;
    const auto& springs = system.springs();
    const auto& k = system.stiffness();
    const auto& r = system.rest_lengths();
    const Scalar* x = x_.data();
    Scalar* b = rhs_.data();
    Scalar energy = 0;
    const int m = system.num_springs();
    for (int e = 0; e < m; ++e) {
      const Scalar* xi = x + 3 * springs(e, 0);
      const Scalar* xj = x + 3 * springs(e, 1);
      const Scalar d0 = xi[0] - xj[0], d1 = xi[1] - xj[1], d2 = xi[2] - xj[2];
      const Scalar len = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
      const Scalar stretch = len - r(e);
      energy += k(e) * stretch * stretch;
      if constexpr (Scatter) {
        Scalar s0, s1, s2;  // k_e r_e times the spring's unit direction
        if (len > 0) {
          const Scalar f = k(e) * r(e) / len;
          s0 = f * d0, s1 = f * d1, s2 = f * d2;
        } else {
          const Scalar f = k(e) * r(e);
          s0 = f * direction_(e, 0), s1 = f * direction_(e, 1), s2 = f * direction_(e, 2);
        }
        Scalar* bi = b + 3 * spring_rows_(e, 0);
        Scalar* bj = b + 3 * spring_rows_(e, 1);
        bi[0] += s0, bi[1] += s1, bi[2] += s2;
        bj[0] -= s0, bj[1] -= s1, bj[2] -= s2;
      } else if (len > 0) {
        direction_(e, 0) = d0 / len, direction_(e, 1) = d1 / len, direction_(e, 2) = d2 / len;
      }
    }
    return energy / 2;
  }

  // X_free = Q^-1 rhs.
  void global_step() {
    if (n_red_ == n_) {
      llt_.solve(rhs_.topRows(n_red_), x_);
      return;
    }
    llt_.solve(rhs_.topRows(n_red_), solution_);
    for (int r = 0; r < n_red_; ++r) x_.row(free_[std::size_t(r)]) = solution_.row(r);
  }

  // The iterate-dependent part of E other than the springs: inertia, external force, penalty.
  Scalar quadratic_energy(const System& system) const {
    const auto& mass = system.masses();
    const Scalar half_inv_dt2 = Scalar(0.5) / (dt_ * dt_);
    Scalar energy = 0;
    for (int r = 0; r < n_red_; ++r) {
      const int i = free_[std::size_t(r)];
      energy += mass(i) * half_inv_dt2 * (x_.row(i) - inertial_.row(i)).squaredNorm() -
                x_.row(i).dot(force_on(system, i).transpose());
    }
    if (pins_ == PinMode::Penalty)
      for (int p = 0; p < system.num_pinned(); ++p)
        energy +=
            weight_ / 2 *
            (x_.row(system.pinned()[std::size_t(p)]) - system.pin_targets().row(p)).squaredNorm();
    return energy;
  }

  struct Coupling {
    int row;  // reduced row of the free point
    int pin;  // row of the pinned point in system.pin_targets()
    Scalar k;
  };

  Scalar dt_ = 0;
  Scalar weight_ = 0;
  PinMode pins_ = PinMode::Exact;
  std::uint64_t revision_ = 0;
  int n_ = 0, n_red_ = 0;
  std::vector<int> free_;
  std::vector<Coupling> coupling_;
  Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> spring_rows_;
  Matrix q_;
  Cholesky llt_;
  PointsType x_, inertial_, rhs0_, rhs_, solution_, direction_;
};

}  // namespace massspring
