#pragma once
/// @file
/// @brief LinearDrag: F_i = -beta v_i, the same coefficient for every point (not scaled by mass).

#include "massspring/detail/validate.hpp"
#include "massspring/forces/force_term.hpp"
#include "massspring/types.hpp"

namespace massspring {

/// @brief Linear drag F_i = -beta v_i [N], beta in N s/m (>= 0). No energy; dF/dv = -beta I.
/// FastMassSpring folds it into its system matrix exactly (a term beta/(2 dt) |X - X^t|^2).
template <class Scalar>
struct LinearDrag {
  Scalar beta = 0;

  LinearDrag() = default;
  /// @param[in] coefficient beta [N s/m], finite and >= 0.
  explicit LinearDrag(Scalar coefficient) : beta(coefficient) {
    detail::require_number("linear drag", "beta", double(beta), false);
  }

  static constexpr bool velocity_dependent = true;
  [[nodiscard]] const char* name() const { return "linear drag"; }
  /// @brief beta: the term declares F = -beta v with dF/dv = -beta I (see force_term.hpp).
  [[nodiscard]] Scalar linear_damping() const { return beta; }
  /// @brief beta (the older name of linear_damping()).
  [[nodiscard]] Scalar drag_coefficient() const { return beta; }

  void add_force(const ForceContext<Scalar>& c, Points<Scalar>& f) const { f -= beta * c.v; }
  void add_dfdv(const ForceContext<Scalar>& c, JacobianSink<Scalar>& j) const {
    for (int i = 0; i < int(c.x.rows()); ++i) j.add_diagonal(i, -beta);
  }
};

}  // namespace massspring
