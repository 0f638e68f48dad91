#pragma once
/// @file
/// @brief ContactProjection: the contact term of FastMassSpring's iteration, projective dynamics'
/// collision constraint (Bouaziz et al. 2014, "Projective Dynamics", sections 3 and 5) with a
/// constant weight, so Q never changes with the contacts.
///
/// Each unknown point i carries E_c = w_i / 2 |x_i - P(x_i)|^2, w_i = alpha m_i / dt^2 (alpha:
/// FastMassSpringOptions::contact_weight), P the projection out of the system's colliders
/// (ColliderSet::project: the position response, with Coulomb friction on the displacement over
/// the step). Q carries w_i on its diagonal (ReducedSystem::assemble's mass_scale 1 + alpha). The
/// local step projects the iterate, p_i = P(x_i), and adds w_i p_i to the right-hand side: a point
/// outside every collider has p_i = x_i, its term is zero with zero gradient, and at convergence
/// it moves as without the term; a point in contact is pulled to the surface, and the springs and
/// the global step see it there. Pinned points (penalty pins) keep the term without projection.

#include <cstddef>
#include <vector>

#include "massspring/contact/colliders/colliders.hpp"
#include "massspring/integrators/local_global/reduced_system.hpp"
#include "massspring/types.hpp"

namespace massspring::local_global {

template <class Scalar>
class ContactProjection {
 public:
  /// @brief Per-row weights w_r = alpha m / dt^2 (inv_dt2 = 1 / dt^2) and which rows project (the
  /// unknowns that are not pinned); nothing when alpha is 0. Allocates; called when Q is built.
  template <class System>
  void build(const System& system, const ReducedSystem<Scalar>& reduced, Scalar alpha,
             Scalar inv_dt2) {
    const int nr = alpha > 0 ? reduced.nr : 0;
    weight_.resize(nr);
    projects_.assign(std::size_t(nr), 0);
    point_.assign(std::size_t(nr), 0);
    base_.resize(3 * Eigen::Index(nr));
    for (int r = 0; r < nr; ++r) {
      const int i = reduced.point[std::size_t(r)];
      point_[std::size_t(r)] = i;
      weight_(r) = alpha * system.masses()(i) * inv_dt2;
      projects_[std::size_t(r)] = system.is_pinned(i) ? 0 : 1;
    }
  }

  /// @brief The step's colliders (their end-of-step poses set), start positions and right-hand
  /// side's constant part (rhs0, kept as the base the term adds to). Inactive without colliders
  /// or with alpha 0. Allocates nothing.
  template <class System>
  void prepare(System& system, Scalar dt, const Vector<Scalar>& rhs0) {
    colliders_ = system.colliders().empty() ? nullptr : &system.colliders();
    if (colliders_) system.colliders().begin_step(dt);
    active_ = colliders_ != nullptr && weight_.size() > 0;
    if (!active_) return;
    x_start_ = system.positions().data();
    dt_ = dt;
    base_ = rhs0.head(base_.size());  // same size: no allocation
  }

  /// @brief True when the term acts this step.
  [[nodiscard]] bool active() const { return active_; }

  /// @brief Projects the iterate x in place and sets rhs0 = base + w p on the term's rows;
  /// returns E_c at the x given [J].
  double apply(Scalar* x, Vector<Scalar>& rhs0) const {
    double energy = 0;
    Scalar* b = rhs0.data();
    const Scalar* b0 = base_.data();
    for (int r = 0; r < int(weight_.size()); ++r) {
      Scalar* xr = x + 3 * r;
      if (projects_[std::size_t(r)]) energy += project(r, xr);
      const Scalar w = weight_(r);
      for (int c = 0; c < 3; ++c) b[3 * r + c] = b0[3 * r + c] + w * xr[c];
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
    colliders_->project(x_start_ + 3 * point_[std::size_t(r)], xr, dt_);
    const Scalar d0 = xr[0] - x0, d1 = xr[1] - x1, d2 = xr[2] - x2;
    return double(weight_(r) / 2 * (d0 * d0 + d1 * d1 + d2 * d2));
  }

  Vector<Scalar> weight_;
  std::vector<unsigned char> projects_;
  std::vector<int> point_;
  Vector<Scalar> base_;
  const contact::ColliderSet<Scalar>* colliders_ = nullptr;
  const Scalar* x_start_ = nullptr;
  Scalar dt_ = 0;
  bool active_ = false;
};

}  // namespace massspring::local_global
