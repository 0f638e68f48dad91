#pragma once
/// @file
/// @brief local_global::InertialTerm: the part of FastMassSpring's step objective that is not the
/// springs', constant over a step: the inertia 1/(2 h^2) |X - Y|_M^2 with the inertial prediction
/// Y = X^t + h V^t, the uniform damping beta/(2 h) |X - X^t|^2 folded into it, the external force
/// -tr(X^T F) and the penalty pins w/2 |X_P - X_target|^2; and the constant part of the global
/// step's right-hand side.
///
/// The global step solves for the displacement from the step's start, D = X - X^t (the origin:
/// X^t on the free rows, the targets on exact pins' rows), not for X: Q X = b becomes
/// Q D = b - Q X^t, whose constant part is
///   rhs0 = M V^t / h + F (+ w (X_target - X^t) on penalty pins) - A^T K A X^t,
/// each term formed as a difference (Y - X^t = h V^t; per spring k_e (x_i - x_j) with the
/// pinned ends' targets) so that no term of size |X| is cancelled by another. A point on which
/// nothing acts then gets D = 0 exactly and stays where it is, where X = Q^-1 (M Y / h^2) would
/// round it by about eps |X| each step, the same way every step (a drift of eps |X| / h in
/// velocity per step). Units: h [s], M [kg], beta [N s/m], F [N], w [N/m]; energies in J.

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>

#include "massspring/integrators/local_global/reduced_system.hpp"
#include "massspring/types.hpp"

namespace massspring::local_global {

template <class Scalar>
struct InertialTerm {
  using Buffer = Vector<Scalar>;

  Buffer rhs0;      // 3 per unknown: the right-hand side's constant part (for D = X - origin)
  Buffer origin;    // 3 per iterate row: X^t on the free rows, the targets on exact pins' rows
  Buffer inertial;  // 3 per unknown: Y (with damping: (m/h^2 Y + beta/h X^t) / (m/h^2 + beta/h))
  Buffer force;     // 3 per unknown: F
  Buffer mass_h2;   // per unknown: m / h^2 + beta / h
  Buffer targets;   // 3 per exact pin, in the iterate's pinned rows' order
  Buffer penalty_targets;  // 3 per penalty pin
  Scalar weight = 0;       // the penalty weight w (0 with exact pins)

  /// @brief Sizes the arrays for this numbering and sets m / h^2 + drag_diagonal. Allocates.
  template <class System>
  void build(const System& system, const ReducedSystem<Scalar>& reduced, Scalar inv_dt2,
             Scalar drag_diagonal) {
    const int nr = reduced.nr, nx = reduced.nx;
    const Eigen::Index free_size = 3 * Eigen::Index(nr);
    mass_h2.resize(nr);
    for (int r = 0; r < nr; ++r)
      mass_h2(r) = system.masses()(reduced.point[std::size_t(r)]) * inv_dt2 + drag_diagonal;
    rhs0.resize(free_size);
    origin.resize(3 * Eigen::Index(nx));
    inertial.resize(free_size);
    force.resize(free_size);
    targets.resize(3 * Eigen::Index(nx - nr));
    penalty_targets.resize(3 * Eigen::Index(reduced.penalty_rows.size()));
  }

  /// @brief The step's constants at the system's state, and the starting iterate x0 (the current
  /// positions, or Y when `inertial_guess`) on the free rows. `term_force` (may be null: no
  /// force) is the force terms' at the step's start [N]; `penalty_weight` is w, 0 for exact pins.
  /// The springs' part of rhs0, -A^T K A origin, is added by PackedSprings::subtract_from.
  template <class System>
  void prepare(const System& system, const ReducedSystem<Scalar>& reduced, Scalar dt, Scalar drag,
               Scalar penalty_weight, const Points<Scalar>* term_force, bool inertial_guess,
               Scalar* x0) {
    const auto& x = system.positions();
    const auto& v = system.velocities();
    const Scalar inv_dt2 = Scalar(1) / (dt * dt);
    const Scalar drag_h = drag / dt;
    const int nr = reduced.nr, nx = reduced.nx;
    weight = penalty_weight;
    for (int r = 0; r < nr; ++r) {
      const int i = reduced.point[std::size_t(r)];
      Vector3<Scalar> f = Vector3<Scalar>::Zero();
      if (term_force) f = term_force->row(i).transpose();
      const Scalar mh = system.masses()(i) * inv_dt2;
      for (int c = 0; c < 3; ++c) {
        const Scalar y = x(i, c) + dt * v(i, c);
        // m/(2h^2)|x - y|^2 + beta/(2h)|x - x^t|^2 = (m/h^2 + beta/h)/2 |x - y'|^2 + const.
        inertial(3 * r + c) = drag > 0 ? (mh * y + drag_h * x(i, c)) / (mh + drag_h) : y;
        force(3 * r + c) = f(c);
        // (m/h^2 Y + beta/h X^t + F) - (m/h^2 + beta/h) X^t
        rhs0(3 * r + c) = mh * (dt * v(i, c)) + f(c);
        origin(3 * r + c) = x(i, c);
        x0[3 * r + c] = inertial_guess ? y : x(i, c);
      }
    }
    const auto& pins = system.pin_targets();
    if (penalty_weight > 0) {
      const auto& rows = reduced.penalty_rows;
      for (std::size_t p = 0; p < rows.size(); ++p)
        for (int c = 0; c < 3; ++c) {
          penalty_targets(3 * Eigen::Index(p) + c) = pins(Eigen::Index(p), c);
          rhs0(3 * rows[p] + c) +=
              penalty_weight * (pins(Eigen::Index(p), c) - origin(3 * rows[p] + c));
        }
    } else {
      // A spring to an exact pin: its k x_target on the right-hand side (-Q_FP X_P) comes with
      // the springs' difference k (x_free - x_target) (PackedSprings::subtract_from).
      for (int p = 0; p < nx - nr; ++p)
        for (int c = 0; c < 3; ++c) {
          targets(3 * p + c) = pins(p, c);
          origin(3 * (nr + p) + c) = pins(p, c);
        }
    }
  }

  /// @brief X = origin + D on the free rows, for the global step's solution D in place.
  void add_origin(Scalar* d, int free_rows) const {
    const Scalar* o = origin.data();
    const Eigen::Index size = 3 * Eigen::Index(free_rows);
    for (Eigen::Index i = 0; i < size; ++i) d[i] += o[i];
  }

  /// @brief The exact pins' rows (after the `free_rows` free ones) back to their targets.
  void restore_pins(Scalar* x, int free_rows) const {
    const Eigen::Index np = targets.size();
    if (np > 0) std::copy_n(targets.data(), np, x + 3 * Eigen::Index(free_rows));
  }

  /// @brief With Write, w = rhs0 on the free rows; with Energy, returns this term's energy at x
  /// (inertia, external force, penalty pins) [J], up to a constant, in the same pass.
  template <bool Energy, bool Write = true>
  double start(const Scalar* x, Scalar* w, const ReducedSystem<Scalar>& reduced) const {
    const Scalar* b0 = rhs0.data();
    const int nr = reduced.nr;
    const Eigen::Index size = 3 * Eigen::Index(nr);
    if constexpr (!Energy) {
      std::copy_n(b0, size, w);
      return 0;
    } else {
      const Scalar* y = inertial.data();
      const Scalar* f = force.data();
      const Scalar* mh = mass_h2.data();
      double energy = 0;
      for (int r = 0; r < nr; ++r) {
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
      const auto& rows = reduced.penalty_rows;
      for (std::size_t p = 0; p < rows.size(); ++p) {
        const Scalar* xp = x + 3 * rows[p];
        const Scalar* tp = penalty_targets.data() + 3 * p;
        const Scalar e0 = xp[0] - tp[0], e1 = xp[1] - tp[1], e2 = xp[2] - tp[2];
        energy += double(weight / 2 * (e0 * e0 + e1 * e1 + e2 * e2));
      }
      return energy;
    }
  }
};

}  // namespace massspring::local_global
