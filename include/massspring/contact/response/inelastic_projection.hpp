#pragma once
/// @file
/// @brief InelasticProjection: the inelastic projection of impact zones (Harmon, Vouga, Tamstorf
/// and Grinspun 2008, "Robust treatment of simultaneous collisions", section 4), in displacements
/// over a step.
///
/// Points k have start positions x0_k, proposed end positions x1_k and inverse masses w_k (0: an
/// immobile point, pinned or an obstacle's, which the projection never moves). A collision c
/// gives the linearised non-penetration constraint
///
///   g_c(x1) = sum_k a_ck n_c . (x1_k - x0_k) >= b_c,
///
/// with the pair's barycentric weights a_ck (+ on one element, - on the other), its unit normal
/// n_c (from the second element to the first) and a lower bound b_c [m] on the relative
/// displacement along n_c (0: the approach cancelled, an inelastic impact; a small b_c > 0 parts
/// the pair a little). The projection replaces x1 by the nearest end positions in the mass norm,
///
///   minimise 1/2 sum_k m_k |x1'_k - x1_k|^2  subject to g_c(x1') >= b_c for every c,
///
/// over the mobile points. Only normal displacements change: the tangential (sliding) motion of a
/// zone is kept, it is not frozen rigid. Its dual is a linear complementarity problem in the
/// multipliers lambda_c >= 0, with x1' = x1 + sum_c lambda_c W G_c^T; solve() runs projected
/// Gauss-Seidel on it (sequential impulses with the accumulated multiplier clamped at 0: Cottle,
/// Pang and Stone 1992, section 5.2; convergent for a positive semi-definite G W G^T with a
/// positive diagonal). Each update moves point k of constraint c by w_k a_ck delta n_c: linear
/// momentum is kept, and an immobile point never moves. The multipliers are kept between calls,
/// so constraints added later (Harmon's growing set) start from the solution of the earlier ones.
///
/// Two cases are left to the caller's next stage (the rigid impact zones) instead of being swept:
/// a constraint whose mobile points carry a negligible share of its weights (meeting it would
/// move them by the violation over that share), and constraints that contradict each other (the
/// LCP has no solution: the multipliers grow without bound and the sweeps move the points back
/// and forth by the same amount, which solve() detects as a stall).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief One linearised non-penetration constraint (see the file comment).
template <class Scalar>
struct ProjectionConstraint {
  /// @brief The points (indices into the arrays solve() is given); weights of unused slots are 0.
  std::array<int, 4> p{};
  /// @brief Their weights a_k (barycentric, + on the first element, - on the second).
  std::array<Scalar, 4> a{};
  /// @brief The unit normal, from the second element to the first.
  Vector3<Scalar> n = Vector3<Scalar>::UnitZ();
  /// @brief The least relative displacement along n over the step [m].
  Scalar target = 0;
};

/// @brief What solve() found.
template <class Scalar>
struct ProjectionResult {
  /// @brief Projected Gauss-Seidel sweeps done.
  int sweeps = 0;
  /// @brief The largest violation b_c - g_c(x1') left [m] (<= 0: every constraint holds).
  Scalar violation = 0;
  /// @brief True when a constraint that is violated beyond the tolerance has no mobile point:
  /// nothing the projection may move can satisfy it.
  bool immobile_violated = false;
  /// @brief True when the sweeps stopped because InelasticProjection::kStallSweeps sweeps in a
  /// row each moved the points as much as the sweep kStallSweeps before it, to a relative
  /// InelasticProjection::kStallTolerance, in the mass norm (sum_k m_k |dx_k|^2): the sweeps
  /// repeat a cycle, the constraints contradict each other (a point held above one element and
  /// below another), and more sweeps only move the points back and forth. Converging sweeps move
  /// the points less and less, though not steadily when constraints leave and join the active
  /// set; they do not repeat a motion to a millionth.
  bool stalled = false;
};

/// @brief The inelastic projection (see the file comment); its arrays keep their capacity.
template <class Scalar>
class InelasticProjection {
 public:
  using V3 = Vector3<Scalar>;
  using Constraint = ProjectionConstraint<Scalar>;

  /// @brief No constraint.
  void clear() {
    constraints_.clear();
    lambda_.clear();
  }
  /// @brief Adds a constraint, its multiplier 0.
  void add(const Constraint& c) {
    constraints_.push_back(c);
    lambda_.push_back(0);
  }
  /// @brief Replaces constraint `index` by `c`, its multiplier 0: the displacement the old one
  /// applied stays in the end positions, and the new one only adds to it.
  void replace(std::size_t index, const Constraint& c) {
    constraints_[index] = c;
    lambda_[index] = 0;
  }
  [[nodiscard]] std::size_t size() const { return constraints_.size(); }
  [[nodiscard]] const Constraint& constraint(std::size_t c) const { return constraints_[c]; }
  /// @brief Constraint c's multiplier [m] (the normal displacement it has applied, per unit of
  /// sum_k a_ck^2 w_ck).
  [[nodiscard]] Scalar multiplier(std::size_t c) const { return lambda_[c]; }

  /// @brief g_c(x1) - b_c: >= 0 when constraint c holds [m].
  [[nodiscard]] static Scalar slack(const Constraint& c, const Points<Scalar>& x0,
                                    const Points<Scalar>& x1) {
    Scalar g = 0;
    for (int k = 0; k < 4; ++k) {
      const int i = c.p[std::size_t(k)];
      const Scalar a = c.a[std::size_t(k)];
      if (a != 0) g += a * c.n.dot((x1.row(i) - x0.row(i)).transpose());
    }
    return g - c.target;
  }

  /// @brief The least share of a constraint's weights, sum of |a_k| over its mobile points (out
  /// of 2: each element's barycentric weights sum to 1), for the projection to move it. Below
  /// it, cancelling a violation r would move a point by more than r / kLeastMobileShare; such a
  /// constraint counts as having no mobile point (the rigid stage takes it).
  static constexpr Scalar kLeastMobileShare = Scalar(1) / 1024;
  /// @brief The lag [sweeps] at which a sweep's motion is compared with an earlier one, and the
  /// number of sweeps in a row that must repeat it for solve() to stop (ProjectionResult::stalled).
  static constexpr int kStallSweeps = 10;
  /// @brief The relative tolerance of a repeated motion (ProjectionResult::stalled).
  static constexpr double kStallTolerance = 1e-6;

  /// @brief True when constraint c has a mobile share of at least kLeastMobileShare.
  [[nodiscard]] static bool mobile(const Constraint& c, const Vector<Scalar>& w) {
    Scalar share = 0;
    for (int k = 0; k < 4; ++k)
      if (w(c.p[std::size_t(k)]) > 0) share += std::abs(c.a[std::size_t(k)]);
    return share >= kLeastMobileShare;
  }

  /// @brief Projects x1 (see the file comment) by sweeps over the constraints until no
  /// constraint is violated by more than `tolerance` [m] and no sweep moves a point by more than
  /// `tolerance`, or `max_sweeps` sweeps, or the sweeps stall (ProjectionResult::stalled).
  /// Constraints without a mobile share (mobile()) are left out. `moved[i]` is set for each
  /// point moved.
  /// @param[in] w  inverse masses [1/kg] (0: immobile)
  /// @param[in] x0 start positions; @param[in,out] x1 end positions
  ProjectionResult<Scalar> solve(const Vector<Scalar>& w, const Points<Scalar>& x0,
                                 Points<Scalar>& x1, Scalar tolerance, int max_sweeps,
                                 std::vector<char>& moved) {
    ProjectionResult<Scalar> result;
    std::array<Scalar, kStallSweeps> earlier{};  // the last sweeps' motions, by sweep % lag
    int repeated = 0;  // consecutive sweeps whose motion repeated the one kStallSweeps before
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
      result.sweeps = sweep + 1;
      Scalar largest_move = 0, worst = 0, motion = 0;
      for (std::size_t ci = 0; ci < constraints_.size(); ++ci) {
        const Constraint& c = constraints_[ci];
        if (!mobile(c, w)) continue;
        const Scalar r = -slack(c, x0, x1);  // > 0: violated
        Scalar den = 0;
        for (int k = 0; k < 4; ++k) {
          const Scalar a = c.a[std::size_t(k)];
          den += a * a * w(c.p[std::size_t(k)]);
        }
        const Scalar next = std::max(Scalar(0), lambda_[ci] + r / den);
        const Scalar delta = next - lambda_[ci];
        lambda_[ci] = next;
        worst = std::max(worst, r);
        if (delta == 0) continue;
        motion += den * delta * delta;
        for (int k = 0; k < 4; ++k) {
          const int i = c.p[std::size_t(k)];
          const Scalar step = c.a[std::size_t(k)] * w(i) * delta;
          if (step == 0) continue;
          x1.row(i) += step * c.n.transpose();
          moved[std::size_t(i)] = 1;
          largest_move = std::max(largest_move, std::abs(step));
        }
      }
      if (worst <= tolerance && largest_move <= tolerance) break;
      Scalar& before = earlier[std::size_t(sweep % kStallSweeps)];
      const bool repeats = sweep >= kStallSweeps && motion > 0 &&
                           std::abs(motion - before) <= Scalar(kStallTolerance) * before;
      repeated = repeats ? repeated + 1 : 0;
      before = motion;
      if (repeated >= kStallSweeps) {
        result.stalled = true;
        break;
      }
    }
    result.violation = -std::numeric_limits<Scalar>::infinity();
    for (const Constraint& c : constraints_) {
      const Scalar r = -slack(c, x0, x1);
      result.violation = std::max(result.violation, r);
      if (r > tolerance) result.immobile_violated = result.immobile_violated || !mobile(c, w);
    }
    if (constraints_.empty()) result.violation = 0;
    return result;
  }

 private:
  std::vector<Constraint> constraints_;
  std::vector<Scalar> lambda_;
};

}  // namespace massspring::contact
