#pragma once
/// @file
/// @brief Springs (Hooke) and SpringDamping (along the spring axis): the force terms of a system's
/// own springs. Integrators apply them to every system; they read the springs, stiffness k_e, rest
/// lengths l0_e and damping b_e from the ForceContext.
///
/// With d = x_j - x_i, l = |d| and n = d / l for spring e = (i, j):
/// - Hooke: E = k/2 (l - l0)^2, F_i = k (l - l0) n, F_j = -F_i;
///   dF_i/dx_j = k [n n^T + (l - l0)/l (I - n n^T)] =: K, dF_i/dx_i = -K.
/// - damping: F_i = -b ((v_i - v_j) . n) n, F_j = -F_i; dF_i/dv_i = -b n n^T, dF_i/dv_j = b n n^T;
///   dF_i/dx_j = -(b/l) [n u^T P + (u . n) P] with u = v_i - v_j, P = I - n n^T (not symmetric).

#include <Eigen/Core>
#include <cmath>

#include "massspring/forces/force_term.hpp"
#include "massspring/types.hpp"

namespace massspring {

namespace detail {
/// @brief d = x_j - x_i, l = |d|, n = d / l (n = 0 when l = 0) of spring e.
template <class Scalar>
struct SpringFrame {
  Vector3<Scalar> d, n;
  Scalar l;
  SpringFrame(const Points<Scalar>& x, int i, int j) {
    d = (x.row(j) - x.row(i)).transpose();
    l = d.norm();
    n = l > 0 ? Vector3<Scalar>(d / l) : Vector3<Scalar>::Zero();
  }
};

/// @brief Adds the four blocks [-B, B; B, -B] of a pair (i, j) whose force on i has derivative B
/// with respect to x_j (and -B with respect to x_i).
template <class Scalar, class Block>
void add_pair_blocks(JacobianSink<Scalar>& j, int a, int b, const Block& block) {
  j.add_block(a, a, -block);
  j.add_block(a, b, block);
  j.add_block(b, a, block);
  j.add_block(b, b, -block);
}
}  // namespace detail

/// @brief Hooke springs: per spring stiffness k [N/m] and rest length l0 [m].
template <class Scalar>
struct Springs {
  static constexpr bool velocity_dependent = false;
  [[nodiscard]] const char* name() const { return "springs"; }

  void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const {
    // Raw pointers: the compiler cannot prove that writes to f leave the model alone, and would
    // reload every member of the context per spring.
    const int m = int(c.springs.rows());
    const int* ends = c.springs.data();
    const Scalar* k = c.stiffness.data();
    const Scalar* l0 = c.rest_lengths.data();
    const Scalar* x = c.x.data();
    Scalar* out = f.data();
    for (int e = 0; e < m; ++e) {
      const int i = 3 * ends[2 * e], j = 3 * ends[2 * e + 1];
      const Scalar d0 = x[j] - x[i], d1 = x[j + 1] - x[i + 1], d2 = x[j + 2] - x[i + 2];
      const Scalar l = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
      // k (l - l0) n = k (l - l0) / l d; at l = 0, d = 0 and so is the force (for l0 = 0 it is
      // k d, continuous through l = 0).
      const Scalar s = l > 0 ? k[e] * (l - l0[e]) / l : Scalar(0);
      out[i] += s * d0;
      out[i + 1] += s * d1;
      out[i + 2] += s * d2;
      out[j] -= s * d0;
      out[j + 1] -= s * d1;
      out[j + 2] -= s * d2;
    }
  }
  [[nodiscard]] Scalar energy(const ForceContext<Scalar>& c) const {
    Scalar sum = 0;
    for (int e = 0; e < int(c.springs.rows()); ++e) {
      const Scalar l = (c.x.row(c.springs(e, 1)) - c.x.row(c.springs(e, 0))).norm();
      const Scalar s = l - c.rest_lengths(e);
      sum += Scalar(0.5) * c.stiffness(e) * s * s;
    }
    return sum;
  }
  void add_dfdx(const ForceContext<Scalar>& c, JacobianSink<Scalar>& jac) const {
    using M3 = Eigen::Matrix<Scalar, 3, 3>;
    for (int e = 0; e < int(c.springs.rows()); ++e) {
      const int i = c.springs(e, 0), j = c.springs(e, 1);
      const Scalar k = c.stiffness(e), l0 = c.rest_lengths(e);
      const detail::SpringFrame<Scalar> s(c.x, i, j);
      M3 block;
      if (l0 == 0) {
        block = k * M3::Identity();  // F_i = k d: linear, smooth through l = 0
      } else if (s.l == 0) {
        block.setZero();  // direction undefined: no stiffness until the points separate
      } else {
        const M3 nn = s.n * s.n.transpose();
        Scalar t = (s.l - l0) / s.l;
        if (c.definite && t < 0) t = 0;
        block = k * (nn + t * (M3::Identity() - nn));
      }
      detail::add_pair_blocks(jac, i, j, block);
    }
  }
};

/// @brief Damping along each spring's axis: per spring b [N s/m]. No energy.
template <class Scalar>
struct SpringDamping {
  static constexpr bool velocity_dependent = true;
  static constexpr bool symmetric = false;  // dF/dx is not symmetric off the spring's line
  [[nodiscard]] const char* name() const { return "spring damping"; }

  void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const {
    for (int e = 0; e < int(c.springs.rows()); ++e) {
      const Scalar b = c.damping(e);
      if (b == 0) continue;
      const int i = c.springs(e, 0), j = c.springs(e, 1);
      const detail::SpringFrame<Scalar> s(c.x, i, j);
      const Vector3<Scalar> u = (c.v.row(i) - c.v.row(j)).transpose();
      const Vector3<Scalar> fi = -b * u.dot(s.n) * s.n;
      f.row(i) += fi.transpose();
      f.row(j) -= fi.transpose();
    }
  }
  void add_dfdv(const ForceContext<Scalar>& c, JacobianSink<Scalar>& jac) const {
    for (int e = 0; e < int(c.springs.rows()); ++e) {
      const int i = c.springs(e, 0), j = c.springs(e, 1);
      const detail::SpringFrame<Scalar> s(c.x, i, j);
      // dF_i/dv_j = +b n n^T, dF_i/dv_i = -b n n^T: the same shape as a position pair.
      detail::add_pair_blocks(jac, i, j,
                              Eigen::Matrix<Scalar, 3, 3>(c.damping(e) * s.n * s.n.transpose()));
    }
  }
  void add_dfdx(const ForceContext<Scalar>& c, JacobianSink<Scalar>& jac) const {
    using M3 = Eigen::Matrix<Scalar, 3, 3>;
    for (int e = 0; e < int(c.springs.rows()); ++e) {
      const int i = c.springs(e, 0), j = c.springs(e, 1);
      const detail::SpringFrame<Scalar> s(c.x, i, j);
      M3 block = M3::Zero();
      const Scalar b = c.damping(e);
      if (b != 0 && s.l > 0 && !c.definite) {
        const Vector3<Scalar> u = (c.v.row(i) - c.v.row(j)).transpose();
        const M3 p = M3::Identity() - s.n * s.n.transpose();
        block = -(b / s.l) * (s.n * (u.transpose() * p) + u.dot(s.n) * p);
      }
      detail::add_pair_blocks(jac, i, j, block);
    }
  }
};

}  // namespace massspring
