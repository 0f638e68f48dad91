#pragma once
/// @file
/// @brief stable_time_step(): a safe time step for the explicit integrators, from a Gershgorin
/// bound on the system's frequencies and damping rates.

#include <Eigen/Core>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "massspring/detail/validate.hpp"
#include "massspring/error.hpp"
#include "massspring/forces/evaluate.hpp"
#include "massspring/forces/force_term.hpp"

namespace massspring {

/// @brief The explicit integrators stable_time_step() knows.
enum class ExplicitMethod {
  ForwardEuler,     ///< x += h v, v += h a
  SymplecticEuler,  ///< v += h a, then x += h v
  RK4,              ///< classical fourth-order Runge-Kutta
};

/// @brief Bounds on the linearised dynamics at one state, from block Gershgorin discs.
///
/// With K = -dF/dx and D = -dF/dv (3x3 blocks K_ij, D_ij; rows and columns of pinned points
/// removed), every eigenvalue of M^-1 K lies within `omega_max^2` of zero and every damping rate
/// of M^-1 D within [`damping_min`, `damping_max`]:
///
///     omega_max^2 = max_i (1/m_i) sum_j |K_ij|_2      (for Hooke springs at rest: sum_e 2 k_e /
///     m_i) damping_max = max_i (1/m_i) sum_j |D_ij|_2 damping_min = min_i beta / m_i (beta: the
///     sum of the LinearDrag terms)
///
/// |.|_2 is the spectral norm (largest singular value). Units: omega_max in rad/s, the
/// damping rates in 1/s.
struct FrequencyBounds {
  double omega_max = 0;
  double damping_max = 0;
  double damping_min = 0;
};

namespace detail {

/// @brief Per free point, sum_j |J_ij|_2 / m_i over the blocks of one Jacobian given as entries
/// (row, col, value), pinned columns left out. Returns the maximum over free points.
template <class Scalar>
double gershgorin_rows(const std::vector<std::pair<int, int>>& entries,
                       const std::vector<Scalar>& values, const Vector<Scalar>& masses,
                       const std::vector<char>& pinned) {
  // Sum the entries into 3x3 blocks keyed by (i, j), then take each block's spectral norm.
  std::vector<std::pair<std::pair<int, int>, int>> keyed;  // ((i, j), entry index)
  keyed.reserve(entries.size());
  for (std::size_t k = 0; k < entries.size(); ++k)
    keyed.push_back({{entries[k].first / 3, entries[k].second / 3}, int(k)});
  std::sort(keyed.begin(), keyed.end());
  std::vector<double> row_sum(std::size_t(masses.size()), 0.0);
  for (std::size_t a = 0; a < keyed.size();) {
    const auto ij = keyed[a].first;
    Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
    for (; a < keyed.size() && keyed[a].first == ij; ++a) {
      const auto& e = entries[std::size_t(keyed[a].second)];
      block(e.first % 3, e.second % 3) += double(values[std::size_t(keyed[a].second)]);
    }
    const auto [i, j] = ij;
    if (pinned[std::size_t(i)] || pinned[std::size_t(j)]) continue;
    // A non-finite block (a non-finite state): JacobiSVD would leave its singular values unset,
    // and std::max below would drop a NaN. NaN makes stable_time_step() throw.
    if (!block.allFinite()) return std::numeric_limits<double>::quiet_NaN();
    // The spectral norm (largest singular value) of the block.
    row_sum[std::size_t(i)] += Eigen::JacobiSVD<Eigen::Matrix3d>(block).singularValues()(0);
  }
  double worst = 0;
  for (Eigen::Index i = 0; i < masses.size(); ++i)
    if (!pinned[std::size_t(i)])
      worst = std::max(worst, row_sum[std::size_t(i)] / double(masses(i)));
  return worst;
}

}  // namespace detail

/// @brief Gershgorin bounds on the frequencies and damping rates of the system linearised at its
/// current positions and velocities (see FrequencyBounds). Every force's Jacobians count, user
/// terms included; a term without Jacobians is not seen (its stiffness is then not bounded).
/// Allocates: call it once, not per step.
template <class System>
FrequencyBounds frequency_bounds(const System& system) {
  using Scalar = typename System::Scalar;
  const int n = system.num_points();
  std::vector<char> pinned(std::size_t(n), 0);
  for (const int i : system.pinned()) pinned[std::size_t(i)] = 1;
  const auto ctx = system.force_context(system.positions(), system.velocities(), false);
  // Record both patterns, then accumulate every entry into its own slot.
  std::vector<std::pair<int, int>> ex, ev;
  auto rx = JacobianSink<Scalar>::recorder(ex);
  auto rv = JacobianSink<Scalar>::recorder(ev);
  add_jacobians(system, ctx, rx, rv);
  std::vector<Eigen::Index> sx(ex.size()), sv(ev.size());
  for (std::size_t k = 0; k < sx.size(); ++k) sx[k] = Eigen::Index(k);
  for (std::size_t k = 0; k < sv.size(); ++k) sv[k] = Eigen::Index(k);
  std::vector<Scalar> vx(ex.size(), Scalar(0)), vv(ev.size(), Scalar(0));
  auto ax = JacobianSink<Scalar>::accumulator(vx.data(), sx, Scalar(1));
  auto av = JacobianSink<Scalar>::accumulator(vv.data(), sv, Scalar(1));
  add_jacobians(system, ctx, ax, av);

  FrequencyBounds b;
  b.omega_max = std::sqrt(detail::gershgorin_rows(ex, vx, system.masses(), pinned));
  b.damping_max = detail::gershgorin_rows(ev, vv, system.masses(), pinned);
  double beta = 0;
  for (const auto& term : system.forces())
    if (term->linear_damping) beta += double(term->linear_damping_coefficient());
  b.damping_min = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i)
    if (!pinned[std::size_t(i)])
      b.damping_min = std::min(b.damping_min, beta / double(system.masses()(i)));
  if (!std::isfinite(b.damping_min)) b.damping_min = 0;  // no free point
  return b;
}

/// @brief The largest h [s] at which `method` is stable for the system linearised at its current
/// state (from frequency_bounds(); exact for one spring on a pinned point, conservative otherwise
/// because the bounds are):
///
/// - SymplecticEuler: h = 4 / (c + sqrt(c^2 + 4 omega^2)), with c = damping_max; 2 / omega_max
///   for an undamped system. (From the step's 2x2 matrix on a mode: h^2 omega^2 + 2 h c <= 4.)
/// - RK4: h = 2.6 / (c/2 + sqrt(c^2/4 + omega^2)): the disc of radius 2.6 in the left half plane
///   lies in RK4's stability region (which reaches 2 sqrt 2 on the imaginary axis).
/// - ForwardEuler: h = min(c_min / omega^2, 2 / c_max), where c_min = damping_min. An undamped
///   oscillation grows by (1 + h^2 omega^2)^(1/2) per step at every h, so without linear drag
///   there is no stable step and the result is 0.
///
/// This is the edge, not a step to run a scene at: a run at exactly the limit sits on the boundary
/// of stability, and as the scene moves its frequencies change (stretched springs gain sideways
/// stiffness, compressed ones more). Use stable_time_step() for that.
///
/// Returns +infinity when the system has no stiffness and no damping (nothing limits h).
/// @throws Error when a bound is not finite (a non-finite state or Jacobian).
template <class System>
double stability_limit(const System& system,
                       ExplicitMethod method = ExplicitMethod::SymplecticEuler) {
  const FrequencyBounds b = frequency_bounds(system);
  if (!std::isfinite(b.omega_max) || !std::isfinite(b.damping_max))
    throw Error(detail::message("stability_limit: the frequency bound is not finite (omega_max ",
                                b.omega_max, ", damping_max ", b.damping_max,
                                "); is the state finite?"));
  const double w = b.omega_max, c = b.damping_max;
  const double inf = std::numeric_limits<double>::infinity();
  switch (method) {
    case ExplicitMethod::SymplecticEuler:
      return (w == 0 && c == 0) ? inf : 4.0 / (c + std::sqrt(c * c + 4 * w * w));
    case ExplicitMethod::RK4: {
      const double lambda = c / 2 + std::sqrt(c * c / 4 + w * w);
      return lambda == 0 ? inf : 2.6 / lambda;
    }
    case ExplicitMethod::ForwardEuler: {
      const double oscillation = w == 0 ? inf : b.damping_min / (w * w);
      const double decay = c == 0 ? inf : 2.0 / c;
      return std::min(oscillation, decay);
    }
  }
  return 0;
}

/// @brief The default `safety` of stable_time_step(): the stress suite (docs/stability.md) ran
/// chains and cloths with stiffness 1 to 1e8 N/m for 10 s at 1, 0.75 and 0.5 times the initial
/// stability_limit(); every run at 0.5 stayed stable, while at 1.0 10 of 18 symplectic Euler runs
/// did not. A measured margin on those scenes, not a guarantee: stiff scenes at the edge fail from
/// nonlinear swings alone (their limit moves by < 5%), and soft scenes that fold compress springs
/// to a few percent of their rest length, where the limit of the state falls to 0.1-0.45 of the
/// initial one (four runs at 0.5 passed through such states and still finished stable).
inline constexpr double default_stability_safety = 0.5;

/// @brief A time step [s] at which `method` can run the scene: `safety` times
/// stability_limit(system, method) at the current state. `safety` in (0, 1], default 0.5 (see
/// default_stability_safety). 0 for ForwardEuler without linear drag (no step is stable); +infinity
/// when nothing limits h.
/// @throws Error for a safety outside (0, 1] or a non-finite bound.
template <class System>
double stable_time_step(const System& system,
                        ExplicitMethod method = ExplicitMethod::SymplecticEuler,
                        double safety = default_stability_safety) {
  if (!(safety > 0 && safety <= 1))
    throw Error(detail::message("stable_time_step: safety must be in (0, 1], got ", safety));
  return safety * stability_limit(system, method);
}

}  // namespace massspring
