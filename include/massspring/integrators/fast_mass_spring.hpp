#pragma once
/// @file
/// @brief FastMassSpring: the local-global solver of Liu et al. 2013, "Fast Simulation of
/// Mass-Spring Systems", for one implicit-Euler step per call, with optional Chebyshev (Wang 2015)
/// or Anderson (Peng et al. 2018) acceleration.

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>  // SSE2
#endif
#include <limits>
#include <numeric>
#include <type_traits>
#include <utility>
#include <vector>

#include "massspring/error.hpp"
#include "massspring/forces/springs.hpp"
#include "massspring/integrators/step_report.hpp"
#include "massspring/storage/lower_factor.hpp"
#include "massspring/storage/nested_dissection.hpp"
#include "massspring/system/detail/avx2.hpp"
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
  /// move by about |force| / w. Needs double: in float, w = 1e10 swamps the rest of Q, so
  /// FastMassSpring<float system> refuses it unless `allow_float_penalty` is set.
  Penalty,
};

/// @brief Where each step's iterations start.
enum class InitialGuess {
  /// From the current positions X^t (what the assignment's completed solutions do).
  Current,
  /// From the inertial prediction X^t + dt V^t.
  Inertial,
};

namespace detail {

/// For two squared lengths sq and numerators num, lane by lane: len = sqrt(sq) and
/// quotient = num / len, each rounded once as by std::sqrt and by `/`. quotient is finite but
/// meaningless where sq is 0 or NaN (the caller does not use it there). With SSE2 two doubles go
/// through one sqrtpd and one divpd, built from and read back to registers: the divider, the
/// costliest part of a spring, then takes about what one lane did (docs/performance.md). Floats
/// go lane by lane: their scalar square root and division are short enough that sqrtps/divps
/// measured slower (flag and skirt steps, 4%).
template <class Scalar>
inline void lengths2(const Scalar* sq, const Scalar* num, Scalar* len, Scalar* quotient) {
#if defined(__SSE2__)
  if constexpr (std::is_same_v<Scalar, double>) {
    const __m128d l = _mm_sqrt_pd(_mm_set_pd(sq[1], sq[0]));
    // max(l, clamp) is l for every sq > 0 (sqrt is monotone, and sq >= 2^-1074 gives
    // l >= 2^-537), and the clamp for 0 and NaN (max returns its second operand for NaN).
    const __m128d clamp = _mm_set1_pd(0x1p-537);
    const __m128d q = _mm_div_pd(_mm_set_pd(num[1], num[0]), _mm_max_pd(l, clamp));
    len[0] = _mm_cvtsd_f64(l), len[1] = _mm_cvtsd_f64(_mm_unpackhi_pd(l, l));
    quotient[0] = _mm_cvtsd_f64(q), quotient[1] = _mm_cvtsd_f64(_mm_unpackhi_pd(q, q));
    return;
  }
#endif
  for (int k = 0; k < 2; ++k) {
    len[k] = std::sqrt(sq[k]);
    quotient[k] = sq[k] > 0 ? num[k] / len[k] : Scalar(0);
  }
}

}  // namespace detail

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

/// @brief The elimination order of Q's Cholesky factorisation (Sparse storage).
enum class FillOrdering {
  /// Nested dissection of the rest positions when its factor has fewer nonzeros than the
  /// Cholesky type's own order (both counted symbolically before factorising), else the latter.
  /// On cloth grids nested dissection wins from about 80 x 80 points up (docs/performance.md).
  Auto,
  /// The Cholesky type's own ordering: Eigen's AMD for the default SparseCholesky.
  Solver,
  /// Geometric nested dissection of the rest positions (massspring::nested_dissection).
  NestedDissection,
};

/// @brief Options of FastMassSpring. Changing `pins`, `penalty_weight` or `ordering` makes the
/// next step factorise again; the others take effect at the next step for free.
template <class Scalar>
struct FastMassSpringOptions {
  /// @brief Most local-global iterations (global solves) per step (>= 1). Default 50, as the
  /// assignment suggests.
  int iterations = 50;
  /// @brief Stop early when the relative energy decrease of an iteration,
  /// (E_{k-1} - E_k) / (E_0 - E_k), is <= tolerance. 0 (the default) runs every iteration.
  Scalar tolerance = 0;
  /// @brief How pinned points are held (default Exact).
  PinMode pins = PinMode::Exact;
  /// @brief Penalty weight w for PinMode::Penalty [N/m], > 0. Default 1e10 (the seed's).
  Scalar penalty_weight = Scalar(1e10);
  /// @brief A force applied to every point [N], whatever its mass, in addition to the system's
  /// force terms (the same as a ConstantForce term). The assignment's scenes use (0, -9.8, 0).
  /// Default zero.
  Vector3<Scalar> external_force = Vector3<Scalar>::Zero();
  /// @brief An acceleration applied to every point [m/s^2] (a force m_i g), in addition to the
  /// system's force terms (the same as a Gravity term). Default zero.
  Vector3<Scalar> gravity = Vector3<Scalar>::Zero();
  /// @brief Where iterations start (default Current).
  InitialGuess initial_guess = InitialGuess::Current;
  /// @brief Acceleration of the iterations (default None: plain local-global).
  Acceleration acceleration = Acceleration::None;
  /// @brief Chebyshev: spectral radius rho of the plain iteration, in [0, 1). 0 (the default):
  /// estimated by the solver on the first Chebyshev step after each factorisation, from
  /// `chebyshev_estimate_iterations` trial iterations (see chebyshev_rho()).
  Scalar chebyshev_rho = 0;
  /// @brief Chebyshev: under-relaxation gamma, in (0, 1]. Default 1: the global step is an
  /// exact solve, so nothing to damp (Wang damps Jacobi sweeps with 0.9).
  Scalar chebyshev_gamma = 1;
  /// @brief Chebyshev: plain iterations before the acceleration starts (delayed start S), >= 1.
  /// Default 2 (measured on skirt and curtain: S = 2 reaches a given error in the fewest
  /// iterations; Wang uses S = 10 for projective dynamics).
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
  /// set_threads(); refused otherwise. Pays only on large factors: docs/performance.md gives the
  /// crossover measured on 2 cores. A change takes effect at the next step (planning the split
  /// allocates, once).
  int threads = 1;
  /// @brief Use AVX2 and FMA instructions where the CPU has them (GCC or Clang on x86-64; checked
  /// at run time): in the substitutions (Sparse storage and CHOLMOD) and in the local step's pass
  /// over the springs (double). Default true: see docs/performance.md for what it gains. The
  /// substitutions' results differ from the SSE2 ones' in the last bits (fused multiply-adds), so
  /// a trajectory is the same bit for bit only between machines that take the same path: false
  /// takes the SSE2 code everywhere. The spring pass gives the same bits on either path.
  /// Compiling with MASSSPRING_NO_AVX2 defined leaves the AVX2 code out.
  bool avx2 = true;
  /// @brief The factor's elimination order (default Auto: the one with fewer nonzeros of nested
  /// dissection and the Cholesky type's own). Sparse storage only: with a Cholesky that takes no
  /// given order (Dense, CHOLMOD) Auto is its own order and NestedDissection is refused. The
  /// order changes rounding only, not the solution.
  FillOrdering ordering = FillOrdering::Auto;
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
/// Force terms of the system (system.add_force): `LinearDrag` folds into Q exactly (the term
/// beta/(2 dt) |X - X^t|^2 adds beta/dt to Q's diagonal and beta/dt X^t to the right-hand side);
/// every other term, and spring damping, is evaluated once per step at (X^t, V^t) and added to F.
/// That is exact for constant forces (Gravity, ConstantForce) and explicit, first order, for the
/// others (GravitationalAttraction, SpringDamping, user terms): evaluating them at each iterate
/// instead would move the energy each iteration descends, and lose the monotone descent and the
/// tolerance test. For implicit treatment of such terms use BackwardEuler. The options'
/// `external_force` and `gravity` are added to the system's terms.
///
/// precompute() factorises Q once (n x n, three right-hand sides). step() re-factorises only when
/// the system's revision(), the time step or the pin options changed; it allocates nothing
/// otherwise. A zero-length spring keeps the direction it had at the end of the previous step.
///
/// Inside a step the iterate lives in the factor's row order (the fill-reducing permutation), as a
/// row-major #rows x 3 array, so that an iteration is one pass over the springs (sorted by row)
/// scattering k_e d_e into the right-hand side, then one forward and one back substitution in
/// place: no permutation, no copy of the iterate, no allocation. On the AVX2 path (double) the
/// pass stores each spring's k_e d_e in an array of its own instead, and the forward substitution
/// assembles each row of the right-hand side from it as it reaches the row (see share_pass_avx2).
///
/// @tparam System a MassSpringSystem<Scalar, Storage>
/// @tparam Cholesky_ the factorisation of Q: by default the Storage's (SparseCholesky or
/// DenseCholesky); any type with compute(Matrix), permutation(), solve_in_place(Scalar*),
/// factor_nonzeros() works (e.g. CholmodCholesky from massspring/storage/cholmod.hpp); one that
/// also has solve_in_place(Scalar*, const detail::RightHandSide<Scalar>&) gets the assembly of
/// the right-hand side inside its forward substitution.
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

  /// @brief The options; read at every step.
  Options options;

  FastMassSpring() = default;
  explicit FastMassSpring(const Options& opts) : options(opts) {}

  /// @brief Builds and factorises Q for this system and time step dt [s] (finite, > 0).
  /// Allocates every buffer step() needs. Throws massspring::Error on bad input or when Q cannot
  /// be factorised.
  void precompute(const System& system, Scalar dt) {
    if (!(std::isfinite(dt) && dt > 0))
      throw Error(detail::message("FastMassSpring: dt must be finite and > 0, got ", dt));
    check_options();
    dt_ = dt;
    build(system);
  }

  /// @brief Advances the system by one time step dt. Returns what happened; when the result is not
  /// finite, the report says so and the system keeps its previous state.
  StepReport step(System& system) {
    if (!(dt_ > 0)) throw Error("FastMassSpring: step() before precompute()");
    check_options();
    StepReport report;
    if (system.revision() != revision_ || system.num_points() != n_ || options.pins != pins_ ||
        (pins_ == PinMode::Penalty && options.penalty_weight != weight_) ||
        options.ordering != ordering_) {
      build(system);
      report.refactorized = true;
    }
    apply_threads();
    prepare(system);
    Scalar* result = nullptr;
    switch (options.acceleration) {
      case Acceleration::None:
        result = run_plain(report);
        break;
      case Acceleration::Chebyshev:
        if (!(options.chebyshev_rho > 0) && !(rho_estimate_ > 0)) {
          estimate_rho();
          prepare(system);
        }
        result = run_chebyshev(report);
        break;
      case Acceleration::Anderson:
        result = run_anderson(report);
        break;
    }
    return commit(system, result, report);
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
  /// @brief The factorisation of Q.
  [[nodiscard]] const Cholesky& factorization() const { return llt_; }
  /// @brief The rho Chebyshev uses: options.chebyshev_rho when > 0, else the solver's estimate
  /// (0 until the first Chebyshev step after a factorisation has estimated it).
  [[nodiscard]] Scalar chebyshev_rho() const {
    return options.chebyshev_rho > 0 ? options.chebyshev_rho : rho_estimate_;
  }
  /// @brief Accelerated iterates replaced by the plain step because the energy rose (Chebyshev
  /// restarts, Anderson rejections), counted since construction.
  [[nodiscard]] std::size_t rejections() const { return rejections_; }

 private:
  using Buffer = Vector<Scalar>;

  struct SpringEnds {
    int a, b;  // rows of the end points in the iterate (factor order; pinned rows after), a <= b
  };
  struct Coupling {
    int row;  // iterate row of the free point
    int pin;  // row of the pinned point in system.pin_targets()
    Scalar k;
  };

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
    if (std::is_same_v<Scalar, float> && options.pins == PinMode::Penalty &&
        !options.allow_float_penalty)
      throw Error(detail::message(
          "FastMassSpring: PinMode::Penalty in float: the penalty weight w = ",
          options.penalty_weight,
          " swamps the rest of Q in single precision (about 7 digits), so the free points' "
          "equations are lost to rounding; use PinMode::Exact (the default), double, or set "
          "options.allow_float_penalty to accept it"));
    if (!options.external_force.allFinite())
      throw Error("FastMassSpring: options.external_force must be finite");
    if (!options.gravity.allFinite()) throw Error("FastMassSpring: options.gravity must be finite");
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
      throw Error(detail::message(
          "FastMassSpring: options.chebyshev_estimate_iterations must be >= 4, got ",
          options.chebyshev_estimate_iterations));
    if (options.anderson_window < 1 || options.anderson_window > kMaxWindow)
      throw Error(detail::message("FastMassSpring: options.anderson_window must be in [1, ",
                                  kMaxWindow, "], got ", options.anderson_window));
    if (options.threads < 1)
      throw Error(
          detail::message("FastMassSpring: options.threads must be >= 1, got ", options.threads));
    if constexpr (!has_ordered_compute<Cholesky>::value) {
      if (options.ordering == FillOrdering::NestedDissection)
        throw Error(
            "FastMassSpring: options.ordering = NestedDissection: this storage's Cholesky takes no "
            "given elimination order (use Sparse storage)");
    }
    if constexpr (!has_threads<Cholesky>::value) {
      if (options.threads > 1)
        throw Error(detail::message("FastMassSpring: options.threads = ", options.threads,
                                    ": this storage's Cholesky solves on one thread only (use "
                                    "Sparse storage)"));
    }
  }

  template <class C, class = void>
  struct has_threads : std::false_type {};
  template <class C>
  struct has_threads<C, std::void_t<decltype(std::declval<C&>().set_threads(1))>> : std::true_type {
  };

  template <class C, class = void>
  struct has_ordered_compute : std::false_type {};
  template <class C>
  struct has_ordered_compute<
      C, std::void_t<decltype(std::declval<C&>().compute(std::declval<const Matrix&>(),
                                                         std::declval<const std::vector<int>&>()))>>
      : std::true_type {};

  // Factorises Q in the order options.ordering asks for (see FillOrdering).
  bool factorise(const System& system) {
    if constexpr (has_ordered_compute<Cholesky>::value) {
      if (options.ordering != FillOrdering::Solver) {
        Eigen::Matrix<double, Eigen::Dynamic, 3> xyz(nr_, 3);
        for (int r = 0; r < nr_; ++r)
          xyz.row(r) = system.rest_positions().row(free_[std::size_t(r)]).template cast<double>();
        const Graph graph = graph_of(q_);
        std::size_t dissected = 0;  // nnz(L) in that order
        std::vector<int> order = nested_dissection(xyz, graph, {}, &dissected);
        if (options.ordering == FillOrdering::Auto) {
          std::vector<int> own = Cholesky::ordering_of(q_);
          if (cholesky_nonzeros(graph, own) <= dissected) order.swap(own);
        }
        return llt_.compute(q_, order);
      }
    }
    (void)system;
    return llt_.compute(q_);
  }

  template <class C, class = void>
  struct has_assembled_solve : std::false_type {};
  template <class C>
  struct has_assembled_solve<
      C, std::void_t<decltype(std::declval<const C&>().solve_in_place(
             std::declval<Scalar*>(), std::declval<const detail::RightHandSide<Scalar>&>()))>>
      : std::true_type {};

  template <class C, class = void>
  struct has_avx2 : std::false_type {};
  template <class C>
  struct has_avx2<C, std::void_t<decltype(std::declval<C&>().set_avx2(true))>> : std::true_type {};

  // The solver's threads and the AVX2 choice (substitutions, share pass) to the options'
  // (SparseCholesky::set_threads checks for OpenMP).
  void apply_threads() {
    if constexpr (has_threads<Cholesky>::value) {
      if (llt_.threads() != options.threads) llt_.set_threads(options.threads);
    }
    if constexpr (has_avx2<Cholesky>::value) llt_.set_avx2(options.avx2);
    wide_ = std::is_same_v<Scalar, double> && options.avx2 && detail::cpu_has_avx2_fma();
    assembled_in_solve_ = wide_ && has_assembled_solve<Cholesky>::value;
  }

  // ---- precompute -------------------------------------------------------------------------------

  // Q, its factor, the packed springs and every buffer step() uses. The only place that allocates.
  void build(const System& system) {
    n_ = system.num_points();
    pins_ = options.pins;
    weight_ = options.penalty_weight;
    revision_ = system.revision();
    rho_estimate_ = 0;
    const bool exact = pins_ == PinMode::Exact;
    const int m = system.num_springs();
    const auto& springs = system.springs();
    const auto& k = system.stiffness();
    const auto& mass = system.masses();
    const Scalar inv_dt2 = Scalar(1) / (dt_ * dt_);

    // Reduced row (of Q) of each point; with exact pins, pinned points have none.
    std::vector<int> reduced(std::size_t(n_), -1);
    free_.clear();
    for (int i = 0; i < n_; ++i)
      if (!(exact && system.is_pinned(i))) {
        reduced[std::size_t(i)] = int(free_.size());
        free_.push_back(i);
      }
    nr_ = int(free_.size());

    std::vector<Triplet> t;
    t.reserve(std::size_t(4 * m + n_));
    for (int e = 0; e < m; ++e) {
      const int ri = reduced[std::size_t(springs(e, 0))], rj = reduced[std::size_t(springs(e, 1))];
      if (ri >= 0) t.emplace_back(ri, ri, k(e));
      if (rj >= 0) t.emplace_back(rj, rj, k(e));
      if (ri >= 0 && rj >= 0) {
        t.emplace_back(ri, rj, -k(e));
        t.emplace_back(rj, ri, -k(e));
      }
    }
    // The system's force terms: linear drag folds into Q exactly (beta/(2 dt) |X - X^t|^2 adds
    // beta/dt to the diagonal); every other term is evaluated once per step (see prepare()).
    drag_ = 0;
    other_terms_ = system.has_spring_damping();
    for (const auto& term : system.forces()) {
      if (term->is_drag)
        drag_ += term->drag_coefficient();
      else
        other_terms_ = true;
    }
    term_force_.setZero(other_terms_ ? n_ : 0, 3);
    const Scalar drag_diagonal = drag_ / dt_;
    for (int r = 0; r < nr_; ++r)
      t.emplace_back(r, r, mass(free_[std::size_t(r)]) * inv_dt2 + drag_diagonal);
    if (!exact)
      for (int p : system.pinned()) t.emplace_back(p, p, weight_);
    q_ = Traits::from_triplets(nr_, nr_, t);
    std::vector<Triplet>().swap(t);
    apply_threads();
    ordering_ = options.ordering;
    if (!factorise(system))
      throw Error(
          detail::message("FastMassSpring: Q = A^T K A + M / dt^2", exact ? "" : " + w C^T C",
                          " is not numerically positive definite (dt = ", dt_,
                          exact ? "" : detail::message(", penalty weight = ", weight_), ")"));

    // Iterate rows: free points in the factor's order, then (exact pins) the pinned points.
    const Eigen::VectorXi& perm = llt_.permutation();
    const int np = exact ? system.num_pinned() : 0;
    nx_ = nr_ + np;
    row_.assign(std::size_t(n_), 0);
    point_.assign(std::size_t(nx_), 0);
    for (int r = 0; r < nr_; ++r) {
      row_[std::size_t(free_[std::size_t(r)])] = perm(r);
      point_[std::size_t(perm(r))] = free_[std::size_t(r)];
    }
    for (int p = 0; p < np; ++p) {
      const int i = system.pinned()[std::size_t(p)];
      row_[std::size_t(i)] = nr_ + p;
      point_[std::size_t(nr_ + p)] = i;
    }
    penalty_rows_.clear();
    if (!exact)
      for (int p : system.pinned()) penalty_rows_.push_back(row_[std::size_t(p)]);

    // Springs sorted by their lower row a, then by the higher row b. The local step then sums
    // row a's share in registers over its run and scatters into row b only, with no
    // read-modify-write chain through memory (see spring_pass).
    order_.resize(std::size_t(m));
    flipped_.clear();
    flipped_.reserve(std::size_t(m));
    std::iota(order_.begin(), order_.end(), 0);
    const auto key = [&](int e) {
      const int a = row_[std::size_t(springs(e, 0))], b = row_[std::size_t(springs(e, 1))];
      return std::pair<int, int>(std::min(a, b), std::max(a, b));
    };
    std::sort(order_.begin(), order_.end(), [&](int x, int y) { return key(x) < key(y); });
    ends_.resize(std::size_t(m));
    stiffness_.resize(m);
    rest_.resize(m);
    kr_.resize(m);
    coupling_.clear();
    for (int s = 0; s < m; ++s) {
      const int e = order_[std::size_t(s)];
      const int i = row_[std::size_t(springs(e, 0))], j = row_[std::size_t(springs(e, 1))];
      const int a = std::min(i, j), b = std::max(i, j);
      // Stored as (a, b): d = x_a - x_b, which flips the sign of the spring's direction when
      // i > j; the direction of a zero-length spring is kept in that orientation.
      ends_[std::size_t(s)] = {a, b};
      stiffness_(s) = k(e);
      flipped_.push_back(i > j);
      // -Q_FP X_P: a free point joined to a pinned one (rows after the free ones, so b) is pulled
      // by k x_pinned.
      if (a < nr_ && b >= nr_) coupling_.push_back({a, b - nr_, k(e)});
    }
    mass_h2_.resize(nr_);
    for (int r = 0; r < nr_; ++r)
      mass_h2_(r) = mass(point_[std::size_t(r)]) * inv_dt2 + drag_ / dt_;

    const Eigen::Index size = 3 * Eigen::Index(nx_), free_size = 3 * Eigen::Index(nr_);
    // One value more than the iterate's rows: share_pass_avx2 loads the last row as four values.
    for (Buffer& b : buffers_) b.setZero(size + 1);
    run_sum_.setZero(size);
    rhs0_.resize(free_size);
    // share_pass_avx2's shares and the right-hand side assembled from them, only where it can run
    // (options.avx2 may change later). Row a's run of springs is plus_begin_[a] ..
    // plus_begin_[a + 1] - 1 (sorted by a); the springs whose b is row r are listed in
    // minus_share_[minus_begin_[r] ..], ascending, as the baseline pass subtracts them.
    shares_.resize(0);
    plus_begin_.clear();
    minus_begin_.clear();
    minus_share_.clear();
    if (std::is_same_v<Scalar, double> && detail::cpu_has_avx2_fma()) {
      shares_.setZero(4 * Eigen::Index(m) + 4);  // room to start at a 32-byte boundary
      plus_begin_.assign(std::size_t(nx_) + 1, 0);
      minus_begin_.assign(std::size_t(nx_) + 1, 0);
      for (const SpringEnds& s : ends_) {
        ++plus_begin_[std::size_t(s.a) + 1];
        ++minus_begin_[std::size_t(s.b) + 1];
      }
      for (std::size_t r = 0; r < std::size_t(nx_); ++r) {
        plus_begin_[r + 1] += plus_begin_[r];
        minus_begin_[r + 1] += minus_begin_[r];
      }
      minus_share_.resize(std::size_t(m));
      std::vector<int> next(minus_begin_.begin(), minus_begin_.end() - 1);
      for (int s = 0; s < m; ++s)
        minus_share_[std::size_t(next[std::size_t(ends_[std::size_t(s)].b)]++)] = s;
    }
    inertial_.resize(free_size);
    force_.resize(free_size);
    targets_.resize(3 * Eigen::Index(np));
    penalty_targets_.resize(3 * Eigen::Index(penalty_rows_.size()));
    direction_.resize(3 * Eigen::Index(m));
    for (int s = 0; s < m; ++s) {
      const int e = order_[std::size_t(s)];
      Vector3<Scalar> u =
          (system.positions().row(springs(e, 0)) - system.positions().row(springs(e, 1)))
              .transpose();
      if (!(u.norm() > 0))
        u = (system.rest_positions().row(springs(e, 0)) -
             system.rest_positions().row(springs(e, 1)))
                .transpose();
      if (u.norm() > 0) u.normalize();
      direction_.template segment<3>(3 * s) = flipped_[std::size_t(s)] ? Vector3<Scalar>(-u) : u;
    }
    // Anderson's history: the differences of the last `window` residuals and maps, column-major.
    const int window = options.acceleration == Acceleration::Anderson ? options.anderson_window : 0;
    df_.setZero(free_size, window);
    dg_.setZero(free_size, window);
  }

  // ---- per step ---------------------------------------------------------------------------------

  Vector3<Scalar> force_on(const System& system, int i) const {
    return options.external_force + system.masses()(i) * options.gravity;
  }

  // Inertial prediction, constant part of the right-hand side, starting iterate (buffer 0),
  // current rest lengths and pin targets.
  void prepare(const System& system) {
    const auto& x = system.positions();
    const auto& v = system.velocities();
    const Scalar inv_dt2 = Scalar(1) / (dt_ * dt_);
    const bool inertial_guess = options.initial_guess == InitialGuess::Inertial;
    Scalar* x0 = buffers_[0].data();
    if (other_terms_) {
      // Terms other than drag (gravity, constant forces, attraction, spring damping, the user's)
      // at the step's start (x^t, v^t): constant over the step, so each iteration still descends
      // one fixed energy. Exact for constant forces; explicit (first order) for the others.
      term_force_.setZero();
      const auto context = system.force_context(x, v);
      if (system.has_spring_damping()) SpringDamping<Scalar>{}.add_force(context, term_force_);
      for (const auto& term : system.forces())
        if (!term->is_drag) term->add_force(context, term_force_);
    }
    const Scalar drag_h = drag_ / dt_;
    for (int r = 0; r < nr_; ++r) {
      const int i = point_[std::size_t(r)];
      Vector3<Scalar> f = force_on(system, i);
      if (other_terms_) f += term_force_.row(i).transpose();
      const Scalar mh = system.masses()(i) * inv_dt2;
      for (int c = 0; c < 3; ++c) {
        const Scalar y = x(i, c) + dt_ * v(i, c);
        // m/(2h^2)|x - y|^2 + beta/(2h)|x - x^t|^2 = (m/h^2 + beta/h)/2 |x - y'|^2 + const.
        inertial_(3 * r + c) = drag_ > 0 ? (mh * y + drag_h * x(i, c)) / (mh + drag_h) : y;
        force_(3 * r + c) = f(c);
        rhs0_(3 * r + c) = mh * y + drag_h * x(i, c) + f(c);
        x0[3 * r + c] = inertial_guess ? y : x(i, c);
      }
    }
    const auto& targets = system.pin_targets();
    if (pins_ == PinMode::Penalty) {
      for (std::size_t p = 0; p < penalty_rows_.size(); ++p)
        for (int c = 0; c < 3; ++c) {
          penalty_targets_(3 * Eigen::Index(p) + c) = targets(Eigen::Index(p), c);
          rhs0_(3 * penalty_rows_[p] + c) += weight_ * targets(Eigen::Index(p), c);
        }
    } else {
      for (int p = 0; p < nx_ - nr_; ++p)
        for (int c = 0; c < 3; ++c) targets_(3 * p + c) = targets(p, c);
      for (const Coupling& cp : coupling_)
        for (int c = 0; c < 3; ++c) rhs0_(3 * cp.row + c) += cp.k * targets(cp.pin, c);
      for (Buffer& b : buffers_) restore_pins(b.data());
    }
    const auto& rest = system.rest_lengths();
    for (Eigen::Index s = 0; s < rest_.size(); ++s) {
      rest_(s) = rest(order_[std::size_t(s)]);
      kr_(s) = stiffness_(s) * rest_(s);
    }
  }

  // Pinned rows (exact pins) back to their targets, after a solve or a scatter wrote into them.
  void restore_pins(Scalar* x) const {
    const Eigen::Index np = targets_.size();
    if (np > 0) std::copy_n(targets_.data(), np, x + 3 * Eigen::Index(nr_));
  }

  // One pass over the springs at the iterate x. With Scatter (the local step) it adds
  // A^T K D into w (rows of pinned points get garbage, see restore_pins); with Energy it returns
  // the springs' energy; with neither (after the last iteration) it records each spring's
  // direction, which a spring of zero length keeps at the next step.
  //
  // Springs are sorted by (a, b), a <= b, and go two at a time whatever their rows: the two
  // square roots and the two divisions k r / |d| share one SSE2 instruction each
  // (detail::lengths2), and no branch depends on where a row's run of springs ends (about five
  // springs on a cloth, at irregular intervals: a branch the predictor most likely misses, each
  // time draining the divisions in flight; without it the pairs paid, with it they did not). Row
  // a's share is summed in registers over its run, restarted where the run starts by a
  // multiplication with 0 instead of a branch, and stored to run_sum_ after every spring, so that
  // the last store holds the run's sum; run_sum_ is added to w after the pass. Row a's other
  // additions (as the b of springs of lower rows) all come before that, as they came before the end
  // of its run when the sum was added there. Rows that start no run keep run_sum_ at 0.
  template <bool Scatter, bool Energy>
  double spring_pass(const Scalar* x, Scalar* w) {
    const SpringEnds* sp = ends_.data();
    const Scalar* k = stiffness_.data();
    const Scalar* r = rest_.data();
    const Scalar* kr = kr_.data();
    const int m = int(ends_.size());
    Scalar* dir = direction_.data();
    Scalar* sums = run_sum_.data();
    double energy = 0;
    int previous = -1;
    Scalar acc0 = 0, acc1 = 0, acc2 = 0;  // k_e r_e d_e / |d_e| summed over row a's run so far
    // Springs e and e + 1 (N = 2), or the odd last one (N = 1).
    const auto springs_at = [&](int e, auto lanes) MASSSPRING_LAMBDA_ALWAYS_INLINE {
      constexpr int N = decltype(lanes)::value;
      Scalar d[2][3], sq[2], len[2], f[2], num[2];
      MASSSPRING_UNROLL
      for (int i = 0; i < 2; ++i) {
        const int q = e + (i < N ? i : 0);  // N = 1: the second lane is not used
        const SpringEnds& s = sp[q];
        num[i] = Scatter ? kr[q] : Scalar(1);
        const Scalar* xa = x + 3 * s.a;
        const Scalar* xb = x + 3 * s.b;
        d[i][0] = xa[0] - xb[0], d[i][1] = xa[1] - xb[1], d[i][2] = xa[2] - xb[2];
        sq[i] = d[i][0] * d[i][0] + d[i][1] * d[i][1] + d[i][2] * d[i][2];
      }
      detail::lengths2(sq, num, len, f);  // f = k r / |d| (Scatter) or 1 / |d|
      MASSSPRING_UNROLL
      for (int i = 0; i < N; ++i) {
        const SpringEnds& s = sp[e + i];
        if constexpr (Energy) {
          const Scalar stretch = len[i] - r[e + i];
          energy += double(k[e + i] * stretch * stretch);
        }
        if constexpr (Scatter) {
          Scalar s0, s1, s2;  // k_e r_e times the spring's unit direction
          if (sq[i] > 0) {
            s0 = f[i] * d[i][0], s1 = f[i] * d[i][1], s2 = f[i] * d[i][2];
          } else {
            const Scalar* u = dir + 3 * (e + i);
            s0 = num[i] * u[0], s1 = num[i] * u[1], s2 = num[i] * u[2];
          }
          // acc * 1 + s is acc + s and acc * 0 + s is s, exactly, for finite acc (a NaN or an
          // infinity reaches the next row too, where the substitution would take it anyway).
          const Scalar keep = Scalar(s.a == previous);
          previous = s.a;
          acc0 = acc0 * keep + s0, acc1 = acc1 * keep + s1, acc2 = acc2 * keep + s2;
          Scalar* sa = sums + 3 * s.a;
          sa[0] = acc0, sa[1] = acc1, sa[2] = acc2;
          Scalar* wb = w + 3 * s.b;
          wb[0] -= s0, wb[1] -= s1, wb[2] -= s2;
        } else if (sq[i] > 0) {
          Scalar* u = dir + 3 * (e + i);
          u[0] = d[i][0] * f[i], u[1] = d[i][1] * f[i], u[2] = d[i][2] * f[i];
        }
      }
    };
    int e = 0;
    for (; e + 1 < m; e += 2) springs_at(e, std::integral_constant<int, 2>{});
    if (e < m) springs_at(e, std::integral_constant<int, 1>{});
    if constexpr (Scatter) {
      const Eigen::Index size = 3 * Eigen::Index(nx_);
      for (Eigen::Index i = 0; i < size; ++i) w[i] += sums[i];
    }
    return energy / 2;
  }

#ifdef MASSSPRING_HAVE_AVX2_PATH
  // The local step's pass over the springs compiled for AVX2, doubles only: each spring's share
  // k r d / |d| is stored in shares (shares_ from share_start(), four values per spring), and
  // the right-hand side is assembled from them where a row is needed (assembled().row(), or
  // inside the forward substitution: see detail::RightHandSide), in the order the baseline pass
  // adds them: row b's subtractions in the order of the springs, then row a's run summed first to
  // last and added. A point's three coordinates are one 256-bit register (fourth lane 0); four
  // springs share one vsqrtpd and one vdivpd; |d|^2 is summed as (x^2 + y^2) + z^2 as in the
  // baseline: the same results, bit for bit (tested through Dense storage, whose solve assembles
  // the right-hand side before it). Storing the shares instead of scattering them into the
  // right-hand side (the earlier AVX2 pass) removes every read-modify-write of a row from the
  // pass, the run sums with their 0/1 restarts and the pass that added them, and the copy of
  // rhs0. The earlier pass's time also depended on where its arrays lay in memory: 103 or 168 us
  // on the curtain, 12 or 20 us on a 32 x 32 cloth, from run to run of one binary; the share pass
  // does not vary. An iteration takes 5-12% less time (32^2 to 128^2 and the curtain; a throwaway
  // driver, quoted in the notes of docs/performance.md). Float stays on the baseline pass.
  //
  // Without Shares it is the baseline pass's energy_at() instead: no shares, each spring of
  // nonzero length has its direction d / |d| recorded (with the same rounding: 1 / |d| by one
  // division, then three products), and the energy summed in the same order.
  template <bool Energy, bool Shares = true>
  MASSSPRING_TARGET_AVX2 double share_pass_avx2(const double* x) {
    const int m = int(ends_.size());
    // The arrays in locals: a store through __m256d may alias anything, so members would be
    // read again after every store.
    const SharePass pass{x,
                         ends_.data(),
                         kr_.data(),
                         rest_.data(),
                         stiffness_.data(),
                         direction_.data(),
                         Shares ? share_start() : nullptr};
    double energy = 0;
    int e = 0;
    for (; e + 3 < m; e += 4) springs4_avx2<Energy, Shares, 4>(pass, e, energy);
    switch (m - e) {
      case 3:
        springs4_avx2<Energy, Shares, 3>(pass, e, energy);
        break;
      case 2:
        springs4_avx2<Energy, Shares, 2>(pass, e, energy);
        break;
      case 1:
        springs4_avx2<Energy, Shares, 1>(pass, e, energy);
        break;
      default:
        break;
    }
    return energy / 2;
  }

  // What share_pass_avx2 reads and writes.
  struct SharePass {
    const double* x;  // the iterate, one double readable past its last row (see precompute)
    const SpringEnds* ends;
    const double *kr, *rest, *stiffness;
    double* direction;  // written without shares only
    double* shares;
  };

  // p[0 .. 3]; for N < 4, lanes N .. 3 repeat p[N - 1] (never read past the array).
  template <int N>
  MASSSPRING_TARGET_AVX2 MASSSPRING_ALWAYS_INLINE static __m256d load4(const double* p) {
    if constexpr (N == 4)
      return _mm256_loadu_pd(p);
    else
      return _mm256_set_pd(p[std::min(3, N - 1)], p[std::min(2, N - 1)], p[std::min(1, N - 1)],
                           p[0]);
  }

  // Lane i of v in all four lanes (the permutation needs an immediate: i is one once unrolled).
  MASSSPRING_TARGET_AVX2 MASSSPRING_ALWAYS_INLINE static __m256d broadcast_lane(__m256d v, int i) {
    switch (i) {
      case 0:
        return _mm256_permute4x64_pd(v, 0x00);
      case 1:
        return _mm256_permute4x64_pd(v, 0x55);
      case 2:
        return _mm256_permute4x64_pd(v, 0xAA);
      default:
        return _mm256_permute4x64_pd(v, 0xFF);
    }
  }

  // Springs e .. e + N - 1 (N <= 4) of share_pass_avx2; lanes N .. 3 repeat spring e, unused.
  template <bool Energy, bool Shares, int N>
  MASSSPRING_TARGET_AVX2 MASSSPRING_ALWAYS_INLINE static void springs4_avx2(const SharePass& pass,
                                                                            int e, double& energy) {
    const SpringEnds* sp = pass.ends + e;
    const double* x = pass.x;
    // d = x_a - x_b from two plain 256-bit loads, the fourth lane (the next row's first value, or
    // the padding after the last row) set to 0: with the arrays in locals (SharePass), the pass
    // took 53 instead of 60 us on the curtain and 19.8 instead of 22.3 us on flag, an iteration
    // 3% less (a throwaway driver, best of 15; docs/performance.md).
    __m256d d[4];
    MASSSPRING_UNROLL
    for (int i = 0; i < 4; ++i) {
      const SpringEnds& s = sp[i < N ? i : 0];
      d[i] =
          _mm256_blend_pd(_mm256_sub_pd(_mm256_loadu_pd(x + 3 * s.a), _mm256_loadu_pd(x + 3 * s.b)),
                          _mm256_setzero_pd(), 0x8);
    }
    // hadd(p, q) = (p0 + p1, q0 + q1, p2 + p3, q2 + q3), and p3 = q3 = 0: the squared lengths'
    // x^2 + y^2 in the low halves, z^2 in the high ones.
    const __m256d t0 = _mm256_hadd_pd(_mm256_mul_pd(d[0], d[0]), _mm256_mul_pd(d[1], d[1]));
    const __m256d t1 = _mm256_hadd_pd(_mm256_mul_pd(d[2], d[2]), _mm256_mul_pd(d[3], d[3]));
    const __m256d sq =
        _mm256_add_pd(_mm256_permute2f128_pd(t0, t1, 0x20), _mm256_permute2f128_pd(t0, t1, 0x31));
    const __m256d len = _mm256_sqrt_pd(sq);
    // The clamp of detail::lengths2: f is finite, and unused, where sq is 0 or NaN.
    const __m256d f = _mm256_div_pd(Shares ? load4<N>(pass.kr + e) : _mm256_set1_pd(1.0),
                                    _mm256_max_pd(len, _mm256_set1_pd(0x1p-537)));
    if constexpr (Energy) {
      const __m256d stretch = _mm256_sub_pd(len, load4<N>(pass.rest + e));
      alignas(32) double lane[4];
      _mm256_store_pd(lane,
                      _mm256_mul_pd(_mm256_mul_pd(load4<N>(pass.stiffness + e), stretch), stretch));
      MASSSPRING_UNROLL
      for (int i = 0; i < N; ++i) energy += lane[i];
    }
    const int positive = _mm256_movemask_pd(_mm256_cmp_pd(sq, _mm256_setzero_pd(), _CMP_GT_OQ));
    if constexpr (!Shares) {
      double* dir = pass.direction + 3 * std::ptrdiff_t(e);
      MASSSPRING_UNROLL
      for (int i = 0; i < N; ++i)
        if (positive >> i & 1) {  // d / |d|; a spring of zero length keeps its direction
          const __m256d u = _mm256_mul_pd(broadcast_lane(f, i), d[i]);
          _mm_storeu_pd(dir + 3 * i, _mm256_castpd256_pd128(u));
          _mm_store_sd(dir + 3 * i + 2, _mm256_extractf128_pd(u, 1));
        }
    } else {
      double* shares = pass.shares + 4 * std::ptrdiff_t(e);
      const __m256i three = _mm256_setr_epi64x(-1, -1, -1, 0);
      MASSSPRING_UNROLL
      for (int i = 0; i < N; ++i) {
        // k r / |d| times d; fourth lane 0
        __m256d s = _mm256_mul_pd(broadcast_lane(f, i), d[i]);
        if (!(positive >> i & 1))  // zero length (or NaN): k r along the direction kept
          s = _mm256_mul_pd(_mm256_set1_pd(pass.kr[e + i]),
                            _mm256_maskload_pd(pass.direction + 3 * (e + i), three));
        _mm256_store_pd(shares + 4 * i, s);
      }
    }
  }
#endif

  // With Write, w = rhs0 on the free rows; with Energy, returns the iterate-dependent energy other
  // than the springs' (inertia, external force, penalty) at x, in the same pass.
  template <bool Energy, bool Write = true>
  double start_rhs(const Scalar* x, Scalar* w) const {
    const Scalar* b0 = rhs0_.data();
    const Eigen::Index size = 3 * Eigen::Index(nr_);
    if constexpr (!Energy) {
      std::copy_n(b0, size, w);
      return 0;
    } else {
      const Scalar* y = inertial_.data();
      const Scalar* f = force_.data();
      const Scalar* mh = mass_h2_.data();
      double energy = 0;
      for (int r = 0; r < nr_; ++r) {
        const Scalar* xr = x + 3 * r;
        const Scalar e0 = xr[0] - y[3 * r], e1 = xr[1] - y[3 * r + 1], e2 = xr[2] - y[3 * r + 2];
        energy += double(mh[r] / 2 * (e0 * e0 + e1 * e1 + e2 * e2) -
                         (xr[0] * f[3 * r] + xr[1] * f[3 * r + 1] + xr[2] * f[3 * r + 2]));
        if constexpr (Write) {
          w[3 * r] = b0[3 * r];
          w[3 * r + 1] = b0[3 * r + 1];
          w[3 * r + 2] = b0[3 * r + 2];
        }
      }
      for (std::size_t p = 0; p < penalty_rows_.size(); ++p) {
        const Scalar* xp = x + 3 * penalty_rows_[p];
        const Scalar* tp = penalty_targets_.data() + 3 * p;
        const Scalar e0 = xp[0] - tp[0], e1 = xp[1] - tp[1], e2 = xp[2] - tp[2];
        energy += double(weight_ / 2 * (e0 * e0 + e1 * e1 + e2 * e2));
      }
      return energy;
    }
  }

  // shares_'s first value on a 32-byte boundary (computed at each use: a copy of the solver has
  // buffers of its own, aligned differently).
  Scalar* share_start() {
    const auto address = reinterpret_cast<std::uintptr_t>(shares_.data());
    return shares_.data() + (32 - address % 32) % 32 / sizeof(Scalar);
  }

  // rhs0 plus the shares, as the forward substitution assembles it (see detail::RightHandSide).
  detail::RightHandSide<Scalar> assembled() {
    detail::RightHandSide<Scalar> rhs;
    rhs.base = rhs0_.data();
    rhs.shares = share_start();
    rhs.plus_begin = plus_begin_.data();
    rhs.minus_begin = minus_begin_.data();
    rhs.minus_share = minus_share_.data();
    return rhs;
  }

  // The local step at x into w (w = rhs0 + A^T K D); returns E(x) when Energy. On the AVX2 path
  // with a factorisation that assembles the right-hand side itself, only the springs' shares are
  // computed and w is left as it is: global_step() must follow before w is read.
  template <bool Energy>
  double local_step(const Scalar* x, Scalar* w) {
#ifdef MASSSPRING_HAVE_AVX2_PATH
    if constexpr (std::is_same_v<Scalar, double>) {
      if (wide_) {
        double energy = 0;
        if constexpr (Energy) energy = start_rhs<true, false>(x, nullptr);
        energy += share_pass_avx2<Energy>(x);
        if (!assembled_in_solve_) {
          const detail::RightHandSide<Scalar> rhs = assembled();
          for (int r = 0; r < nr_; ++r) rhs.row(r, w + 3 * r);
        }
        return energy;
      }
    }
#endif
    const double quadratic = start_rhs<Energy>(x, w);
    return quadratic + spring_pass<true, Energy>(x, w);
  }

  // The global step in place: w = Q^-1 w on the free rows (w = Q^-1 (rhs0 + A^T K D) assembled
  // from the shares, see local_step()); pinned rows restored.
  void global_step(Scalar* w) {
    if constexpr (has_assembled_solve<Cholesky>::value) {
      if (assembled_in_solve_) {
        llt_.solve_in_place(w, assembled());
        restore_pins(w);
        return;
      }
    }
    llt_.solve_in_place(w);
    restore_pins(w);
  }

  // One whole iteration, w = G(x) = Q^-1 (rhs0 + A^T K D(x)), returning E(x) when Energy.
  template <bool Energy>
  double iteration(const Scalar* x, Scalar* w) {
    const double energy = local_step<Energy>(x, w);
    global_step(w);
    return energy;
  }

  // E at x without touching any right-hand side (and recording the springs' directions).
  double energy_at(const Scalar* x) {
#ifdef MASSSPRING_HAVE_AVX2_PATH
    if constexpr (std::is_same_v<Scalar, double>)
      if (wide_) return start_rhs<true, false>(x, nullptr) + share_pass_avx2<true, false>(x);
#endif
    return start_rhs<true, false>(x, nullptr) + spring_pass<false, true>(x, nullptr);
  }

  // Relative-decrease bookkeeping shared by the loops; true when the tolerance stop fires.
  bool tolerance_met(StepReport& report, int k, double e0, double e_prev, double e) const {
    if (!(options.tolerance > 0) || k == 0) return false;
    report.relative_decrease = relative(e_prev - e, e0 - e);
    if (report.relative_decrease <= double(options.tolerance)) {
      report.converged = true;
      return true;
    }
    return false;
  }

  // ---- the iterations ---------------------------------------------------------------------------

  // Plain local-global. Energy only where it is reported or the tolerance needs it.
  Scalar* run_plain(StepReport& report) {
    Scalar* x = buffers_[0].data();
    Scalar* w = buffers_[1].data();
    const int cap = options.iterations;
    const bool track = options.tolerance > 0;
    double e0 = 0, e_prev = 0;
    for (int k = 0; k < cap; ++k) {
      if (track || k == 0 || k == cap - 1) {
        const double e = iteration<true>(x, w);
        if (k == 0) e0 = e;
        // The tolerance is judged at x: w (one more solve, already done) is dropped.
        if (tolerance_met(report, k, e0, e_prev, e)) break;
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
    if (!report.converged) report.relative_decrease = relative(e_prev - e, e0 - e);
    return x;
  }

  // Trial plain iterations from the prepared start; rho from the ratio of update norms over the
  // second half. Uses buffers 0 and 1 (prepare() must run again afterwards).
  void estimate_rho() {
    const int iterations = options.chebyshev_estimate_iterations;
    const int half = iterations / 2;
    Scalar* x = buffers_[0].data();
    Scalar* w = buffers_[1].data();
    const Eigen::Index size = 3 * Eigen::Index(nr_);
    double norm_half = 0, norm_last = 0;
    for (int k = 0; k < iterations; ++k) {
      local_step<false>(x, w);
      global_step(w);
      if (k == half - 1 || k == iterations - 1) {
        const double d = (Eigen::Map<const Buffer>(w, size) - Eigen::Map<const Buffer>(x, size))
                             .template cast<double>()
                             .norm();
        (k == half - 1 ? norm_half : norm_last) = d;
      }
      std::swap(x, w);
    }
    const double rho = std::pow(norm_last / norm_half, 1.0 / double(iterations - half));
    rho_estimate_ = std::isfinite(rho) && rho > 0 && rho < 1 ? Scalar(rho) : Scalar(0);
  }

  // Chebyshev semi-iterative acceleration (Wang 2015) with an energy-monotone restart.
  Scalar* run_chebyshev(StepReport& report) {
    const double rho = double(chebyshev_rho());
    const double gamma = double(options.chebyshev_gamma);
    const int delay = options.chebyshev_delay;
    const Eigen::Index size = 3 * Eigen::Index(nr_);
    // x: x_k; p: x_{k-1}; h: G(x_{k-1}) (the plain iterate, E(h) <= E(x_{k-1})); w: free.
    Scalar* x = buffers_[0].data();
    Scalar* p = buffers_[1].data();
    Scalar* h = buffers_[2].data();
    Scalar* w = buffers_[3].data();
    std::copy_n(x, 3 * Eigen::Index(nx_), p);
    std::copy_n(x, 3 * Eigen::Index(nx_), h);
    const int cap = options.iterations;
    double e0 = 0, e_prev = 0, omega = 1;
    int since = 0;  // iterations since the (re)start
    for (int k = 0; k < cap; ++k) {
      double e = local_step<true>(x, w);
      if (k == 0) e0 = e;
      if (k > 0 && !(e <= e_prev)) {
        // The energy rose (or is not finite): back to the plain iterate, momentum dropped.
        std::swap(x, h);
        std::copy_n(x, size, p);
        since = 0;
        e = local_step<true>(x, w);
        ++rejections_;
      }
      if (tolerance_met(report, k, e0, e_prev, e)) break;
      e_prev = e;
      global_step(w);  // w = G(x_k)
      ++report.iterations;
      ++since;
      if (since < delay || !(rho > 0)) {
        omega = 1;
      } else if (since == delay) {
        omega = 2 / (2 - rho * rho);
      } else {
        omega = 4 / (4 - rho * rho * omega);
      }
      if (omega == 1 && gamma == 1) {
        // x_{k+1} = G(x_k): rotate, no arithmetic.
        Scalar* old_p = p;  // never x_k or G(x_k): the one buffer free after the rotation
        p = x;
        x = w;
        h = w;
        w = old_p;
      } else {
        const auto om = Scalar(omega), ga = Scalar(gamma);
        for (Eigen::Index i = 0; i < size; ++i)
          p[i] = om * (ga * (w[i] - x[i]) + x[i] - p[i]) + p[i];
        // Now p = x_{k+1}, x = x_k, w = G(x_k).
        Scalar* old_h = h;
        h = w;
        std::swap(x, p);
        w = old_h == x || old_h == p || old_h == h ? free_buffer(x, p, h) : old_h;
      }
    }
    // The last iterate is accepted only when its energy is not above the last evaluated one;
    // otherwise the plain iterate G(x_{k-1}) (never above it) is returned.
    double e = energy_at(x);
    if (report.iterations > 0 && !(e <= e_prev) && x != h) {
      x = h;
      e = energy_at(x);
    }
    report.energy = e;
    if (!report.converged && report.iterations > 0)
      report.relative_decrease = relative(e_prev - e, e0 - e);
    return x;
  }

  // The one buffer of the four not among a, b, c (which may coincide).
  Scalar* free_buffer(const Scalar* a, const Scalar* b, const Scalar* c) {
    for (Buffer& buf : buffers_)
      if (buf.data() != a && buf.data() != b && buf.data() != c) return buf.data();
    return nullptr;
  }

  // Anderson acceleration (Peng et al. 2018, Algorithm 2): the energy at each iterate decides
  // between the accelerated iterate and the plain step from the last accepted one.
  Scalar* run_anderson(StepReport& report) {
    const Eigen::Index size = 3 * Eigen::Index(nr_);
    const int window = options.anderson_window;
    if (window > df_.cols()) {  // Anderson chosen, or its window enlarged, after precompute()
      df_.setZero(size, window);
      dg_.setZero(size, window);
    }
    // x: x_k (pinned rows fixed, never swapped); w: right-hand side, then G(x_k); g: G of the last
    // accepted iterate (the fallback); f: its residual G - x; fn: the new residual.
    Scalar* x = buffers_[0].data();
    Scalar* w = buffers_[1].data();
    Scalar* g = buffers_[2].data();
    Scalar* f = buffers_[3].data();
    Scalar* fn = buffers_[4].data();
    int count = 0, slot = 0;
    bool have_previous = false;
    const int cap = options.iterations;
    double e0 = 0, e_prev = 0;
    for (int k = 0; k < cap; ++k) {
      double e = local_step<true>(x, w);
      if (k == 0) e0 = e;
      if (k > 0 && !(e < e_prev)) {
        // Rejected: the plain step from the last accepted iterate, whose energy is <= e_prev.
        std::copy_n(g, size, x);
        count = 0;
        slot = 0;
        have_previous = false;
        e = local_step<true>(x, w);
        ++rejections_;
      }
      if (tolerance_met(report, k, e0, e_prev, e)) break;
      e_prev = e;
      global_step(w);  // w = G(x_k)
      ++report.iterations;
      // Residual, new history column and its inner products, in one pass.
      const int s = slot;
      Scalar* dfs = df_.col(s).data();
      Scalar* dgs = dg_.col(s).data();
      if (have_previous) {
        double dfs_f = 0, dfs_dfs = 0;
        for (Eigen::Index i = 0; i < size; ++i) {
          const Scalar r = w[i] - x[i];
          const Scalar d = r - f[i];
          fn[i] = r;
          dfs[i] = d;
          dgs[i] = w[i] - g[i];
          dfs_f += double(d * r);
          dfs_dfs += double(d * d);
        }
        count = std::min(count + 1, window);
        slot = (slot + 1) % window;
        const Eigen::Map<const Buffer> dfs_map(dfs, size), fn_map(fn, size);
        for (int j = 0; j < count; ++j) {
          if (j == s) {
            gram_(s, s) = dfs_dfs;
            rhs_(s) = dfs_f;
          } else {
            gram_(s, j) = gram_(j, s) = double(df_.col(j).dot(dfs_map));
            rhs_(j) = double(df_.col(j).dot(fn_map));
          }
        }
      } else {
        for (Eigen::Index i = 0; i < size; ++i) fn[i] = w[i] - x[i];
      }
      std::swap(f, fn);  // f = residual of x_k
      std::swap(g, w);   // g = G(x_k), w free
      have_previous = true;
      // x_{k+1} = G(x_k) - dG theta, theta = argmin |f - dF theta|.
      if (count > 0 && solve_normal_equations(count)) {
        for (Eigen::Index i = 0; i < size; ++i) {
          Scalar v = g[i];
          for (int j = 0; j < count; ++j) v -= Scalar(theta_[std::size_t(j)]) * dg_(i, j);
          x[i] = v;
        }
      } else {
        count = 0;
        slot = 0;
        std::copy_n(g, size, x);
      }
    }
    // Accept the last iterate only if it is not above the last accepted energy.
    double e = energy_at(x);
    if (report.iterations > 0 && !(e <= e_prev)) {
      std::copy_n(g, size, x);
      e = energy_at(x);
    }
    report.energy = e;
    if (!report.converged && report.iterations > 0)
      report.relative_decrease = relative(e_prev - e, e0 - e);
    return x;
  }

  // theta = (dF^T dF + eps I)^-1 dF^T f by a small Cholesky; false when it fails.
  bool solve_normal_equations(int count) {
    std::array<double, kMaxWindow * kMaxWindow> a{};
    double trace = 0;
    for (int j = 0; j < count; ++j) trace += gram_(j, j);
    const double eps = 1e-12 * trace / count + std::numeric_limits<double>::min();
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < count; ++j)
        a[std::size_t(i * count + j)] = gram_(i, j) + (i == j ? eps : 0.0);
    for (int j = 0; j < count; ++j) {
      double d = a[std::size_t(j * count + j)];
      for (int q = 0; q < j; ++q)
        d -= a[std::size_t(j * count + q)] * a[std::size_t(j * count + q)];
      if (!(d > 0)) return false;
      const double l = std::sqrt(d);
      a[std::size_t(j * count + j)] = l;
      for (int i = j + 1; i < count; ++i) {
        double v = a[std::size_t(i * count + j)];
        for (int q = 0; q < j; ++q)
          v -= a[std::size_t(i * count + q)] * a[std::size_t(j * count + q)];
        a[std::size_t(i * count + j)] = v / l;
      }
    }
    for (int i = 0; i < count; ++i) {
      double v = rhs_(i);
      for (int q = 0; q < i; ++q) v -= a[std::size_t(i * count + q)] * theta_[std::size_t(q)];
      theta_[std::size_t(i)] = v / a[std::size_t(i * count + i)];
    }
    for (int i = count - 1; i >= 0; --i) {
      double v = theta_[std::size_t(i)];
      for (int q = i + 1; q < count; ++q)
        v -= a[std::size_t(q * count + i)] * theta_[std::size_t(q)];
      theta_[std::size_t(i)] = v / a[std::size_t(i * count + i)];
    }
    for (int i = 0; i < count; ++i)
      if (!std::isfinite(theta_[std::size_t(i)])) return false;
    return true;
  }

  // Writes the result into the system when it is finite (positions and the velocities they imply).
  StepReport commit(System& system, const Scalar* x, StepReport& report) {
    auto& positions = system.positions();
    const Scalar inv_dt = Scalar(1) / dt_;
    for (int r = 0; r < nx_; ++r) {
      const int i = point_[std::size_t(r)];
      for (int c = 0; c < 3; ++c) {
        const Scalar value = x[3 * r + c];
        if (!std::isfinite(value) || !std::isfinite((value - positions(i, c)) * inv_dt)) {
          report.finite = false;
          return report;
        }
      }
    }
    auto& velocities = system.velocities();
    for (int r = 0; r < nx_; ++r) {
      const int i = point_[std::size_t(r)];
      for (int c = 0; c < 3; ++c) {
        const Scalar value = x[3 * r + c];
        velocities(i, c) = (value - positions(i, c)) * inv_dt;
        positions(i, c) = value;
      }
    }
    return report;
  }

  static constexpr int kMaxWindow = 16;

  Scalar dt_ = 0;
  Scalar weight_ = 0;
  Scalar rho_estimate_ = 0;
  PinMode pins_ = PinMode::Exact;
  FillOrdering ordering_ = FillOrdering::Auto;
  std::uint64_t revision_ = 0;
  int n_ = 0, nr_ = 0, nx_ = 0;
  std::size_t rejections_ = 0;
  std::vector<int> free_, row_, point_, order_, penalty_rows_;
  std::vector<bool> flipped_;
  std::vector<SpringEnds> ends_;  // springs sorted by (a, b); their k, r and k r below
  std::vector<Coupling> coupling_;
  Matrix q_;
  Cholesky llt_;
  std::array<Buffer, 5> buffers_;
  Buffer rhs0_, inertial_, force_, mass_h2_, targets_, penalty_targets_, direction_;
  Buffer stiffness_, rest_, kr_;
  bool wide_ = false;  // share_pass_avx2 (double, options.avx2, a CPU with AVX2 and FMA)
  bool assembled_in_solve_ = false;  // wide_, and llt_ assembles the right-hand side
  Buffer shares_;  // share_pass_avx2: k r d / |d| per sorted spring, four values (from 32 bytes)
  std::vector<int> plus_begin_, minus_begin_, minus_share_;  // see build()
  Buffer run_sum_;   // per row: the sum of its run of springs (spring_pass), 0 for rows with none
  Scalar drag_ = 0;  // sum of the system's LinearDrag coefficients [N s/m]
  bool other_terms_ = false;   // the system has force terms other than drag
  Points<Scalar> term_force_;  // their force at the step's start
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> df_, dg_;
  Eigen::Matrix<double, kMaxWindow, kMaxWindow> gram_ =
      Eigen::Matrix<double, kMaxWindow, kMaxWindow>::Zero();
  Eigen::Matrix<double, kMaxWindow, 1> rhs_ = Eigen::Matrix<double, kMaxWindow, 1>::Zero();
  std::array<double, kMaxWindow> theta_{};
};

}  // namespace massspring
