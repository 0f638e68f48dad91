#pragma once
/// @file
/// @brief ContactProjection: the contact term of FastMassSpring's iteration, projective dynamics'
/// collision constraint (Bouaziz et al. 2014, "Projective Dynamics", sections 3 and 5) with a
/// constant weight, so Q never changes with the contacts, and a scaled dual variable per point
/// that makes the converged step exact (the alternating direction method of multipliers: Boyd et
/// al. 2011, "Distributed Optimization and Statistical Learning via ADMM", section 3.1.1; Overby
/// et al. 2017, "ADMM ⊇ Projective Dynamics").
///
/// Each unknown point i carries the weight w_i = alpha sqrt(m_i (m_i + dt^2 k_i)) / dt^2 [N/m]
/// (alpha: FastMassSpringOptions::contact_weight; k_i the summed stiffness of its springs;
/// detail::contact_weights gives the numerator, in kg) on Q's diagonal (ReducedSystem::assemble's
/// point_diagonal) and, per iteration, with P the projection out of the system's colliders
/// (ColliderSet::project: the normal push, with Coulomb friction at position level on the
/// displacement over the step) and u_i the dual variable [m] (kept from the previous step, 0 after
/// a factorization):
///   z_i = P(x_i + u_i),   u_i <- x_i + u_i - z_i,   right-hand side += w_i (z_i - u_i).
/// P also keeps points out of a band about each box's edges and corners and each capsule's axis
/// (detail::edge_distances(), per point), so that the iterate has no cloth edge across a box's rim
/// or a rod for the end-of-step pass to push off. A point that touches nothing has z_i = x_i and
/// u_i = 0: the term is w_i x_i, a proximal term that vanishes at convergence. A point in contact
/// converges to x_i = z_i on the surface with the contact force -w_i u_i [N]: its normal part w_i
/// delta >= 0 (delta the depth of x_i + u_i) and its tangential part opposed to the displacement
/// over the step, of length <= mu w_i delta (equal when sliding) - Signorini's condition and
/// Coulomb's law for one implicit-Euler step, without the error of a penalty (without u the fixed
/// point would sit inside by the depth the weight allows, and its friction would be scaled down
/// with it). Pinned points (penalty pins) keep the proximal term without projection.
///
/// E_c = w_i / 2 |x_i - P(x_i)|^2 [J] (0 on the surface or outside) is what energy() adds to the
/// step's objective: a merit for the accelerated loops' guard and the report, not an energy the
/// iteration descends (contact with friction has none).

#include <cstddef>
#include <vector>

#include "massspring/contact/colliders/collider_set.hpp"
#include "massspring/integrators/detail/contact_dual.hpp"
#include "massspring/integrators/local_global/reduced_system.hpp"
#include "massspring/types.hpp"

namespace massspring::local_global {

template <class Scalar>
class ContactProjection {
 public:
  /// @brief Per-row weights w_r [N/m] from the points' (`point_weight`, the ones Q carries; empty
  /// when the term is off) and which rows project (the unknowns that are not pinned); nothing when
  /// the term is off. Allocates; called when Q is built.
  template <class System>
  void build(const System& system, const ReducedSystem<Scalar>& reduced,
             const Vector<Scalar>& point_weight) {
    const int nr = point_weight.size() > 0 ? reduced.nr : 0;
    weight_.resize(nr);
    projects_.assign(std::size_t(nr), 0);
    point_.assign(std::size_t(nr), 0);
    base_.resize(3 * Eigen::Index(nr));
    dual_.setZero(3 * Eigen::Index(nr));
    kept_.setZero(3 * Eigen::Index(nr));
    clearance2_.setZero(nr);
    edge_distance_.setZero(system.num_points());
    for (int r = 0; r < nr; ++r) {
      const int i = reduced.point[std::size_t(r)];
      point_[std::size_t(r)] = i;
      weight_(r) = point_weight(i);
      projects_[std::size_t(r)] = system.is_pinned(i) ? 0 : 1;
    }
  }

  /// @brief The step's colliders (their end-of-step poses set), start positions, right-hand
  /// side's constant part (rhs0, kept as the base the term adds to) and the origin the global
  /// step solves from (its right-hand side is for X - origin: the term adds w (z - u - origin));
  /// the dual variables are kept from the previous step (warm start). Inactive without colliders or
  /// with alpha 0. Allocates nothing.
  template <class System>
  void prepare(System& system, Scalar dt, const Vector<Scalar>& rhs0,
               const Vector<Scalar>& origin) {
    colliders_ = system.colliders().empty() ? nullptr : &system.colliders();
    if (colliders_) system.colliders().begin_step(dt);
    active_ = colliders_ != nullptr && weight_.size() > 0;
    if (!active_) return;
    x_start_ = system.positions().data();
    origin_ = origin.data();
    dt_ = dt;
    base_ = rhs0.head(base_.size());                 // same size: no allocation
    detail::edge_distances(system, edge_distance_);  // same size: no allocation
    for (int r = 0; r < int(weight_.size()); ++r) {
      const Scalar c = projects_[std::size_t(r)]
                           ? colliders_->clearance(Eigen::Map<const Vector3<Scalar>>(
                                 x_start_ + 3 * point_[std::size_t(r)])) -
                                 edge_distance_(point_[std::size_t(r)])
                           : Scalar(0);
      clearance2_(r) = c > 0 ? c * c : Scalar(0);
    }
  }

  /// @brief True when the term acts this step.
  [[nodiscard]] bool active() const { return active_; }

  /// @brief The dual variables u [m] into the rows of `u` (n x 3, one row per point of the
  /// system); rows of points the term does not project are left as they are.
  template <class Points>
  void get_duals(Points& u) const {
    for (int r = 0; r < int(weight_.size()); ++r)
      if (projects_[std::size_t(r)])
        u.row(point_[std::size_t(r)]) = dual_.template segment<3>(3 * Eigen::Index(r)).transpose();
  }

  /// @brief Sets the dual variables from the rows of `u` (n x 3). Returns -1, or (nothing set)
  /// the first point the term does not project whose row is not zero.
  template <class Points>
  int set_duals(const Points& u) {
    std::vector<unsigned char> acted(std::size_t(u.rows()), 0);
    for (int r = 0; r < int(weight_.size()); ++r)
      if (projects_[std::size_t(r)]) acted[std::size_t(point_[std::size_t(r)])] = 1;
    for (Eigen::Index i = 0; i < u.rows(); ++i)
      if (!acted[std::size_t(i)] && !u.row(i).isZero(0)) return int(i);
    for (int r = 0; r < int(weight_.size()); ++r)
      if (projects_[std::size_t(r)])
        dual_.template segment<3>(3 * Eigen::Index(r)) = u.row(point_[std::size_t(r)]).transpose();
    return -1;
  }

  /// @brief Keeps a copy of the dual variables, for restore_duals(): iterations that are not the
  /// step's (FastMassSpring's trial iterations estimating Chebyshev's rho) must not move them.
  /// Allocates nothing.
  void keep_duals() { kept_ = dual_; }
  /// @brief The dual variables back to what keep_duals() copied. Allocates nothing.
  void restore_duals() { dual_ = kept_; }

  /// @brief The local step of the term at the iterate x: z = P(x + u), u <- x + u - z, and
  /// rhs0 = base + w (z - u - origin) on the term's rows (x unchanged); returns E_c at x [J]
  /// when Energy (one more projection per point in contact), else 0.
  template <bool Energy>
  double apply(const Scalar* x, Vector<Scalar>& rhs0) {
    double energy = 0;
    Scalar* b = rhs0.data();
    const Scalar* b0 = base_.data();
    Scalar* dual = dual_.data();
    for (int r = 0; r < int(weight_.size()); ++r) {
      const Scalar* xr = x + 3 * r;
      const Scalar w = weight_(r);
      Scalar* b_r = b + 3 * r;
      const Scalar* b0_r = b0 + 3 * r;
      const Scalar* o = origin_ + 3 * r;
      if (!projects_[std::size_t(r)]) {
        for (int c = 0; c < 3; ++c) b_r[c] = b0_r[c] + w * (xr[c] - o[c]);
        continue;
      }
      Scalar target[3];
      const bool touches = detail::contact_dual_update(
          *colliders_, x_start_ + 3 * point_[std::size_t(r)], xr, dual + 3 * r, dt_, target,
          clearance2_(r), edge_distance_(point_[std::size_t(r)]));
      for (int c = 0; c < 3; ++c) b_r[c] = b0_r[c] + w * (target[c] - o[c]);
      if (Energy && touches) {
        Scalar p[3] = {xr[0], xr[1], xr[2]};
        energy += project(r, p);
      }
    }
    return energy;
  }

  /// @brief E_c at x [J], x unchanged.
  [[nodiscard]] double energy(const Scalar* x) const {
    double energy = 0;
    for (int r = 0; r < int(weight_.size()); ++r) {
      if (!projects_[std::size_t(r)]) continue;
      Scalar p[3] = {x[3 * r], x[3 * r + 1], x[3 * r + 2]};
      energy += project(r, p);
    }
    return energy;
  }

 private:
  // Projects the 3 values at xr in place; returns w_r / 2 |x - P(x)|^2.
  double project(int r, Scalar* xr) const {
    const Scalar x0 = xr[0], x1 = xr[1], x2 = xr[2];
    const Scalar* xs = x_start_ + 3 * point_[std::size_t(r)];
    const Scalar d0 = x0 - xs[0], d1 = x1 - xs[1], d2 = x2 - xs[2];
    if (d0 * d0 + d1 * d1 + d2 * d2 < clearance2_(r)) return 0;  // P moves nothing
    colliders_->project(xs, xr, dt_, edge_distance_(point_[std::size_t(r)]));
    const Scalar p0 = xr[0] - x0, p1 = xr[1] - x1, p2 = xr[2] - x2;
    return double(weight_(r) / 2 * (p0 * p0 + p1 * p1 + p2 * p2));
  }

  Vector<Scalar> weight_;
  std::vector<unsigned char> projects_;
  std::vector<int> point_;
  Vector<Scalar> base_;
  Vector<Scalar> dual_;  // u, 3 per row [m]
  Vector<Scalar> kept_;  // keep_duals()'s copy of dual_
  // Per row, the square of ColliderSet::clearance() of the step's start position [m^2] (0 when
  // not positive): an iterate closer than that to the start is not projected.
  Vector<Scalar> clearance2_;
  const contact::ColliderSet<Scalar>* colliders_ = nullptr;
  const Scalar* x_start_ = nullptr;
  const Scalar* origin_ = nullptr;  // 3 per row [m]
  Scalar dt_ = 0;
  Vector<Scalar> edge_distance_;  // detail::edge_distances() at the step's start, per point [m]
  bool active_ = false;
};

}  // namespace massspring::local_global
