#pragma once
/// @file
/// @brief Gravity (an acceleration, F_i = m_i g) and ConstantForce (the same force on every point,
/// the JSON+OBJ scenes' convention).

#include <Eigen/Core>

#include "massspring/detail/validate.hpp"
#include "massspring/forces/force_term.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Uniform gravity: F_i = m_i g, E = -sum_i m_i g . x_i. g is an acceleration [m/s^2],
/// e.g. (0, -9.81, 0). Its Jacobians are zero.
template <class Scalar>
struct Gravity {
  Vector3<Scalar> g = Vector3<Scalar>::Zero();

  Gravity() = default;
  /// @param[in] acceleration [m/s^2], finite.
  explicit Gravity(const Vector3<Scalar>& acceleration) : g(acceleration) {
    if (!g.allFinite())
      throw Error(
          detail::message("gravity: acceleration must be finite, got ", detail::format_row(g)));
  }

  static constexpr bool constant = true;
  static constexpr bool velocity_dependent = false;
  [[nodiscard]] const char* name() const { return "gravity"; }

  void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const {
    f.noalias() += c.masses * g.transpose();
  }
  [[nodiscard]] Scalar energy(const ForceContext<Scalar>& c) const {
    Scalar e = 0;  // a loop: the product form would allocate a temporary
    for (Eigen::Index i = 0; i < c.x.rows(); ++i) e -= c.masses(i) * c.x.row(i).dot(g.transpose());
    return e;
  }
};

/// @brief The same force on every point, whatever its mass: F_i = f, E = -sum_i f . x_i [N].
/// The JSON+OBJ scenes use (0, -9.8, 0). Its Jacobians are zero.
template <class Scalar>
struct ConstantForce {
  Vector3<Scalar> force = Vector3<Scalar>::Zero();

  ConstantForce() = default;
  /// @param[in] f force on each point [N], finite.
  explicit ConstantForce(const Vector3<Scalar>& f) : force(f) {
    if (!force.allFinite())
      throw Error(
          detail::message("constant force: must be finite, got ", detail::format_row(force)));
  }

  static constexpr bool constant = true;
  static constexpr bool velocity_dependent = false;
  [[nodiscard]] const char* name() const { return "constant force"; }

  void add_force(const ForceContext<Scalar>&, Points<Scalar>& f) const {
    f.rowwise() += force.transpose();
  }
  [[nodiscard]] Scalar energy(const ForceContext<Scalar>& c) const { return -(c.x * force).sum(); }
};

}  // namespace massspring
