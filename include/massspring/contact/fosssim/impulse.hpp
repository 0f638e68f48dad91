#pragma once
/// @file
/// @brief FOSSSim's impulse responses (Theme 2, SimpleCollisionHandler::respond*,
/// ContinuousTimeCollisionHandler::respond*, HybridCollisionHandler::respond*), written with
/// inverse masses w (0 for a fixed particle: infinite mass).
///
/// With n^ the unit normal from the particle towards the other primitive, u the velocities the
/// response reads and e the coefficient of restitution:
/// - particle-particle: \f$ \lambda = (1+e) \frac{(u_j - u_i)\cdot\hat n}{w_i + w_j} \f$,
///   \f$ \Delta v_i = w_i \lambda \hat n,\ \Delta v_j = -w_j \lambda \hat n \f$;
///   FOSSSim's \f$ \frac{2\frac{1+e}{2}(u_2-u_1)\cdot\hat n}{1 + m_1/m_2} \f$ times w_1 / w_1.
/// - particle-edge at parameter alpha: \f$ u_\alpha = (1-\alpha) u_2 + \alpha u_3 \f$,
///   \f$ \lambda = (1+e)\frac{(u_\alpha - u_1)\cdot\hat n}{w_1 + (1-\alpha)^2 w_2 + \alpha^2 w_3}
///   \f$, \f$ \Delta v_1 = w_1\lambda\hat n \f$, \f$ \Delta v_2 = -(1-\alpha) w_2 \lambda\hat n
///   \f$, \f$ \Delta v_3 = -\alpha w_3\lambda\hat n \f$: linear momentum is conserved, and angular
///   momentum too (the impulses act along n^ through the contact point).
/// - particle-plane: \f$ \Delta v = -(1+e)(u\cdot\hat n)\hat n \f$ (the plane does not move).
/// The relative normal velocity after the impulse is -e times the one before.
/// The responses add dt Delta v to the positions too where FOSSSim does (continuous time,
/// hybrid: as if the impulse had acted at the start of the step).

#include <Eigen/Core>

#include "massspring/types.hpp"

namespace massspring::contact {

/// @brief Where an impulse goes: velocities, and (when `x` is not null) positions moved by
/// dt Delta v.
template <class Scalar>
struct ImpulseTarget {
  Points<Scalar>& v;
  Points<Scalar>* x = nullptr;
  Scalar dt = 0;
  void add(int i, const Vector3<Scalar>& dv) const {
    v.row(i) += dv.transpose();
    if (x) x->row(i) += (dt * dv).transpose();
  }
};

/// @brief Particle-particle impulse. @param[in] n_hat unit normal from i towards j;
/// @param[in] ui, uj velocities read [m/s]; @param[in] wi, wj inverse masses [1/kg] (0: fixed).
template <class Scalar>
void point_point_impulse(const ImpulseTarget<Scalar>& t, int i, int j, const Vector3<Scalar>& n_hat,
                         const Vector3<Scalar>& ui, const Vector3<Scalar>& uj, Scalar wi, Scalar wj,
                         Scalar cor) {
  const Scalar w = wi + wj;
  if (!(w > 0)) return;
  const Scalar lambda = (1 + cor) * (uj - ui).dot(n_hat) / w;
  if (wi > 0) t.add(i, (wi * lambda) * n_hat);
  if (wj > 0) t.add(j, (-wj * lambda) * n_hat);
}

/// @brief Particle-edge impulse: particle p, edge (a, b), contact at parameter alpha in [0, 1].
/// @param[in] n_hat unit normal from the particle towards the edge
template <class Scalar>
void point_edge_impulse(const ImpulseTarget<Scalar>& t, int p, int a, int b, Scalar alpha,
                        const Vector3<Scalar>& n_hat, const Vector3<Scalar>& up,
                        const Vector3<Scalar>& ua, const Vector3<Scalar>& ub, Scalar wp, Scalar wa,
                        Scalar wb, Scalar cor) {
  const Scalar beta = 1 - alpha;
  const Scalar w = wp + beta * beta * wa + alpha * alpha * wb;
  if (!(w > 0)) return;
  const Vector3<Scalar> u_edge = ua + alpha * (ub - ua);
  const Scalar lambda = (1 + cor) * (u_edge - up).dot(n_hat) / w;
  if (wp > 0) t.add(p, (wp * lambda) * n_hat);
  if (wa > 0) t.add(a, (-beta * wa * lambda) * n_hat);
  if (wb > 0) t.add(b, (-alpha * wb * lambda) * n_hat);
}

/// @brief Particle-plane impulse. @param[in] n_hat unit normal from the particle towards the
/// plane.
template <class Scalar>
void point_plane_impulse(const ImpulseTarget<Scalar>& t, int p, const Vector3<Scalar>& n_hat,
                         const Vector3<Scalar>& up, Scalar wp, Scalar cor) {
  if (!(wp > 0)) return;
  t.add(p, (-(1 + cor) * up.dot(n_hat)) * n_hat);
}

}  // namespace massspring::contact
