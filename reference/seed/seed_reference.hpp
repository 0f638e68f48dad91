#pragma once
/// @file
/// @brief SeedFastMassSpring: the assignment's ("the seed's") local-global loop, written straight
/// from its formulas with Eigen's sparse products and Eigen's own SimplicialLLT solve. A test
/// oracle for FastMassSpring (tests/integrators/test_seed_reference.cpp) and the baseline the
/// benchmarks measure it against (benchmarks/bench_step.cpp). Reached through the CMake target
/// `massspring_seed_reference` (reference/CMakeLists.txt) as "seed/seed_reference.hpp"; not
/// installed.
///
/// Deliberately plain: it forms A, M, K, C and Q with sparse products, allocates in every
/// iteration and solves with `SimplicialLLT::solve` on the n x 3 right-hand side. It shares no code
/// with FastMassSpring; it only reads the system's model through its public accessors.

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <stdexcept>
#include <string>

#include "massspring/storage/sparse.hpp"
#include "massspring/system/mass_spring_system.hpp"

namespace massspring::test {

/// @brief The seed's fast mass-spring solver (Liu et al. 2013 as the assignment states it), double
/// precision, sparse, penalty pins.
///
/// precompute(system, dt):
///   A = system.incidence() (m x n), M = system.mass_matrix(), C = system.pin_selector() (p x n),
///   K = diag(stiffness), Q = A^T K A + M / dt^2 + w C^T C, factorized by SimplicialLLT;
///   U = system.positions(), U_prev = U - dt V (the system's velocities).
/// step(), one frame:
///   y = M (2 U - U_prev) / dt^2 + F_ext + w C^T C U_rest;  X = U;
///   `iterations` times: D = A X, row e scaled to length r_e;  b = A^T K D + y;  X = Q^-1 b;
///   U_prev = U;  U = X.
/// F_ext has `external_force` in every row (a force per point, not m g), plus M g when the
/// (non-seed) option `gravity` is set. Pins hold the rest
/// positions U_rest, as in the seed; precompute() throws when a pin target differs from its rest
/// position. A zero-length spring gets d_e = 0 (Eigen's normalized() of a zero row), where
/// FastMassSpring keeps the spring's previous direction.
class SeedFastMassSpring {
 public:
  using System = MassSpringSystem<double, Sparse>;
  using SparseMatrix = Eigen::SparseMatrix<double>;
  using Factorization = Eigen::SimplicialLLT<SparseMatrix>;

  /// @brief The seed's constants.
  struct Options {
    /// @brief Local-global iterations per step (>= 1), read by step(). The seed's 50.
    int iterations = 50;
    /// @brief Penalty weight w of the pins [N/m], > 0, read by precompute(). The seed's 1e10.
    double penalty_weight = 1e10;
    /// @brief Force on every point [N], read by step(). The seed's (0, -9.8, 0).
    Eigen::RowVector3d external_force = Eigen::RowVector3d(0, -9.8, 0);
    /// @brief An acceleration of every point [m/s^2] (a force m_i g, added to external_force),
    /// read by step(). Not the seed's (it has none): zero by default. Liu 2013's curtain uses it.
    Eigen::RowVector3d gravity = Eigen::RowVector3d::Zero();
  };

  /// @brief The options (see each field for when it is read).
  Options options;

  SeedFastMassSpring() = default;
  explicit SeedFastMassSpring(const Options& opts) : options(opts) {}

  /// @brief Builds and factorizes Q and takes the system's state (positions U, velocities V) as
  /// the solver's own: U_prev = U - dt V. Throws std::invalid_argument on bad input,
  /// std::runtime_error when Q cannot be factorized.
  /// @param[in] system the model (read now, not kept)
  /// @param[in] dt     time step [s], > 0
  void precompute(const System& system, double dt) {
    if (!(dt > 0)) throw std::invalid_argument("SeedFastMassSpring: dt must be > 0");
    if (!(options.penalty_weight > 0))
      throw std::invalid_argument("SeedFastMassSpring: penalty_weight must be > 0");
    for (int r = 0; r < system.num_pinned(); ++r) {
      const int i = system.pinned()[std::size_t(r)];
      if (system.pin_targets().row(r) != system.rest_positions().row(i))
        throw std::invalid_argument("SeedFastMassSpring: point " + std::to_string(i) +
                                    " is pinned away from its rest position; the seed pins at "
                                    "rest positions only");
    }
    dt_ = dt;
    const double w = options.penalty_weight;
    a_ = system.incidence();
    m_ = system.mass_matrix();
    c_ = system.pin_selector();
    k_ = system.stiffness_matrix();
    r_ = system.rest_lengths();
    ctc_ = SparseMatrix(c_.transpose()) * c_;
    const SparseMatrix at = a_.transpose();
    q_ = at * k_ * a_ + m_ / (dt * dt) + w * ctc_;
    llt_.compute(q_);
    if (llt_.info() != Eigen::Success)
      throw std::runtime_error("SeedFastMassSpring: Q is not numerically positive definite");
    u_rest_ = system.rest_positions();
    u_ = system.positions();
    u_prev_ = u_ - dt * Eigen::MatrixXd(system.velocities());
  }

  /// @brief Advances the solver's own state by one time step (the seed's loop, verbatim).
  void step() {
    if (!(dt_ > 0)) throw std::logic_error("SeedFastMassSpring: call precompute() first");
    if (options.iterations < 1)
      throw std::invalid_argument("SeedFastMassSpring: iterations must be >= 1");
    const Eigen::Index n = u_.rows();
    const Eigen::MatrixXd f_ext = options.external_force.replicate(n, 1) +
                                  m_ * Eigen::MatrixXd(options.gravity.replicate(n, 1));
    const Eigen::MatrixXd y =
        m_ * (2.0 * u_ - u_prev_) / (dt_ * dt_) + f_ext + options.penalty_weight * (ctc_ * u_rest_);
    Eigen::MatrixXd x = u_;
    for (int it = 0; it < options.iterations; ++it) {
      Eigen::MatrixXd d = a_ * x;
      for (Eigen::Index e = 0; e < d.rows(); ++e) d.row(e) = r_(e) * d.row(e).normalized();
      const Eigen::MatrixXd b = a_.transpose() * (k_ * d) + y;
      x = llt_.solve(b);
    }
    u_prev_ = u_;
    u_ = x;
  }

  /// @brief Replaces the state: U = positions, U_prev = positions - dt velocities (both n x 3).
  void set_state(const Eigen::MatrixXd& positions, const Eigen::MatrixXd& velocities) {
    if (positions.rows() != u_.rows() || positions.cols() != 3 || velocities.rows() != u_.rows() ||
        velocities.cols() != 3)
      throw std::invalid_argument("SeedFastMassSpring::set_state: expected n by 3 matrices");
    u_ = positions;
    u_prev_ = positions - dt_ * velocities;
  }

  /// @brief #points by 3 positions U [m].
  [[nodiscard]] const Eigen::MatrixXd& positions() const { return u_; }
  /// @brief #points by 3 velocities (U - U_prev) / dt [m/s].
  [[nodiscard]] Eigen::MatrixXd velocities() const { return (u_ - u_prev_) / dt_; }
  /// @brief The time step of the last precompute() [s].
  [[nodiscard]] double dt() const { return dt_; }
  /// @brief Q = A^T K A + M / dt^2 + w C^T C (#points by #points).
  [[nodiscard]] const SparseMatrix& system_matrix() const { return q_; }
  /// @brief Stored entries of the Cholesky factor L of P Q P^T (diagonal included).
  [[nodiscard]] Eigen::Index factor_nonzeros() const {
    return llt_.matrixL().nestedExpression().nonZeros();
  }
  /// @brief The factorization of Q (Eigen's SimplicialLLT, its default AMD ordering).
  [[nodiscard]] const Factorization& factorization() const { return llt_; }

 private:
  double dt_ = 0;
  SparseMatrix a_, m_, c_, k_, ctc_, q_;
  Eigen::VectorXd r_;
  Factorization llt_;
  Eigen::MatrixXd u_rest_, u_, u_prev_;
};

}  // namespace massspring::test
