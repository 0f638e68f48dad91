#pragma once
/// @file
/// @brief The options of FastMassSpring (the local-global solver of Liu et al. 2013): how pins are
/// held, where iterations start, how they are accelerated, and the factor's elimination order.

#include <cmath>
#include <type_traits>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief The largest FastMassSpringOptions::anderson_window.
inline constexpr int kMaxAndersonWindow = 16;

/// @brief How pinned points are held.
enum class PinMode {
  /// Pinned rows and columns are eliminated; the factor covers the free points only. Pinned points
  /// sit exactly at their targets. Well conditioned; works in float.
  Exact,
  /// The reference solver's penalty: Q += w C^T C and the right-hand side += w C^T X_target. Pinned
  /// points
  /// move by about |force| / w. Needs double: in float, w = 1e10 swamps the rest of Q, so
  /// FastMassSpring<float system> refuses it unless `allow_float_penalty` is set.
  Penalty,
};

/// @brief Where each step's iterations start.
enum class InitialGuess {
  /// From the current positions X^t (what the reference solver does).
  Current,
  /// From the inertial prediction X^t + dt V^t.
  Inertial,
};

/// @brief How the local-global iterations of a step are combined.
enum class Acceleration {
  /// Plain local-global: each iterate is the last one's local and global step. Never increases
  /// the energy.
  None,
  /// Chebyshev semi-iterative acceleration (Wang 2015): after `chebyshev_delay` plain iterations,
  /// x_{k+1} = omega_{k+1} (gamma (G(x_k) - x_k) + x_k - x_{k-1}) + x_{k-1} with
  /// omega_{k+1} = 4 / (4 - rho^2 omega_k). Restarted (momentum dropped, back to the plain
  /// iterate) whenever the energy rises.
  Chebyshev,
  /// Anderson acceleration (Peng et al. 2018) of the fixed-point map G (one local-global
  /// iteration) over the last `anderson_window` iterates; an iterate whose energy is not below the
  /// last accepted one is replaced by the plain step from that one and the history is cleared.
  Anderson,
};

/// @brief The elimination order of Q's Cholesky factorization (Sparse storage).
enum class FillOrdering {
  /// Nested dissection of the rest positions when its factor has fewer nonzeros than the
  /// Cholesky type's own order (both counted symbolically before factorizing), else the latter.
  /// On cloth grids nested dissection wins on the larger grids (docs/performance.md).
  Auto,
  /// The Cholesky type's own ordering: Eigen's AMD for the default SparseCholesky.
  Solver,
  /// Geometric nested dissection of the rest positions (massspring::nested_dissection).
  NestedDissection,
};

/// @brief Options of FastMassSpring. Changing `pins`, `penalty_weight`, `ordering` or (for a
/// system with colliders) `contact_weight` makes the next step factorize again; the others take
/// effect at the next step for free.
template <class Scalar>
struct FastMassSpringOptions {
  /// @brief Most local-global iterations (global solves) per step (>= 1). Default 10: with the
  /// default Anderson acceleration and inertial start, enough for cloth at dt = 1/30 s to stay
  /// within a few percent strain (docs/choosing_settings.md; reference() gives the assignment's
  /// 50 plain iterations).
  int iterations = 10;
  /// @brief Stop early when the relative energy decrease of an iteration,
  /// (E_{k-1} - E_k) / (E_0 - E_k), is <= tolerance. 0 (the default) runs every iteration.
  Scalar tolerance = 0;
  /// @brief How pinned points are held (default Exact).
  PinMode pins = PinMode::Exact;
  /// @brief Penalty weight w for PinMode::Penalty [N/m], > 0. Default 1e10 (the reference
  /// solver's).
  Scalar penalty_weight = Scalar(1e10);
  /// @brief Weight alpha of the contact term inside the iteration (dimensionless, finite, >= 0):
  /// each unknown point i gets the weight w_i = alpha sqrt(m_i (m_i + dt^2 k_i)) / dt^2 [N/m] on
  /// Q's diagonal (k_i the summed stiffness of its springs: the geometric mean of its inertia's
  /// and its springs' curvature, detail::contact_weights), and each local step projects it out of
  /// the system's colliders with a dual variable (the alternating direction method of
  /// multipliers; local_global/contact_projection.hpp), so the springs and the global step see
  /// contact and Coulomb friction. Converged, the step is implicit Euler with Signorini-Coulomb
  /// contact whatever alpha; alpha sets how fast it converges. Default 1 (used only when the system
  /// has colliders): at dt = 1/30 s and 10 Anderson iterations from the inertial start it holds a
  /// block on an incline, slides it at Coulomb's rate and turns cloth with a turning ball
  /// (docs/contact.md, "Contact inside the iteration"). 0: contact is only the end-of-step
  /// response every integrator applies (docs/contact.md), which at large steps lets cloth slide
  /// off an obstacle.
  Scalar contact_weight = Scalar(1);
  /// @brief Where iterations start (default Inertial: x + dt v, so a falling cloth falls at the
  /// rate gravity gives from the first iteration on).
  InitialGuess initial_guess = InitialGuess::Inertial;
  /// @brief Acceleration of the iterations (default Anderson).
  Acceleration acceleration = Acceleration::Anderson;
  /// @brief Chebyshev: spectral radius rho of the plain iteration, in [0, 1). 0 (the default):
  /// estimated by the solver on the first Chebyshev step after each factorization, from
  /// `chebyshev_estimate_iterations` trial iterations (see chebyshev_rho()).
  Scalar chebyshev_rho = 0;
  /// @brief Chebyshev: under-relaxation gamma, in (0, 1]. Default 1: the global step is an
  /// exact solve, so nothing to damp (Wang damps Jacobi sweeps with 0.9).
  Scalar chebyshev_gamma = 1;
  /// @brief Chebyshev: plain iterations before the acceleration starts (delayed start S), >= 1.
  /// Default 2 (the delay that reached a given error in the fewest iterations on the project's
  /// cloth scenes, docs/performance.md; Wang uses S = 10 for projective dynamics).
  int chebyshev_delay = 2;
  /// @brief Chebyshev: trial iterations for estimating rho when `chebyshev_rho` is 0, >= 4.
  /// Default 100.
  int chebyshev_estimate_iterations = 100;
  /// @brief Anderson: how many past iterates the least-squares fit uses, in [1, 16]. Default 5.
  int anderson_window = 5;
  /// @brief Allow PinMode::Penalty in float (refused otherwise: see PinMode::Penalty).
  bool allow_float_penalty = false;
  /// @brief Threads for the global step's substitutions (>= 1; default 1). With t > 1, Sparse
  /// storage splits the factor's rows along its elimination tree and substitutes on t OpenMP
  /// threads, with the same result bit for bit (SparseCholesky::set_threads); the spring pass
  /// stays on one thread. Needs OpenMP (-fopenmp, OpenMP::OpenMP_CXX) and a Cholesky with
  /// set_threads(); refused otherwise. Pays only on large factors (docs/performance.md). A change
  /// takes effect at the next step (planning the split allocates, once).
  int threads = 1;
  /// @brief Use the SIMD (AVX2 + FMA) substitutions where the CPU has them (GCC or Clang on
  /// x86-64; checked at run time; Sparse storage and CHOLMOD). Default true; docs/performance.md
  /// gives what it gains. Their results differ from the baseline (SSE2) ones' in the last bits
  /// (fused multiply-adds), so a trajectory is the same bit for bit only between machines that
  /// take the same path: false takes the baseline code everywhere. Compiling with
  /// MASSSPRING_NO_SIMD defined leaves the SIMD code out.
  bool simd = true;
  /// @brief The factor's elimination order (default Auto: the one with fewer nonzeros of nested
  /// dissection and the Cholesky type's own). Sparse storage only: with a Cholesky that takes no
  /// given order (Dense, CHOLMOD) Auto is its own order and NestedDissection is refused. The
  /// order changes rounding only, not the solution.
  FillOrdering ordering = FillOrdering::Auto;
  /// @brief A step whose end state's energy (kinetic of the free points plus potential) exceeds
  /// the step's start energy by more than energy_growth (S + S_c), S the scale taken at
  /// precompute() and S_c the colliders' (integrators/detail/energy_bound.hpp), is reported as
  /// blown up (StepReport::blew_up) and not committed: the system keeps the state before the
  /// step. Finite and >= 0; default 100; 0 turns the check off.
  /// Costs two passes over the springs per step.
  double energy_growth = 100;

  /// @brief The plain iteration of Liu et al. 2013 as the assignment states it: 50 iterations
  /// from the current positions, no acceleration, no contact term (contact only at the end of
  /// the step). The reference the project's accuracy figures compare against.
  static FastMassSpringOptions reference() {
    FastMassSpringOptions o;
    o.iterations = 50;
    o.contact_weight = Scalar(0);
    o.initial_guess = InitialGuess::Current;
    o.acceleration = Acceleration::None;
    return o;
  }
};

/// @brief Throws massspring::Error naming the first option out of its range. `ordered`: the
/// Cholesky type takes a given elimination order; `threaded`: it substitutes on several threads.
template <class Scalar>
void check_options(const FastMassSpringOptions<Scalar>& options, bool ordered, bool threaded) {
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
  if (!(std::isfinite(options.contact_weight) && options.contact_weight >= 0))
    throw Error(
        detail::message("FastMassSpring: options.contact_weight must be finite and >= 0, got ",
                        options.contact_weight));
  if (!(std::isfinite(options.energy_growth) && options.energy_growth >= 0))
    throw Error(
        detail::message("FastMassSpring: options.energy_growth must be finite and >= 0, got ",
                        options.energy_growth));
  if (std::is_same_v<Scalar, float> && options.pins == PinMode::Penalty &&
      !options.allow_float_penalty)
    throw Error(detail::message(
        "FastMassSpring: PinMode::Penalty in float: the penalty weight w = ",
        options.penalty_weight,
        " swamps the rest of Q in single precision (about 7 digits), so the free points' "
        "equations are lost to rounding; use PinMode::Exact (the default), double, or set "
        "options.allow_float_penalty to accept it"));
  if (!(options.chebyshev_rho >= 0 && options.chebyshev_rho < 1))
    throw Error(detail::message("FastMassSpring: options.chebyshev_rho must be in [0, 1), got ",
                                options.chebyshev_rho));
  if (!(options.chebyshev_gamma > 0 && options.chebyshev_gamma <= 1))
    throw Error(detail::message("FastMassSpring: options.chebyshev_gamma must be in (0, 1], got ",
                                options.chebyshev_gamma));
  if (options.chebyshev_delay < 1)
    throw Error(detail::message("FastMassSpring: options.chebyshev_delay must be >= 1, got ",
                                options.chebyshev_delay));
  if (options.chebyshev_estimate_iterations < 4)
    throw Error(
        detail::message("FastMassSpring: options.chebyshev_estimate_iterations must be >= 4, got ",
                        options.chebyshev_estimate_iterations));
  constexpr int max_window = kMaxAndersonWindow;
  if (options.anderson_window < 1 || options.anderson_window > max_window)
    throw Error(detail::message("FastMassSpring: options.anderson_window must be in [1, ",
                                max_window, "], got ", options.anderson_window));
  if (options.threads < 1)
    throw Error(
        detail::message("FastMassSpring: options.threads must be >= 1, got ", options.threads));
  if (!ordered && options.ordering == FillOrdering::NestedDissection)
    throw Error(
        "FastMassSpring: options.ordering = NestedDissection: this storage's Cholesky takes no "
        "given elimination order (use Sparse storage)");
  if (!threaded && options.threads > 1)
    throw Error(detail::message("FastMassSpring: options.threads = ", options.threads,
                                ": this storage's Cholesky solves on one thread only (use "
                                "Sparse storage)"));
}

}  // namespace massspring
